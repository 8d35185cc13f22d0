//! Flattening tests on small hand-built models.

use super::*;
use crate::expr::Expr;

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

struct Resistor(f64);
impl Component for Resistor {
    fn type_name(&self) -> String {
        "Resistor".into()
    }
    fn build(&self, s: &mut System) {
        let r = s.param("R", self.0);
        s.add("p", &Pin);
        s.add("n", &Pin);
        let v = s.var("v");
        let i = s.var("i");
        s.equation(v, s.v("p.v") - s.v("n.v"));
        s.equation(Expr::constant(0.0), s.v("p.i") + s.v("n.i"));
        s.equation(i, s.v("p.i"));
        s.equation(v, r * i);
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

fn two_resistors() -> System {
    let mut m = System::new("flat_two_r");
    m.add("r1", &Resistor(1.0));
    m.add("r2", &Resistor(2.0));
    m.add("gnd", &Ground);
    m.connect("r1.n", "r2.p");
    m.connect("r2.n", "gnd.p");
    m.connect("r1.p", "gnd.p");
    m
}

#[test]
fn connection_sets_give_potential_equalities_and_flow_sums() {
    let flat = flatten(&two_resistors()).unwrap();
    // 2 x (v, i, p.v, p.i, n.v, n.i) + gnd.p.v, gnd.p.i = 14 unknowns
    assert_eq!(flat.variables.len(), 14);
    let texts: Vec<String> = flat.equations.iter().map(|e| flat.describe(e)).collect();
    // 4 per resistor + 1 ground + 3 potential equalities + 2 flow sums
    assert_eq!(flat.equations.len(), 4 + 4 + 1 + 3 + 2, "{texts:#?}");
    assert!(
        texts.contains(&"connection: r1.n.v = r2.p.v".to_string()),
        "{texts:#?}"
    );
    assert!(
        texts
            .iter()
            .any(|t| t.contains("r2.n.i + r1.p.i + gnd.p.i = 0")
                || (t.contains("r2.n.i") && t.contains("gnd.p.i") && t.contains("r1.p.i"))),
        "{texts:#?}"
    );
    check_balance(&flat).unwrap();
}

#[test]
fn unconnected_flow_is_zero_and_unbalance_names_variables() {
    let mut m = System::new("flat_open");
    m.add("r1", &Resistor(1.0));
    m.add("gnd", &Ground);
    m.connect("r1.n", "gnd.p");
    let flat = flatten(&m).unwrap();
    let texts: Vec<String> = flat.equations.iter().map(|e| flat.describe(e)).collect();
    assert!(
        texts.contains(&"unconnected flow: r1.p.i = 0".to_string()),
        "{texts:#?}"
    );
    // 8 equations for 8 unknowns: balanced by count (r1.p.v is left undetermined, which
    // only the structural analysis finds).
    check_balance(&flat).unwrap();

    // One unknown more than equations: the balance check names it.
    let mut m = System::new("flat_extra");
    m.add("r1", &Resistor(1.0));
    m.add("gnd", &Ground);
    m.connect("r1.n", "gnd.p");
    m.connect("r1.p", "gnd.p");
    m.var("x");
    let flat = flatten(&m).unwrap();
    let err = check_balance(&flat).unwrap_err().to_string();
    assert!(err.contains("8 equations for 9 unknowns"), "{err}");
    assert!(
        err.contains("no equation is left for `x`") || err.contains("x"),
        "{err}"
    );
}

#[test]
fn bad_connections_are_named() {
    let mut m = System::new("flat_bad");
    m.add("r1", &Resistor(1.0));
    m.add("gnd", &Ground);
    m.connect("r1.q", "gnd.p");
    let err = flatten(&m).unwrap_err().to_string();
    assert!(err.contains("`r1.q` is not a connector"), "{err}");
    assert!(err.contains("r1.p") || err.contains("r1.n"), "{err}");

    let mut m = System::new("flat_bad2");
    m.add("r1", &Resistor(1.0));
    let x = m.var("x");
    m.equation(x, m.v("r1.vv"));
    let err = flatten(&m).unwrap_err().to_string();
    assert!(err.contains("unknown variable `r1.vv`"), "{err}");
    assert!(err.contains("did you mean `r1.v`"), "{err}");
}
