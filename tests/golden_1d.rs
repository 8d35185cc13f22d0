//! Golden structure of the 1-D test models: the exact sizes that flattening, alias
//! elimination, index reduction, state selection, sorting and tearing must give, each
//! derived by hand from the component equations (see the comments) rather than copied
//! from a run.
//!
//! Counting rules used in the derivations (those of Modelica and of
//! `multibody-core/src/simplify/alias.rs`):
//! - a connection set of n connectors gives n - 1 potential equalities and one flow
//!   sum; an unconnected flow is zero (one equation); a signal connection is one
//!   equality;
//! - alias elimination removes one unknown per equation `a = ±b` or `a = expression of
//!   parameters` (tested on the equation as written, so `s = flange.s - L/2` with a
//!   tunable `L` is no alias, and a flow sum of three connectors is none either), and
//!   `der(x) = v` makes `v` the derivative of `x` (a "derivative alias");
//! - then, repeatedly, one more unknown per equation that the substitution of those
//!   turned into `a = expression of parameters` (a node potential `p.v = n.v + V` with
//!   `n` grounded, a flow sum whose other currents cancel);
//! - a torn linear block of n equations with k tearing variables leaves k residuals and
//!   counts its n - k other equations among the explicit assignments.

#[path = "../examples/dc_motor.rs"]
#[allow(dead_code)]
mod example;

#[path = "support/models_1d.rs"]
mod models_1d;

use multibody::Statistics;
use multibody::prelude::*;

/// Expected structure of a simplified model.
struct Golden<'a> {
    flat: usize,
    aliases: usize,
    derivative_aliases: usize,
    differentiated: usize,
    sorted: usize,
    states: &'a [&'a str],
    algebraic: usize,
    assignments: usize,
    diagonal: &'a [f64],
    linear_inline: &'a [(usize, usize)],
    nonlinear: &'a [(usize, usize)],
}

fn sizes(v: &[(usize, usize)], after: bool) -> String {
    if v.is_empty() {
        return "none".into();
    }
    let s: Vec<String> = v
        .iter()
        .map(|p| if after { p.1 } else { p.0 }.to_string())
        .collect();
    format!("{{{}}}", s.join(", "))
}

fn assert_golden(model: &impl AsRef<System>, g: &Golden) -> SimplifiedSystem {
    let ssys = structural_simplify(model).unwrap();
    let st: &Statistics = ssys.statistics();
    let name = ssys.name().to_string();
    assert_eq!(st.flat_equations, g.flat, "{name}: {st}");
    assert_eq!(st.flat_unknowns, g.flat, "{name}: {st}");
    assert_eq!(st.alias_variables, g.aliases, "{name}: {st}");
    assert_eq!(st.derivative_aliases, g.derivative_aliases, "{name}: {st}");
    assert_eq!(
        st.differentiated_equations, g.differentiated,
        "{name}: {st}"
    );
    // Dummy derivatives: one per differentiated equation (Mattsson-Soederlind: each
    // differentiated equation turns one derivative into an algebraic unknown).
    assert_eq!(st.dummy_derivatives, g.differentiated, "{name}: {st}");
    assert_eq!(st.sorted_equations, g.sorted, "{name}: {st}");
    assert_eq!(st.states, g.states.len(), "{name}: {st}");
    assert_eq!(st.algebraic, g.algebraic, "{name}: {st}");
    assert_eq!(st.assignments, g.assignments, "{name}: {st}");
    assert_eq!(st.linear_inline, g.linear_inline, "{name}: {st}");
    assert!(st.linear_sparse.is_empty(), "{name}: {st}");
    assert!(st.linear_solver.is_empty(), "{name}: {st}");
    assert_eq!(st.nonlinear, g.nonlinear, "{name}: {st}");
    assert_eq!(ssys.states(), g.states, "{name}");
    assert_eq!(
        ssys.unknowns().len(),
        g.states.len() + g.algebraic,
        "{name}"
    );
    assert_eq!(ssys.mass_matrix_diagonal(), g.diagonal, "{name}");
    assert_eq!(ssys.equations().len(), ssys.unknowns().len(), "{name}");
    // The report's lines.
    let report = st.to_string();
    for line in [
        format!(
            "flat model: {} scalar equations, {} scalar unknowns",
            g.flat, g.flat
        ),
        format!(
            "alias elimination: {} unknowns removed, {} derivative aliases",
            g.aliases, g.derivative_aliases
        ),
        format!(
            "index reduction: {} equations differentiated, {} dummy derivatives",
            g.differentiated, g.differentiated
        ),
        format!(
            "sorted system: {} equations; {} continuous states, {} algebraic unknowns, {} explicit assignments",
            g.sorted,
            g.states.len(),
            g.algebraic,
            g.assignments
        ),
        format!(
            "linear systems solved inside: sizes {} before and {} after tearing",
            sizes(g.linear_inline, false),
            sizes(g.linear_inline, true)
        ),
        "linear systems solved inside by sparse LU: sizes none before and none after pre-elimination"
            .to_string(),
        "linear systems left to the solver: sizes none".to_string(),
        format!(
            "nonlinear systems: sizes {} before and {} after tearing",
            sizes(g.nonlinear, false),
            sizes(g.nonlinear, true)
        ),
    ] {
        assert!(
            report.lines().any(|l| l.trim() == line),
            "{name}: no line `{line}` in\n{report}"
        );
    }
    ssys
}

#[test]
fn mass_spring_damper() {
    // Variables: fixed 2, spring 6, damper 8, mass 7 = 23. Equations: components
    // 1 + 4 + 6 + 5 = 16; sets {fixed, spring.a, damper.a} and {spring.b, mass.a,
    // damper.b}: 2 + 1 each; mass.flange_b.f = 0: 23.
    // Aliases: the fixed set is the constant s0 (3); the spring's and the damper's
    // forces (2 + 2); the second set's positions (2); mass.flange_b.f (1) = 10. The
    // mass's `flange_a.s = s - L/2` is no alias. Derivative aliases: damper v_rel, a_rel
    // and mass v, a = 4. Left: 9 equations.
    // damper.s_rel = spring.flange_b.s - s0 and spring.flange_b.s = mass.s - L/2 tie the
    // damper's relative position to the mass's: both equations differentiated twice
    // (accelerations) = 4 more, 13 sorted, 4 dummy derivatives. States: the damper's
    // preferred s_rel, v_rel; everything else explicit (13 assignments).
    let model = models_1d::mass_spring_damper(2.0, 50.0, 1.5);
    assert_golden(
        &model,
        &Golden {
            flat: 23,
            aliases: 10,
            derivative_aliases: 4,
            differentiated: 4,
            sorted: 13,
            states: &["damper.s_rel", "damper.v_rel"],
            algebraic: 0,
            assignments: 13,
            diagonal: &[1.0, 1.0],
            linear_inline: &[],
            nonlinear: &[],
        },
    );
}

#[test]
fn rc_circuit() {
    // Variables: three one-ports of 6 and the ground's 2 = 20. Equations: 4 + 4 + 4 + 1
    // and the sets {source.p, resistor.p}, {resistor.n, capacitor.p} (1 + 1 each) and
    // {capacitor.n, source.n, ground.p} (2 + 1) = 20.
    // Aliases: the nine currents are one set (each one-port's two, the two 2-pin flow
    // sums) = 8; potentials 1 + 1 + 3 (the ground set is the constant 0); source.v = V:
    // 14. Then source.p.v = V (source.n is grounded), and the ground current, whose set's
    // other currents are the loop current in and out: 16. `i = C der(v)` is no
    // derivative alias. Left: 4 equations in 4 unknowns with capacitor.v the state, no
    // index reduction, all explicit.
    let model = models_1d::rc_circuit();
    assert_golden(
        &model,
        &Golden {
            flat: 20,
            aliases: 16,
            derivative_aliases: 0,
            differentiated: 0,
            sorted: 4,
            states: &["capacitor.v"],
            algebraic: 0,
            assignments: 4,
            diagonal: &[1.0],
            linear_inline: &[],
            nonlinear: &[],
        },
    );
}

#[test]
fn two_inertias_with_a_spring_damper() {
    // Variables 7 + 8 + 7 = 22; equations 5 + 6 + 5, two 2-connector sets (1 + 1 each),
    // two unconnected flanges: 22.
    // Aliases: each inertia's angle set with the coupling's flange angle (3 + 3), the
    // torque set {coupling.tau, its flange torques, the inertias' connected flange
    // torques} (4), the two free flange torques (2) = 12. Derivative aliases: w, a of
    // both inertias and w_rel, a_rel = 6. Left: 4 equations.
    // phi_rel = phi2 - phi1 relates three angles that all have derivatives: it is
    // differentiated twice (2 more, 6 sorted) and one angle and one speed become
    // dummies. States: the preferred relative pair and inertia1's angle and speed.
    let model = models_1d::two_inertias(1.0, 3.0, 20.0, 0.5);
    assert_golden(
        &model,
        &Golden {
            flat: 22,
            aliases: 12,
            derivative_aliases: 6,
            differentiated: 2,
            sorted: 6,
            states: &[
                "inertia1.phi",
                "coupling.phi_rel",
                "inertia1.w",
                "coupling.w_rel",
            ],
            algebraic: 0,
            assignments: 6,
            diagonal: &[1.0, 1.0, 1.0, 1.0],
            linear_inline: &[],
            nonlinear: &[],
        },
    );
}

#[test]
fn undamped_oscillator() {
    // Variables 2 + 6 + 7 = 15; equations 1 + 4 + 5, two sets (1 + 1 each), the free
    // flange: 15.
    // Aliases: the fixed angle and spring.flange_a.phi are the constant phi0 (2); the
    // torque set {fixed, spring.a, spring.tau, spring.b, inertia.a} (4); the inertia's
    // angle set with spring.flange_b.phi (3); inertia.flange_b.tau (1) = 10. Derivative
    // aliases w, a = 2. Left: 3 equations (phi_rel, the spring law, Newton), no index
    // reduction; states phi, w.
    let model = models_1d::undamped_oscillator(4.0);
    assert_golden(
        &model,
        &Golden {
            flat: 15,
            aliases: 10,
            derivative_aliases: 2,
            differentiated: 0,
            sorted: 3,
            states: &["inertia.phi", "inertia.w"],
            algebraic: 0,
            assignments: 3,
            diagonal: &[1.0, 1.0],
            linear_inline: &[],
            nonlinear: &[],
        },
    );
}

#[test]
fn resistor_bridge() {
    // Variables: seven one-ports of 6 and the ground's 2 = 44; equations 7 * 4 + 1 and
    // four node sets of 3, 4, 4, 4 connectors (2 + 1, 3 + 1, 3 + 1, 3 + 1) = 44.
    // Aliases: two currents per one-port (14; every node has three or more connectors,
    // so no flow sum is an alias), node potentials 2 + 3 + 3 and the grounded node 4,
    // source.v = V: 27; then the top node, source.p.v = V: 28. Left 16 equations, 16
    // unknowns besides the state c.v.
    // With c.v known, the node voltages, the five resistor voltages and currents and the
    // capacitor current form one linear block of 13 equations (the two KCLs of the
    // inner nodes, c.v = va - vb, two per resistor); knowing one node voltage gives
    // the rest in sequence, so one tearing variable. Outside: the source current, the
    // ground current, der(c.v) = 3 assignments, plus the 12 torn ones = 15.
    let model = models_1d::bridge();
    assert_golden(
        &model,
        &Golden {
            flat: 44,
            aliases: 28,
            derivative_aliases: 0,
            differentiated: 0,
            sorted: 16,
            states: &["c.v"],
            algebraic: 0,
            assignments: 15,
            diagonal: &[1.0],
            linear_inline: &[(13, 1)],
            nonlinear: &[],
        },
    );
}

#[test]
fn cubic_resistor_loop() {
    // Variables 4 * 6 + 2 = 26; equations 4 * 4 + 1 and sets {source.p, nonlinear.p}
    // (1 + 1), {nonlinear.n, load.p, c.p} (2 + 1), {load.n, source.n, c.n, ground.p}
    // (3 + 1) = 26.
    // Aliases: currents 8 within the one-ports plus the 2-pin flow sum (source and
    // cubic resistor carry one current) = 9; potentials 1 + 2 + 4 (grounded); source.v
    // = 17; then the top node, source.p.v = V: 18. Left 8 equations. With c.v known:
    // the middle node, the cubic resistor's voltage, then its current from
    // v = R0 i + a i^3, a nonlinear block of one equation whose one unknown is the
    // tearing variable and the only algebraic unknown; the other 7 are assignments.
    // Unknowns: [the current, c.v], diagonal [0, 1].
    let model = models_1d::cubic_loop();
    let ssys = assert_golden(
        &model,
        &Golden {
            flat: 26,
            aliases: 18,
            derivative_aliases: 0,
            differentiated: 0,
            sorted: 8,
            states: &["c.v"],
            algebraic: 1,
            assignments: 7,
            diagonal: &[0.0, 1.0],
            linear_inline: &[],
            nonlinear: &[(1, 1)],
        },
    );
    // The algebraic unknown is the loop current (the source's, representing the alias
    // set of the source and cubic resistor currents: nonlinear.i = -source.i).
    assert_eq!(ssys.unknowns(), ["source.i", "c.v"]);
}

#[test]
fn dc_motor_example() {
    // Variables: resistor 6, inductor 6, emf 12, source 7, ground 2, controller (PI) 8,
    // motor inertia 7, gear 8, fixed 2, load inertia 7, sensor 3, reference 1 = 69.
    // Equations: 4 + 4 + 8 + 4 + 1 + 6 + 5 + 5 + 1 + 5 + 2 + 1 = 46; three 2-pin sets
    // (6), the grounded 3-pin set (3), five 2-flange sets (10), three signal
    // connections (3), gear.support.tau = 0 (1): 69.
    // Aliases: the 12 currents of source, resistor, inductor and emf (11); potentials
    // 1 + 1 + 1 and the grounded set 3; fixed angle and emf.support.phi (2); torques
    // {fixed, emf.support, emf.flange, motor.flange_a} (3); the motor angle set (4);
    // {motor.flange_b.tau, gear.flange_a.tau} (1); gear support angle and torque (2);
    // the load angle set with gear.flange_b.phi and sensor.flange.phi (4);
    // {gear.flange_b.tau, load.flange_a.tau} (1); {load.flange_b.tau,
    // sensor.flange.tau} = 0 (2); signals: reference/u_s, sensor.w/u_m and
    // {controller.y, source.v_ref, source.v} (4); the PI's xd = 0, d_part = 0 (2): 42;
    // then the ground current (the armature current in and out of the grounded set is
    // one set): 43. The reference step's relation `time < reference.start_time` adds a
    // crossing variable and its equation (70 flat), an expression of time: 44 aliases.
    // Derivative aliases: emf w, motor w and a, load w and a = 5 (the sensor's
    // w = der(phi) meets the load's angle, which has its derivative already). Left 21.
    // Index reduction: emf.phi = motor.phi - phi0 once (1); the gear's phi_a, phi_b and
    // phi_a = ratio phi_b twice (6) = 7; 28 sorted. States: motor angle and speed,
    // armature current, integrator. The accelerations and gear torques (mechanics of
    // motor, gear, load, three twice-differentiated gear equations) form one linear
    // block of 6 with one tearing variable; the other 22 equations and the 5 torn ones
    // are assignments (27).
    assert_golden(
        &example::dc_motor(),
        &Golden {
            flat: 70,
            aliases: 44,
            derivative_aliases: 5,
            differentiated: 7,
            sorted: 28,
            states: &[
                "motor_inertia.phi",
                "resistor.i",
                "controller.xi",
                "motor_inertia.w",
            ],
            algebraic: 0,
            assignments: 27,
            diagonal: &[1.0, 1.0, 1.0, 1.0],
            linear_inline: &[(6, 1)],
            nonlinear: &[],
        },
    );
}
