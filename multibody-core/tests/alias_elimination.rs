//! Alias elimination on a circuit whose connections create aliases: the number of
//! eliminated unknowns is the one derived by hand, and eliminated variables stay
//! readable as observed outputs with the right sign.

use multibody_core::model::{Component, System, VarKind, Variable};
use multibody_core::{DaeProblem, SolverOptions, structural_simplify};

struct Pin;
impl Component for Pin {
    fn type_name(&self) -> String {
        "Pin".into()
    }
    fn connector_class(&self) -> Option<String> {
        Some("Electrical.Pin".into())
    }
    fn build(&self, s: &mut System) {
        s.connector_var("v", VarKind::Potential);
        s.connector_var("i", VarKind::Flow);
    }
}

/// The two-pin part shared by the resistor and the capacitor:
/// `v = p.v - n.v`, `0 = p.i + n.i`, `i = p.i`.
fn two_pin(s: &mut System, v: Variable) -> (multibody_core::Expr, multibody_core::Expr) {
    s.add("p", &Pin);
    s.add("n", &Pin);
    let v = s.variable(v);
    let i = s.var("i");
    s.equation(v, s.v("p.v") - s.v("n.v"));
    s.equation(0.0, s.v("p.i") + s.v("n.i"));
    s.equation(i, s.v("p.i"));
    (v, i)
}

struct Resistor(f64);
impl Component for Resistor {
    fn type_name(&self) -> String {
        "Resistor".into()
    }
    fn build(&self, s: &mut System) {
        let r = s.param("R", self.0);
        let (v, i) = two_pin(s, Variable::new("v"));
        s.equation(v, r * i);
    }
}

struct Capacitor(f64);
impl Component for Capacitor {
    fn type_name(&self) -> String {
        "Capacitor".into()
    }
    fn build(&self, s: &mut System) {
        let c = s.param("C", self.0);
        let (v, i) = two_pin(s, Variable::new("v").start(1.0).fixed(true));
        s.equation(c * v.der(), i);
    }
}

struct Ground;
impl Component for Ground {
    fn type_name(&self) -> String {
        "Ground".into()
    }
    fn build(&self, s: &mut System) {
        s.add("p", &Pin);
        s.equation(s.v("p.v"), 0.0);
    }
}

const R: f64 = 2.0;
const CAP: f64 = 0.25;

/// A capacitor discharging through a resistor:
/// `connect(c1.p, r1.p)`, `connect(r1.n, gnd.p)`, `connect(c1.n, gnd.p)`.
///
/// Flat model: 6 unknowns per two-pin part plus `gnd.p.v`, `gnd.p.i` = 14 unknowns;
/// 4 equations per part, 1 ground, 1 + 2 potential equalities and 2 flow sums = 14.
///
/// Aliases by hand:
/// - currents: `r1.p.i = -r1.n.i`, `r1.i = r1.p.i`, `c1.p.i = -c1.n.i`, `c1.i = c1.p.i`
///   and the two-member flow sum `c1.p.i + r1.p.i = 0` join all six currents into one
///   set: 5 eliminated, one kept;
/// - `c1.p.v = r1.p.v`: 1 eliminated;
/// - `gnd.p.v = 0` with `r1.n.v = gnd.p.v` and `c1.n.v = gnd.p.v`: a constant set, all 3
///   eliminated.
///
/// 5 + 1 + 3 = 9 aliases. Substituted, the three-member flow sum at the ground reads
/// `gnd.p.i + i - i = 0`: the constant `gnd.p.i = 0`, found by the second pass: 10.
/// Left: `r1.v`, `c1.v`, one current and one potential, for the 4 remaining equations
/// (the two `v = p.v - n.v`, Ohm's law and the capacitor law).
fn rc_circuit() -> System {
    let mut m = System::new("alias_rc");
    m.add("r1", &Resistor(R));
    m.add("c1", &Capacitor(CAP));
    m.add("gnd", &Ground);
    m.connect("c1.p", "r1.p");
    m.connect("r1.n", "gnd.p");
    m.connect("c1.n", "gnd.p");
    m
}

#[test]
fn connection_aliases_are_counted_and_stay_observable_with_their_sign() {
    let ssys = structural_simplify(&rc_circuit()).unwrap();
    let st = ssys.statistics();
    assert_eq!((st.flat_equations, st.flat_unknowns), (14, 14), "{st}");
    assert_eq!(st.alias_variables, 10, "{st}");
    assert_eq!(st.derivative_aliases, 0, "{st}");
    assert_eq!(st.sorted_equations, 14 - 10, "{st}");
    assert_eq!(ssys.states(), vec!["c1.v"]);

    // Eliminated variables are observed as +-(the kept one): the current set keeps the
    // earliest declared internal variable, r1.i (internal beats connector variables).
    let observed = ssys.observed();
    let how = |name: &str| {
        observed
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, h)| h.clone())
            .unwrap_or_else(|| panic!("{name} is not observed: {observed:?}"))
    };
    assert_eq!(how("r1.p.i"), "r1.i");
    assert_eq!(how("r1.n.i"), "-r1.i");
    assert_eq!(how("c1.p.i"), "-r1.i");
    assert_eq!(how("c1.n.i"), "r1.i");
    assert_eq!(how("c1.i"), "-r1.i");
    assert_eq!(how("gnd.p.v"), "0");
    assert_eq!(how("r1.n.v"), "0");
    assert_eq!(how("c1.n.v"), "0");
    assert_eq!(how("gnd.p.i"), "0");

    // Numerically: the capacitor discharges as exp(-t / (R C)); the current into the
    // resistor's positive pin is v / R, the capacitor's own current its negative.
    let prob = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let opts = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
    .with_output_interval(0.0, 1.0, 0.125);
    let sol = prob.solve(&opts).unwrap();
    let names = [
        "c1.v", "r1.i", "r1.p.i", "r1.n.i", "c1.i", "c1.p.i", "c1.n.i", "gnd.p.i", "r1.p.v",
        "c1.p.v", "r1.n.v", "gnd.p.v", "r1.v",
    ];
    let s = sol.get_many(&names).unwrap();
    assert!(sol.t().len() >= 9);
    for (k, &t) in sol.t().iter().enumerate() {
        let v = (-t / (R * CAP)).exp();
        let i = v / R;
        let want = [v, i, i, -i, -i, -i, i, 0.0, v, v, 0.0, 0.0, v];
        for (j, name) in names.iter().enumerate() {
            assert!(
                (s[j][k] - want[j]).abs() < 1e-7,
                "{name}({t}) = {}, expected {}",
                s[j][k],
                want[j]
            );
        }
        // The sign relations hold exactly (observed expressions of the same unknown).
        assert_eq!(s[3][k], -s[1][k], "r1.n.i = -r1.i at {t}");
        assert_eq!(s[4][k], -s[1][k], "c1.i = -r1.i at {t}");
    }
}
