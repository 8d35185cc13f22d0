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
fn equation_texts_share_the_flat_equations_and_name_connection_variables() {
    let mut flat = flatten(&two_resistors()).unwrap();
    let expected: Vec<String> = flat.equations.iter().map(|e| flat.describe(e)).collect();
    let variables = std::sync::Arc::new(std::mem::take(&mut flat.variables));
    let n = flat.equations.len();
    let origins = FlatOrigins::new(
        std::mem::take(&mut flat.equations),
        variables,
        flat.stores.clone(),
    );
    let texts: Vec<String> = (0..n)
        .map(|k| EquationText::of(&origins, k).to_string())
        .collect();
    assert_eq!(texts, expected);
    let k = texts
        .iter()
        .position(|t| t == "connection: r1.n.v = r2.p.v")
        .expect("the potential equality of r1.n and r2.p");
    let text = EquationText::of(&origins, k);
    assert_eq!(
        text.derivative().to_string(),
        "d/dt[connection: r1.n.v = r2.p.v]"
    );
    assert_eq!(text.clone().to_string(), text.to_string());
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
    let err = check_balance(&flat).unwrap_err();
    // `x` is declared at the root, whose path is empty: its full path is `x`. The
    // Dulmage-Mendelsohn under-determined part is exactly {x} (every other unknown is
    // matched), and nothing is over-determined.
    match &err {
        ModelError::Unbalanced {
            undetermined,
            overdetermined,
            equations,
            unknowns,
            ..
        } => {
            assert_eq!(undetermined, &vec!["x".to_string()], "{err}");
            assert!(overdetermined.is_empty(), "{err}");
            assert_eq!((*equations, *unknowns), (8, 9));
        }
        other => panic!("expected an unbalanced model, got {other:?}"),
    }
    let err = err.to_string();
    assert!(err.contains("8 equations for 9 unknowns"), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines,
        [
            "model `flat_extra` is not balanced: 8 equations for 9 unknowns",
            "  under-determined: no equation is left for x",
        ],
        "{err}"
    );
}

/// A component two levels down with three equations for its two unknowns.
struct OverBlock;
impl Component for OverBlock {
    fn type_name(&self) -> String {
        "OverBlock".into()
    }
    fn build(&self, s: &mut System) {
        let a = s.var("a");
        let b = s.var("b");
        s.equation(a, 1.0);
        s.equation(b, 2.0);
        s.equation(a + b, 3.0);
    }
}

/// Holds an [`OverBlock`] as `blk` and a well-determined unknown `c` of its own.
struct OverPlant;
impl Component for OverPlant {
    fn type_name(&self) -> String {
        "OverPlant".into()
    }
    fn build(&self, s: &mut System) {
        s.add("blk", &OverBlock);
        let c = s.var("c");
        s.equation(c, 5.0);
    }
}

#[test]
fn overdetermined_model_names_its_equations_by_full_path() {
    let mut m = System::new("flat_over");
    m.add("plant", &OverPlant);
    m.add("r1", &Resistor(1.0));
    m.add("gnd", &Ground);
    m.connect("r1.n", "gnd.p");
    m.connect("r1.p", "gnd.p");
    let flat = flatten(&m).unwrap();
    // 4 (plant) + 4 (r1) + 1 (gnd) + 2 potential equalities + 1 flow sum = 12 equations
    // for 3 (plant) + 6 (r1) + 2 (gnd) = 11 unknowns.
    assert_eq!((flat.equations.len(), flat.variables.len()), (12, 11));
    let err = check_balance(&flat).unwrap_err();
    // Matching plant.blk.a and plant.blk.b leaves one of the block's three equations
    // unmatched; alternating paths from it reach the other two, so all three (and no
    // other equation) are over-determined; no unknown is left without an equation.
    let expected = [
        "plant.blk: plant.blk.a = 1",
        "plant.blk: plant.blk.b = 2",
        "plant.blk: plant.blk.a + plant.blk.b = 3",
    ];
    match &err {
        ModelError::Unbalanced {
            model,
            equations,
            unknowns,
            undetermined,
            overdetermined,
            unconnected_inputs,
        } => {
            assert!(unconnected_inputs.is_empty(), "over-determined: not asked");
            assert_eq!(model, "flat_over");
            assert_eq!((*equations, *unknowns), (12, 11));
            assert!(undetermined.is_empty(), "{err}");
            let mut got = overdetermined.clone();
            got.sort();
            let mut want: Vec<String> = expected.iter().map(|s| s.to_string()).collect();
            want.sort();
            assert_eq!(got, want, "{err}");
        }
        other => panic!("expected an unbalanced model, got {other:?}"),
    }
    let msg = err.to_string();
    let lines: Vec<&str> = msg.lines().collect();
    assert_eq!(lines.len(), 2, "{msg}");
    assert_eq!(
        lines[0],
        "model `flat_over` is not balanced: 12 equations for 11 unknowns"
    );
    let prefix = "  over-determined: nothing is left to determine in ";
    let listed = lines[1]
        .strip_prefix(prefix)
        .unwrap_or_else(|| panic!("{msg}"));
    let mut listed: Vec<&str> = listed.split(", ").collect();
    listed.sort();
    let mut want = expected.to_vec();
    want.sort();
    assert_eq!(listed, want, "{msg}");
    assert!(!msg.contains("plant.c"), "{msg}");
    assert!(!msg.contains("r1."), "{msg}");
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

#[test]
fn declared_names_are_the_symbol_tables_and_flat_equations_stay_small() {
    let mut m = System::new("m");
    m.add("r1", &Resistor(2.0));
    m.add("r2", &Resistor(3.0));
    // Every declared name is the full path, kept by the symbol table (no allocation of
    // its own), and the same text for the same path.
    let r1 = m.subsystem("r1").expect("r1");
    let v = r1
        .variables
        .iter()
        .find(|v| &*v.name == "r1.v")
        .expect("r1.v");
    assert!(v.name.is_static());
    assert!(r1.parameters[0].name.is_static());
    assert_eq!(&*r1.parameters[0].name, "r1.R");
    let pin = r1.subsystem("p").expect("r1.p");
    assert_eq!(&*pin.variables[0].name, "r1.p.v");
    assert!(pin.variables[0].name.is_static());
    let again = Expr::var("r1.p.v").name().expect("a leaf");
    assert_eq!(again, "r1.p.v");
    // A variable built by hand keeps its (local) name until it is declared.
    let local = Variable::new(String::from("x"));
    assert!(!local.name.is_static());
    let mut s = System::new("s");
    s.variable(local);
    assert!(s.variables[0].name.is_static());
    // Every pass over the equations reads their origins; a rare kind of origin is
    // boxed so it does not make them all larger.
    assert!(std::mem::size_of::<FlatEquation>() <= 48);
}
