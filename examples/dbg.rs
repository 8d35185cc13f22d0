use multibody::prelude::*;
component! {
    pub struct BlowUp {
        variable x(start = 1.0, fixed = true): Real;
        equation { der(x) = x * x; }
    }
}
fn main() {
    let model = system! { name: "blowup"; part = BlowUp::default(); };
    let ssys = structural_simplify(&model).unwrap();
    let r = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions { max_steps: 3000, ..SolverOptions::default() });
    match r { Ok(sol) => { let n = sol.t().len(); println!("ok {} pts, last t {} x {:?}", n, sol.t()[n-1], sol.unknowns_at(n-1)); for k in (n-10)..n { println!("{} {:?}", sol.t()[k], sol.unknowns_at(k)); } }, Err(e) => println!("{e}") }
}
