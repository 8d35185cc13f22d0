//! The classic cart-pole: a pendulum on a revolute joint on a cart that a force moves
//! along a prismatic joint, upright at `phi = 0` (`phi_offset` 90 deg), started at 5
//! deg. A state controller from the linear-quadratic regulator (started from a pole
//! placement) brings the pendulum upright and the cart back to its start.
//!
//! `cargo run --release --example cart_pole` writes `cart_pole.png` and `cart_pole.gif`.

use multibody::control::{lqr, place_poles};
use multibody::joints::{Prismatic, Revolute};
use multibody::nalgebra::{Complex, DMatrix, DVector};
use multibody::parts::Body;
use multibody::prelude::*;
use multibody::world::World;
use multibody::{LinearModel, linearize, rotational, translational};

component! {
    /// State feedback on the cart and the pendulum: the force
    /// `-(k_s s + k_v v + k_phi phi + k_w w) + u` on the cart.
    pub struct CartController {
        /// Gain on the cart position [N/m], default 0.
        parameter k_s: f64 = 0.0;
        /// Gain on the cart speed [N.s/m], default 0.
        parameter k_v: f64 = 0.0;
        /// Gain on the pendulum angle [N/rad], default 0.
        parameter k_phi: f64 = 0.0;
        /// Gain on the pendulum speed [N.s/rad], default 0.
        parameter k_w: f64 = 0.0;
        /// Force added [N] (the input of the linearization), default 0.
        parameter u: f64 = 0.0;
        /// The prismatic joint's axis.
        connector cart: translational::Flange;
        /// The revolute joint's axis (measured only).
        connector joint: rotational::Flange;
        /// The force on the cart [N].
        variable force: Real;
        equation {
            force = -(k_s * cart.s + k_v * der(cart.s) + k_phi * joint.phi + k_w * der(joint.phi)) + u;
            cart.f = -force;
            joint.tau = 0.0;
        }
    }
}

system! {
    /// The model: a 1 kg cart and a 0.5 kg pendulum of 0.5 m.
    pub fn cart_pole() -> CartPole {
        name: "cart_pole";
        world = World::default();
        slider = Prismatic { n: [1.0, 0.0, 0.0], axisflange: true };
        cart = Body { m: 1.0 };
        hinge = Revolute {
            n: [0.0, 0.0, 1.0],
            axisflange: true,
            phi_offset: std::f64::consts::FRAC_PI_2,
            phi_start: 5f64.to_radians(),
        };
        pole = Body { m: 0.5, r_CM: [0.5, 0.0, 0.0] };
        controller = CartController::default();
        connect(world.frame_b, slider.frame_a);
        connect(slider.frame_b, cart.frame_a);
        connect(slider.frame_b, hinge.frame_a);
        connect(hinge.frame_b, pole.frame_a);
        connect(controller.cart, slider.axis);
        connect(controller.joint, hinge.axis);
    }
}

/// The gains' parameter names in the order of the states `names`.
fn gain_names(states: &[String]) -> Vec<&'static str> {
    states
        .iter()
        .map(|s| match s.as_str() {
            "slider.s" => "controller.k_s",
            "slider.v" => "controller.k_v",
            "hinge.phi" => "controller.k_phi",
            _ => "controller.k_w",
        })
        .collect()
}

/// The cart-pole linearized upright at rest with the gains `k` (in the order of the
/// states), the force `controller.u` as input.
pub fn linearized(
    ssys: &SimplifiedSystem,
    k: &[(&str, f64)],
) -> Result<LinearModel, multibody::Error> {
    let mut values = vec![
        ("slider.s", 0.0),
        ("slider.v", 0.0),
        ("hinge.phi", 0.0),
        ("hinge.w", 0.0),
    ];
    values.extend_from_slice(k);
    let problem = DaeProblem::new(ssys, &values, (0.0, 1.0))?;
    linearize(
        ssys,
        &problem.operating_point(),
        &["controller.u"],
        &["slider.s", "hinge.phi"],
    )
}

/// The regulator's gains (parameter name, value): weights 10 on the cart position, 100
/// on the angle, 1 on the speeds, 0.1 on the force.
pub fn design(open: &LinearModel) -> Vec<(&'static str, f64)> {
    let b = DVector::from_column_slice(open.b.column(0).as_slice());
    let poles = [-2.0, -3.0, -4.0, -5.0].map(|p| Complex::new(p, 0.0));
    let k0 = place_poles(&open.a, &b, &poles).expect("controllable");
    let q: Vec<f64> = open
        .states
        .iter()
        .map(|s| match s.as_str() {
            "slider.s" => 10.0,
            "hinge.phi" => 100.0,
            _ => 1.0,
        })
        .collect();
    let (k, _) = lqr(
        &open.a,
        &open.b,
        &DMatrix::from_diagonal(&DVector::from_vec(q)),
        &DMatrix::from_element(1, 1, 0.1),
        Some(&DMatrix::from_row_slice(1, k0.len(), k0.as_slice())),
    )
    .expect("the regulator converges");
    gain_names(&open.states)
        .into_iter()
        .zip(k.iter().copied())
        .collect()
}

fn main() -> Result<(), multibody::Error> {
    let model = cart_pole();
    let ssys = structural_simplify(&model)?;
    let open = linearized(&ssys, &[])?;
    println!(
        "states {:?}, open-loop eigenvalues {:?}",
        open.states,
        open.eigenvalues()
    );
    let gains = design(&open);
    println!("LQR gains {gains:?}");
    let closed = linearized(&ssys, &gains)?;
    println!("closed-loop eigenvalues {:?}", closed.eigenvalues());
    let sol = DaeProblem::new(&ssys, &gains, (0.0, 8.0))?.solve(&SolverOptions::default())?;
    println!(
        "after 8 s: angle {:.2e} rad, cart {:.2e} m",
        sol.final_value("hinge.phi")?,
        sol.final_value("slider.s")?
    );
    Figure::new()
        .title("Cart-pole with a state controller (LQR)")
        .panel(&sol, &["hinge.phi"])
        .panel(&sol, &["slider.s"])
        .panel(&sol, &["controller.force"])
        .options(PlotOptions {
            columns: 3,
            ..PlotOptions::default()
        })
        .save("cart_pole.png")?;
    println!("wrote cart_pole.png");
    let options = RenderOptions {
        camera: [0.0, 0.5, 3.0],
        look_at: [0.0, 0.3, 0.0],
        times: Some((0..=80).map(|k| 0.1 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "cart_pole.gif", &options)?;
    println!("wrote cart_pole.gif");
    Ok(())
}
