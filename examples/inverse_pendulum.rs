//! The seed's inverse pendulum (`001`, Exercise 1): a box of 0.5 x 0.25 x 0.25 m on a
//! revolute joint driven through its axis flange, `phi_offset` 90 deg so that upright
//! is `phi = 0`, started at 5 deg. Linearized upright it has a real pair of
//! eigenvalues, one unstable; a PD controller on the angle with gains from pole
//! placement, then a state controller from the linear-quadratic regulator, bring it
//! upright and hold it.
//!
//! `cargo run --release --example inverse_pendulum` writes `inverse_pendulum.png` and
//! `inverse_pendulum.gif` (the LQR run), the
//! closed loop's poles (`inverse_pendulum_poles.png`) and its Bode diagram from the
//! torque input to the angle (`inverse_pendulum_bode.png`).

use multibody::blocks::{Add3, Constant, Gain};
use multibody::control::{lqr, place_poles};
use multibody::joints::Revolute;
use multibody::nalgebra::{Complex, DMatrix, DVector};
use multibody::parts::BodyBox;
use multibody::prelude::*;
use multibody::rotational::{AngleSensor, SpeedSensor, Torque};
use multibody::world::World;
use multibody::{LinearModel, linearize};

system! {
    /// The model: the torque on the axis is `-k_phi.k phi - k_w.k w + u.k`.
    pub fn inverse_pendulum() -> InversePendulum {
        name: "inverse_pendulum";
        world = World::default();
        rev = Revolute {
            n: [0.0, 0.0, 1.0],
            axisflange: true,
            phi_offset: std::f64::consts::FRAC_PI_2,
            phi_start: 5f64.to_radians(),
        };
        body = BodyBox { r: [0.5, 0.0, 0.0], width: Some(0.25), height: Some(0.25) };
        angle = AngleSensor::default();
        speed = SpeedSensor::default();
        k_phi = Gain { k: 0.0 };
        k_w = Gain { k: 0.0 };
        u = Constant { k: 0.0 };
        sum = Add3 { k1: -1.0, k2: -1.0, k3: 1.0 };
        torque = Torque::default();
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        connect(rev.axis, angle.flange);
        connect(rev.axis, speed.flange);
        connect(angle.phi, k_phi.u);
        connect(speed.w, k_w.u);
        connect(k_phi.y, sum.u1);
        connect(k_w.y, sum.u2);
        connect(u.y, sum.u3);
        connect(sum.y, torque.tau);
        connect(torque.flange, rev.axis);
    }
}

/// The pendulum linearized upright (`phi = 0`, at rest) with gains `(k_phi, k_w)`, the
/// torque `u.k` as input and the angle and torque as outputs.
pub fn linearized(
    ssys: &SimplifiedSystem,
    gains: (f64, f64),
) -> Result<LinearModel, multibody::Error> {
    let problem = DaeProblem::new(
        ssys,
        &[
            ("rev.phi", 0.0),
            ("rev.w", 0.0),
            ("k_phi.k", gains.0),
            ("k_w.k", gains.1),
        ],
        (0.0, 1.0),
    )?;
    linearize(
        ssys,
        &problem.operating_point(),
        &["u.k"],
        &["rev.phi", "torque.tau"],
    )
}

/// `(k_phi, k_w)` of the state gain row `k` (in the order of `lin.states`).
pub fn gains_of(lin: &LinearModel, k: &[f64]) -> (f64, f64) {
    let at = |name: &str| {
        lin.states
            .iter()
            .position(|s| s == name)
            .map_or(0.0, |i| k[i])
    };
    (at("rev.phi"), at("rev.w"))
}

/// PD gains that place the closed loop's poles at `poles`.
pub fn pd_gains(open: &LinearModel, poles: [f64; 2]) -> (f64, f64) {
    let b = DVector::from_column_slice(open.b.column(0).as_slice());
    let poles = poles.map(|p| Complex::new(p, 0.0));
    let k = place_poles(&open.a, &b, &poles).expect("controllable");
    gains_of(open, k.as_slice())
}

/// State-controller gains of the linear-quadratic regulator with weights `q` on the
/// states and `r` on the torque, started from `start` (stabilizing).
pub fn lqr_gains(open: &LinearModel, q: [f64; 2], r: f64, start: (f64, f64)) -> (f64, f64) {
    let order: Vec<f64> = open
        .states
        .iter()
        .map(|s| if s == "rev.phi" { q[0] } else { q[1] })
        .collect();
    let k0: Vec<f64> = open
        .states
        .iter()
        .map(|s| if s == "rev.phi" { start.0 } else { start.1 })
        .collect();
    let (k, _) = lqr(
        &open.a,
        &open.b,
        &DMatrix::from_diagonal(&DVector::from_vec(order)),
        &DMatrix::from_element(1, 1, r),
        Some(&DMatrix::from_row_slice(1, k0.len(), &k0)),
    )
    .expect("the regulator converges");
    gains_of(open, k.as_slice())
}

/// Simulates `t_end` seconds from 5 deg with gains `(k_phi, k_w)`.
pub fn simulate(
    ssys: &SimplifiedSystem,
    gains: (f64, f64),
    t_end: f64,
) -> Result<Solution, multibody::Error> {
    DaeProblem::new(
        ssys,
        &[("k_phi.k", gains.0), ("k_w.k", gains.1)],
        (0.0, t_end),
    )?
    .solve(&SolverOptions::default())
}

fn main() -> Result<(), multibody::Error> {
    let model = inverse_pendulum();
    let ssys = structural_simplify(&model)?;
    let open = linearized(&ssys, (0.0, 0.0))?;
    println!(
        "states {:?}, open-loop eigenvalues {:?}",
        open.states,
        open.eigenvalues()
    );
    let pd = pd_gains(&open, [-4.0, -6.0]);
    println!(
        "PD gains (poles -4, -6): k_phi = {:.3} N.m/rad, k_w = {:.3} N.m.s/rad",
        pd.0, pd.1
    );
    let state = lqr_gains(&open, [1e4, 1e2], 1e-2, pd);
    println!("LQR gains: k_phi = {:.3}, k_w = {:.3}", state.0, state.1);
    let closed = linearized(&ssys, state)?;
    println!("closed-loop eigenvalues (LQR): {:?}", closed.eigenvalues());
    multibody::plot::plot_poles(&closed, "inverse_pendulum_poles.png")?;
    multibody::plot::plot_bode(
        &closed,
        (0, 0),
        (0.1, 1000.0),
        300,
        "inverse_pendulum_bode.png",
    )?;
    println!("wrote inverse_pendulum_poles.png and inverse_pendulum_bode.png");
    let falling = simulate(&ssys, (0.0, 0.0), 0.8)?;
    let with_pd = simulate(&ssys, pd, 3.0)?;
    let with_lqr = simulate(&ssys, state, 3.0)?;
    println!(
        "phi after 3 s: PD {:.2e} rad, LQR {:.2e} rad",
        with_pd.final_value("rev.phi")?,
        with_lqr.final_value("rev.phi")?
    );
    Figure::new()
        .title("Inverse pendulum: open loop, PD, LQR")
        .panel(&falling, &["rev.phi"])
        .panel_title("open loop")
        .panel(&with_pd, &["rev.phi"])
        .panel_title("PD, poles -4 and -6")
        .panel(&with_lqr, &["rev.phi"])
        .panel_title("LQR")
        .panel(&with_pd, &["torque.tau"])
        .panel_title("PD torque")
        .panel(&with_lqr, &["torque.tau"])
        .panel_title("LQR torque")
        .options(PlotOptions {
            columns: 3,
            ..PlotOptions::default()
        })
        .save("inverse_pendulum.png")?;
    println!("wrote inverse_pendulum.png");
    let options = RenderOptions {
        camera: [0.6, 0.4, 2.0],
        look_at: [0.0, 0.25, 0.0],
        times: Some((0..=60).map(|k| 0.05 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &with_lqr, "inverse_pendulum.gif", &options)?;
    println!("wrote inverse_pendulum.gif");
    Ok(())
}
