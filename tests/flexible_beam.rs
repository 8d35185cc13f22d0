//! The flexible beam against closed forms: the seed's classic pitfall (an axial thrust
//! shortens the beam by a series that converges slowly in the lengthening modes), the
//! cantilever's bending eigenfrequencies, its tip deflection under a transverse load.

#[path = "../examples/flexible_beam.rs"]
#[allow(dead_code)]
mod beam_example;
use beam_example::{cantilever, frequencies, settled_end};
use multibody::parts::{FlexibleBeam, clamped_free_root, section_properties};

#[test]
fn an_axial_thrust_shortens_the_beam_as_the_modal_series_and_the_seed_say() {
    let beam = FlexibleBeam::default();
    let (a, _, _) = section_properties(beam.cross_section);
    let thrust = -1000.0;
    let spring = thrust * beam.l / (beam.E * a);
    // The seed's table: 19, 4, 2 and 1 % short of the equivalent spring.
    for (n, seed_error) in [(1, 0.19), (5, 0.04), (10, 0.02), (15, 0.01)] {
        let model = cantilever(
            FlexibleBeam {
                n_lengthening: n,
                n_bending_xy: 0,
                n_bending_xz: 0,
                damping: 1.0,
                ..FlexibleBeam::default()
            },
            [thrust, 0.0, 0.0],
        );
        let end = settled_end(&model, 0.05).unwrap();
        // Rayleigh-Ritz with the rod's modes sin((2i - 1) pi x / 2l): the end moves by
        // the spring's F l / (E A) times sum 8 / ((2i - 1)^2 pi^2).
        let series: f64 = (1..=n)
            .map(|i| 8.0 / ((2 * i - 1) as f64 * std::f64::consts::PI).powi(2))
            .sum();
        assert!(
            (end[0] - spring * series).abs() < 1e-6 * spring.abs(),
            "{n} modes: {} vs {}",
            end[0],
            spring * series
        );
        let error = 1.0 - end[0] / spring;
        assert!(
            (error - seed_error).abs() < 0.005,
            "{n} modes: error {error}"
        );
        assert!(end[1].abs() < 1e-15 && end[2].abs() < 1e-15, "{end:?}");
    }
}

#[test]
fn the_cantilever_has_the_closed_form_eigenfrequencies() {
    let beam = FlexibleBeam {
        n_bending_xz: 0,
        damping: 0.0,
        ..FlexibleBeam::default()
    };
    let (a, _, i_z) = section_properties(beam.cross_section);
    let scale = (beam.E * i_z / (beam.rho * a * beam.l.powi(4))).sqrt();
    let w = frequencies(beam).unwrap();
    assert_eq!(w.len(), 3, "{w:?}");
    // beta_n l of the textbook (Blevins): 1.87510407, 4.69409113, 7.85475744.
    for (got, bl) in w.iter().zip([1.875_104_07, 4.694_091_13, 7.854_757_44]) {
        let exact = bl * bl * scale;
        assert!((got - exact).abs() < 1e-6 * exact, "{got} vs {exact}");
    }
}

#[test]
fn a_transverse_load_bends_the_cantilever_as_euler_bernoulli_says() {
    let p = 10.0;
    for n in [1, 3] {
        let beam = FlexibleBeam {
            n_bending_xy: n,
            n_bending_xz: 0,
            damping: 1.0,
            ..FlexibleBeam::default()
        };
        let (_, _, i_z) = section_properties(beam.cross_section);
        let cubic = p * beam.l.powi(3) / (beam.E * i_z);
        let end = settled_end(&cantilever(beam, [0.0, p, 0.0]), 3.0).unwrap();
        // Rayleigh-Ritz with the cantilever's modes: sum 4 / (beta_i l)^4 of P l^3 / EI,
        // which tends to 1/3.
        let series: f64 = (1..=n).map(|i| 4.0 / clamped_free_root(i).powi(4)).sum();
        assert!(
            (end[1] - cubic * series).abs() < 1e-6 * cubic,
            "{n} modes: {} vs {}",
            end[1],
            cubic * series
        );
        let relative = end[1] / (cubic / 3.0) - 1.0;
        let bound = if n == 1 { 0.03 } else { 0.002 };
        assert!(relative.abs() < bound, "{n} modes: {relative}");
    }
}

#[test]
fn a_stiff_beam_swings_as_a_rigid_rod() {
    use multibody::joints::Revolute;
    use multibody::prelude::*;
    use multibody::world::World;
    // Very stiff (E x 1e4, modes critically damped): the floating frame's rigid motion
    // and its coupling to nearly rigid modes, a physical pendulum released horizontal:
    // it reaches the bottom after a quarter period sqrt(J / (m g d)) K(sin(pi/4)), with
    // J = m l^2 / 3 + rho I_z l about the hinge.
    let beam = FlexibleBeam {
        E: 2.1e15,
        n_bending_xy: 2,
        n_bending_xz: 0,
        damping: 1.0,
        ..FlexibleBeam::default()
    };
    let (a, _, i_z) = section_properties(beam.cross_section);
    let m = beam.rho * a * beam.l;
    let j = m * beam.l * beam.l / 3.0 + beam.rho * i_z * beam.l;
    let g = 9.80665;
    // K(1/sqrt(2)) by the arithmetic-geometric mean (a fixed number of rounds: it
    // converges quadratically).
    let (mut x, mut y) = (1.0f64, 0.5f64.sqrt());
    for _ in 0..40 {
        (x, y) = (0.5 * (x + y), (x * y).sqrt());
    }
    let k = std::f64::consts::PI / (2.0 * x);
    let quarter = (j / (m * g * beam.l / 2.0)).sqrt() * k;
    let model: System = system! {
        name: "stiff_pendulum";
        world = World::default();
        hinge = Revolute::default();
        beam = beam;
        connect(world.frame_b, hinge.frame_a);
        connect(hinge.frame_b, beam.frame_a);
    }
    .into();
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(
        &ssys,
        &[("hinge.phi", 0.0), ("hinge.w", 0.0)],
        (0.0, quarter),
    )
    .unwrap()
    .solve(&SolverOptions {
        rtol: 1e-8,
        atol: 1e-10,
        ..SolverOptions::default()
    })
    .unwrap();
    let phi = sol.final_value("hinge.phi").unwrap();
    assert!(
        (phi + std::f64::consts::FRAC_PI_2).abs() < 1e-5,
        "phi at the quarter period: {phi}"
    );
    // The speed there from energy: J w^2 / 2 = m g l / 2.
    let w = sol.final_value("hinge.w").unwrap();
    let exact = (m * g * beam.l / j).sqrt();
    assert!((w.abs() - exact).abs() < 1e-5 * exact, "{w} vs {exact}");
}
