//! The flexible beam against closed forms: the seed's classic pitfall (an axial thrust
//! shortens the beam by a series that converges slowly in the lengthening modes), the
//! cantilever's bending eigenfrequencies, its tip deflection under a transverse load.

#[path = "support/analytic.rs"]
mod analytic;
#[path = "../examples/flexible_beam.rs"]
#[allow(dead_code)]
mod beam_example;
use analytic::elliptic_k;
use beam_example::{cantilever, frequencies, natural_frequencies, poles, settled_end};
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
    let k = elliptic_k(0.5f64.sqrt());
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

/// Root `n` (from 1) of `tan b = tanh b` (the pinned-free beam's `beta_n l`), by Newton
/// from `(n + 1/4) pi`.
fn pinned_free_root(n: usize) -> f64 {
    let mut b = (n as f64 + 0.25) * std::f64::consts::PI;
    for _ in 0..50 {
        // f = sin b cosh b - cos b sinh b.
        let f = b.sin() * b.cosh() - b.cos() * b.sinh();
        let df = 2.0 * b.sin() * b.sinh();
        b -= f / df;
    }
    b
}

#[test]
fn a_hinged_beam_vibrates_at_the_pinned_free_frequencies() {
    use multibody::joints::Revolute;
    use multibody::prelude::*;
    use multibody::world::World;
    // The rigid rotation on the hinge and the clamped-free modes of the tangent frame
    // together make a pinned-free beam: its frequencies beta_n^2 sqrt(EI / (rho A)) with
    // tan(beta l) = tanh(beta l) (3.9266, 7.0686, ...), approached from above as modes
    // are added (Rayleigh-Ritz, from above but for the sections' rotary inertia).
    let mut previous = f64::INFINITY;
    for n in [2, 4, 8] {
        let beam = FlexibleBeam {
            n_bending_xy: n,
            n_bending_xz: 0,
            damping: 0.0,
            // A slender rod: the rigid rotation carries its sections' rotary inertia,
            // the modes do not (no Rayleigh beam); 1 mm thin, it shifts the frequencies
            // by less than 1e-6.
            cross_section: multibody::parts::CrossSection::Circle { diameter: 0.001 },
            ..FlexibleBeam::default()
        };
        let (a, _, i_z) = section_properties(beam.cross_section);
        let scale = (beam.E * i_z / (beam.rho * a * beam.l.powi(4))).sqrt();
        let model: System = system! {
            name: "hinged_beam";
            world = World { g: 0.0, ..Default::default() };
            hinge = Revolute::default();
            beam = beam;
            connect(world.frame_b, hinge.frame_a);
            connect(hinge.frame_b, beam.frame_a);
        }
        .into();
        let w = natural_frequencies(&model).unwrap();
        let errors: Vec<f64> = (1..=2)
            .map(|k| w[k - 1] / (pinned_free_root(k).powi(2) * scale) - 1.0)
            .collect();
        assert!(errors.iter().all(|e| *e > -1e-6), "{n} modes: {errors:?}");
        assert!(errors[0] < previous, "{n} modes: {errors:?}");
        previous = errors[0];
        if n == 8 {
            assert!(errors[0] < 1e-5 && errors[1] < 2e-5, "{errors:?}");
        }
    }
}

#[test]
fn a_spinning_cantilever_is_stiffened_by_southwell_s_coefficients() {
    use multibody::blocks::Constant;
    use multibody::joints::Revolute;
    use multibody::prelude::*;
    use multibody::rotational::Speed;
    use multibody::world::World;
    // A cantilever spun about z at its root at a slow speed W: its flapping (xz) modes
    // at w^2 = w_0^2 + K W^2, its lead-lag (xy) modes at w^2 = w_0^2 + (K - 1) W^2, with
    // Southwell's coefficients K = 1.1933 and 6.4782 for the first two modes (Wright et
    // al. 1982). Without geometric stiffening the flapping modes do not stiffen.
    let beam = FlexibleBeam {
        cross_section: multibody::parts::CrossSection::Rectangle {
            width: 0.02,
            height: 0.03,
        },
        n_bending_xy: 5,
        n_bending_xz: 5,
        damping: 0.0,
        ..FlexibleBeam::default()
    };
    let (a, i_y, i_z) = section_properties(beam.cross_section);
    let (e, rho, l) = (beam.E, beam.rho, beam.l);
    let base =
        |i: f64, n: usize| clamped_free_root(n).powi(2) * (e * i / (rho * a * l.powi(4))).sqrt();
    let spin = 0.05 * base(i_z, 1);
    let spun = |beam: FlexibleBeam| -> System {
        system! {
            name: "spun_beam";
            world = World { g: 0.0, ..Default::default() };
            hinge = Revolute { axisflange: true, ..Default::default() };
            motor = Speed { exact: true, ..Default::default() };
            speed = Constant { k: spin };
            beam = beam;
            connect(world.frame_b, hinge.frame_a);
            connect(speed.y, motor.w_ref);
            connect(motor.flange, hinge.axis);
            connect(hinge.frame_b, beam.frame_a);
        }
        .into()
    };
    let w = natural_frequencies(&spun(beam.clone())).unwrap();
    for (n, southwell) in [(1, 1.1933), (2, 6.4782)] {
        let flap0 = base(i_y, n);
        let flap = nearest(&w, flap0);
        let k = (flap * flap - flap0 * flap0) / (spin * spin);
        assert!(
            (k - southwell).abs() < 1e-4 * southwell,
            "flapping {n}: {k}"
        );
        let lag0 = base(i_z, n);
        let lag = nearest(&w, lag0);
        let k = (lag * lag - lag0 * lag0) / (spin * spin);
        assert!(
            (k - (southwell - 1.0)).abs() < 1e-4 * southwell,
            "lead-lag {n}: {k}"
        );
    }
    let w = natural_frequencies(&spun(FlexibleBeam {
        geometric_stiffening: false,
        ..beam
    }))
    .unwrap();
    let flap0 = base(i_y, 1);
    let flap = nearest(&w, flap0);
    assert!((flap - flap0).abs() < 1e-9 * flap0, "{flap} vs {flap0}");
}

#[test]
fn a_tumbling_beam_keeps_its_energy_while_it_deforms() {
    use multibody::parts::Body;
    use multibody::prelude::*;
    use multibody::world::World;
    // A free beam between a hub and a tip body (both with inertia: the end's torque
    // works on the modes), without gravity, started spinning about all three axes and
    // bent: energy moves between
    // the rigid motion and the modes (in all four families; the I-profile's unequal
    // second moments couple its twist to the rotation) and the total stays.
    // Geometric stiffening is off: it is an approximation of the strain, not energy
    // consistent with the inertia.
    let model: System = system! {
        name: "tumbling_beam";
        world = World { g: 0.0, ..Default::default() };
        hub = Body { m: 2.0, I_11: 0.02, I_22: 0.03, I_33: 0.04, w_0_start: [1.0, 3.0, 2.0] };
        beam = FlexibleBeam {
            n_lengthening: 2,
            n_bending_xy: 3,
            n_bending_xz: 3,
            n_torsion: 2,
            damping: 0.0,
            geometric_stiffening: false,
            E: 2.1e9,
            ..FlexibleBeam::default()
        };
        tip = Body { m: 0.5, I_11: 1e-3, I_22: 2e-3, I_33: 3e-3 };
        connect(hub.frame_a, beam.frame_a);
        connect(beam.frame_b, tip.frame_a);
    }
    .into();
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(
        &ssys,
        &[
            ("beam.q.x[3]", 0.02),
            ("beam.q.x[6]", -0.01),
            ("beam.q.x[4]", 0.003),
            ("beam.q.x[9]", 0.05),
            ("beam.q.x[1]", 1e-4),
        ],
        (0.0, 2.0),
    )
    .unwrap()
    .solve(&SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    })
    .unwrap();
    let v = |name: &str, t: f64| sol.at(name, t).unwrap();
    let sq = |name: &str, t: f64| {
        (1..=3)
            .map(|i| v(&format!("{name}[{i}]"), t).powi(2))
            .sum::<f64>()
    };
    let energy = |t: f64| {
        let hub_rotation = 0.02 * v("hub.w_a[1]", t).powi(2)
            + 0.03 * v("hub.w_a[2]", t).powi(2)
            + 0.04 * v("hub.w_a[3]", t).powi(2);
        let tip_rotation = 1e-3 * v("tip.w_a[1]", t).powi(2)
            + 2e-3 * v("tip.w_a[2]", t).powi(2)
            + 3e-3 * v("tip.w_a[3]", t).powi(2);
        let rigid = 0.5 * 2.0 * sq("hub.v_0", t)
            + 0.5 * hub_rotation
            + 0.5 * 0.5 * sq("tip.v_0", t)
            + 0.5 * tip_rotation;
        (
            rigid + v("beam.kinetic_energy", t),
            v("beam.elastic_energy", t),
        )
    };
    let (kinetic0, elastic0) = energy(0.0);
    let total0 = kinetic0 + elastic0;
    let (mut low, mut high) = (f64::INFINITY, 0.0f64);
    for k in 0..=200 {
        let (kinetic, elastic) = energy(0.01 * k as f64);
        low = low.min(elastic);
        high = high.max(elastic);
        let total = kinetic + elastic;
        assert!(
            (total - total0).abs() < 1e-6 * total0,
            "t = {}: {total} vs {total0}",
            0.01 * k as f64
        );
    }
    // The exchange is large: the elastic energy swings by a tenth of the total.
    assert!(high - low > 0.1 * total0, "{low} .. {high} of {total0}");
    // The beam deforms noticeably: its end moves by more than 1 % of its length.
    let bent = (0..=200)
        .map(|k| sq("beam.u_b", 0.01 * k as f64).sqrt())
        .fold(0.0f64, f64::max);
    assert!(bent > 0.0158, "{bent}");
}

#[test]
fn a_shaft_twists_at_the_closed_form_torsion_frequencies() {
    use multibody::joints::Revolute;
    use multibody::prelude::*;
    use multibody::world::World;
    // A circular shaft (J_t = I_p): clamped-free at (2n - 1) pi / (2 l) sqrt(G / rho),
    // exactly (the modes are the eigenfunctions); free to turn about x on a hinge at
    // frame_a, free-free at n pi / l sqrt(G / rho), approached from above.
    let shaft = FlexibleBeam {
        cross_section: multibody::parts::CrossSection::Circle { diameter: 0.02 },
        n_bending_xy: 0,
        n_bending_xz: 0,
        n_torsion: 3,
        damping: 0.0,
        ..FlexibleBeam::default()
    };
    let wave = (shaft.E / (2.0 * (1.0 + shaft.nu)) / shaft.rho).sqrt() / shaft.l;
    let pi = std::f64::consts::PI;
    let w = frequencies(shaft.clone()).unwrap();
    assert_eq!(w.len(), 3, "{w:?}");
    for (n, got) in w.iter().enumerate() {
        let exact = (2 * n + 1) as f64 * pi / 2.0 * wave;
        assert!((got - exact).abs() < 1e-6 * exact, "{got} vs {exact}");
    }
    let mut previous = f64::INFINITY;
    for n in [1, 3, 9] {
        let model: System = system! {
            name: "free_shaft";
            world = World { g: 0.0, ..Default::default() };
            hinge = Revolute { n: [1.0, 0.0, 0.0], ..Default::default() };
            shaft = FlexibleBeam { n_torsion: n, ..shaft.clone() };
            connect(world.frame_b, hinge.frame_a);
            connect(hinge.frame_b, shaft.frame_a);
        }
        .into();
        let w = natural_frequencies(&model).unwrap();
        let error = w[0] / (pi * wave) - 1.0;
        assert!(error > 0.0 && error < previous, "{n} modes: {error}");
        previous = error;
    }
    assert!(previous < 2e-4, "{previous}");
}

/// The largest real part of the poles of `model` linearized at its start \[1/s\]:
/// positive where it is unstable.
fn largest_real_part(model: &multibody::prelude::System) -> f64 {
    poles(model)
        .unwrap()
        .iter()
        .map(|p| p.value.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The frequency of `w` nearest `target`.
fn nearest(w: &[f64], target: f64) -> f64 {
    *w.iter()
        .min_by(|x, y| (*x - target).abs().total_cmp(&(*y - target).abs()))
        .unwrap()
}

#[test]
fn an_axial_thrust_buckles_the_cantilever_at_euler_s_load() {
    // Geometric stiffening by the end's axial force: a cantilever under a dead axial
    // thrust P is stable below Euler's load pi^2 E I / (4 l^2) and unstable above it
    // (1 % either side; Rayleigh-Ritz puts the modes' critical load just above).
    let beam = FlexibleBeam {
        n_bending_xy: 5,
        n_bending_xz: 0,
        ..FlexibleBeam::default()
    };
    let (_, _, i_z) = section_properties(beam.cross_section);
    let euler = std::f64::consts::PI.powi(2) * beam.E * i_z / (4.0 * beam.l * beam.l);
    let below = largest_real_part(&cantilever(beam.clone(), [-0.99 * euler, 0.0, 0.0]));
    assert!(below < 0.0, "{below}");
    let above = largest_real_part(&cantilever(beam.clone(), [-1.01 * euler, 0.0, 0.0]));
    assert!(above > 0.0, "{above}");
    // A pull does not buckle it.
    let pulled = largest_real_part(&cantilever(beam, [10.0 * euler, 0.0, 0.0]));
    assert!(pulled < 0.0, "{pulled}");
}

#[test]
fn a_column_buckles_under_its_own_weight_at_greenhill_s_length() {
    use multibody::prelude::*;
    use multibody::world::World;
    // Geometric stiffening by the axial acceleration: a column clamped at its foot
    // (gravity along -x, the beam along +x) buckles under its own weight where
    // rho A g l^3 / (E I) = 7.837 (Greenhill), here by lowering E; 1 % either side.
    let column = |scale: f64| -> System {
        let beam = FlexibleBeam {
            n_bending_xy: 5,
            n_bending_xz: 0,
            ..FlexibleBeam::default()
        };
        let (a, _, i_z) = section_properties(beam.cross_section);
        let critical = beam.rho * a * 9.80665 * beam.l.powi(3) / (7.837 * i_z);
        let beam = FlexibleBeam {
            E: scale * critical,
            ..beam
        };
        system! {
            name: "column";
            world = World { n: [-1.0, 0.0, 0.0], ..Default::default() };
            beam = beam;
            connect(world.frame_b, beam.frame_a);
        }
        .into()
    };
    let stiff = largest_real_part(&column(1.01));
    assert!(stiff < 0.0, "{stiff}");
    let soft = largest_real_part(&column(0.99));
    assert!(soft > 0.0, "{soft}");
}

#[test]
fn a_spinning_flat_bar_twists_towards_its_larger_inertia() {
    use multibody::blocks::Constant;
    use multibody::joints::Revolute;
    use multibody::prelude::*;
    use multibody::rotational::Speed;
    use multibody::world::World;
    // A flat bar (5 x 20 mm, so I_z > I_y) spun steadily at W about (0, 1, 1)/sqrt(2),
    // across its axis: each section needs the torque w x (J w) about x, which the
    // twist's elastic torque G J_t theta' gives: theta'' = rho (I_z - I_y) w_y w_z /
    // (G J_t) with theta(0) = 0, theta'(l) = 0, so the end turns by
    // rho (I_y - I_z) w_y w_z l^2 / (2 G J_t) (negative here: towards z, the larger
    // inertia). The sine modes give the closed form times
    // 32 / pi^3 sum (-1)^(i+1) / (2i - 1)^3.
    let spin = 10.0;
    let bar = FlexibleBeam {
        l: 1.0,
        cross_section: multibody::parts::CrossSection::Rectangle {
            width: 0.02,
            height: 0.005,
        },
        n_bending_xy: 0,
        n_bending_xz: 0,
        n_torsion: 5,
        damping: 1.0,
        ..FlexibleBeam::default()
    };
    let model: System = system! {
        name: "spun_bar";
        world = World { g: 0.0, ..Default::default() };
        hinge = Revolute { n: [0.0, 1.0, 1.0], axisflange: true, ..Default::default() };
        motor = Speed { exact: true, ..Default::default() };
        speed = Constant { k: spin };
        bar = bar.clone();
        connect(world.frame_b, hinge.frame_a);
        connect(speed.y, motor.w_ref);
        connect(motor.flange, hinge.axis);
        connect(hinge.frame_b, bar.frame_a);
    }
    .into();
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.5))
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-10,
            atol: 1e-14,
            ..SolverOptions::default()
        })
        .unwrap();
    let twist: f64 = (1..=5)
        .map(|i| {
            let q = sol.final_value(format!("bar.q.x[{i}]").as_str()).unwrap();
            if i % 2 == 1 { q } else { -q }
        })
        .sum();
    let (_, i_y, i_z) = section_properties(bar.cross_section);
    let shear = bar.E / (2.0 * (1.0 + bar.nu));
    let j_t = multibody::parts::torsion_constant(bar.cross_section);
    let w_yz = spin * spin / 2.0;
    let closed = bar.rho * (i_y - i_z) * w_yz * bar.l * bar.l / (2.0 * shear * j_t);
    assert!(closed < 0.0);
    let series: f64 = (1..=5)
        .map(|i| {
            let k = (2 * i - 1) as f64;
            let sign = if i % 2 == 1 { 1.0 } else { -1.0 };
            sign / k.powi(3)
        })
        .sum::<f64>()
        * 32.0
        / std::f64::consts::PI.powi(3);
    assert!(
        (twist - closed * series).abs() < 1e-6 * closed.abs(),
        "{twist} vs {}",
        closed * series
    );
    assert!((twist / closed - 1.0).abs() < 2e-3, "{twist} vs {closed}");
}
