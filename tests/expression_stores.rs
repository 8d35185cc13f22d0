//! Where a model's expressions live: in a store that the model (and what is compiled
//! from it) holds, so that dropping them returns its memory, and that threads building
//! different models share nothing but the names.

use std::sync::Mutex;

use multibody::prelude::*;
use multibody::rotational::{Damper, Fixed, Inertia, Spring};
use multibody_core::expr::ExprStore;

/// The tests run one at a time (the count of stores is the process's), each on a
/// thread of its own that has ended, with its thread-local state, when it returns.
static COUNTING: Mutex<()> = Mutex::new(());

fn isolated<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
    let _one_at_a_time = COUNTING.lock().unwrap_or_else(|e| e.into_inner());
    std::thread::spawn(f).join().expect("the test's thread")
}

system! {
    fn oscillator(c: f64) -> Oscillator {
        name: "oscillator";
        fixed = Fixed::default();
        spring = Spring { c };
        damper = Damper { d: 0.4 };
        inertia = Inertia { J: 1.0, phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, inertia.flange_a);
    }
}

/// The angle of the oscillator at t = 2 s.
fn phi_at_2(model: &(impl AsRef<System> + ?Sized)) -> f64 {
    let ssys = structural_simplify(model).expect("compiles");
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .expect("initializes")
        .solve(&SolverOptions::default())
        .expect("solves");
    sol.sample(&["inertia.phi"], &[2.0]).expect("a variable")[0][0]
}

#[test]
fn dropping_a_model_and_its_compiled_forms_returns_its_store() {
    isolated(dropping_returns_the_store);
}

fn dropping_returns_the_store() {
    let base = ExprStore::live();
    for k in 0..20 {
        let model = oscillator(1.0 + k as f64);
        assert_eq!(ExprStore::live(), base + 1, "one store per model");
        let ssys = structural_simplify(&model).unwrap();
        drop(model);
        assert_eq!(
            ExprStore::live(),
            base + 1,
            "the compiled system keeps the store its equations print from"
        );
        let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
            .unwrap()
            .solve(&SolverOptions::default())
            .unwrap();
        drop(ssys);
        assert!(sol.t().len() > 1);
        drop(sol);
        assert_eq!(
            ExprStore::live(),
            base,
            "model {k}: everything was returned"
        );
    }
}

#[test]
fn an_expression_of_another_model_is_copied_into_the_system_that_uses_it() {
    isolated(copied_from_another_model);
}

fn copied_from_another_model() {
    let donor = oscillator(4.0);
    // Built while `donor` is this thread's current model: it lives in donor's store.
    let torque = Expr::param("inertia.J") * -0.5 * Expr::time().sin();
    let mut model = oscillator(4.0).into_system();
    let y = model.var("y");
    model.equation(y.der(), torque);
    model.initial_equation(y, 0.0);
    drop(donor);
    // The equation holds a copy in `model`'s store: it compiles after the donor is
    // gone, and with J = 1, y' = -0.5 sin(t) from 0 gives y(t) = 0.5 (cos t - 1).
    let ssys = structural_simplify(&model).expect("compiles after the donor is gone");
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let w = sol.sample(&["y"], &[2.0]).unwrap()[0][0];
    let exact = 0.5 * (2f64.cos() - 1.0);
    assert!((w - exact).abs() < 1e-4, "{w} against {exact}");
}

#[test]
fn expressions_built_before_a_model_go_to_the_store_it_adopts() {
    isolated(adopted);
}

fn adopted() {
    let base = ExprStore::live();
    let e = Expr::var("x").sin() * 3.0;
    assert_eq!(
        ExprStore::live(),
        base + 1,
        "the thread's store for loose expressions"
    );
    let mut model = System::new("adopting");
    assert_eq!(ExprStore::live(), base + 1, "the model adopted it");
    let x = model.var("x");
    model.equation(x.der(), e);
    model.initial_equation(x, 0.0);
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // x' = 3 sin(x) from x = 0 stays at the equilibrium.
    assert_eq!(sol.sample(&["x"], &[1.0]).unwrap()[0][0], 0.0);
    drop((model, ssys, sol));
    assert_eq!(ExprStore::live(), base);
}

#[test]
fn two_threads_build_and_solve_two_models_with_the_results_of_one() {
    isolated(two_threads);
}

fn two_threads() {
    let sequential = [phi_at_2(&oscillator(4.0)), phi_at_2(&oscillator(9.0))];
    let parallel = std::thread::scope(|s| {
        let a = s.spawn(|| phi_at_2(&oscillator(4.0)));
        let b = s.spawn(|| phi_at_2(&oscillator(9.0)));
        [a.join().unwrap(), b.join().unwrap()]
    });
    assert_eq!(sequential, parallel);
    // The closed form of the underdamped oscillator, J = 1, d = 0.4, phi(0) = 1.
    for (c, phi) in [(4.0f64, sequential[0]), (9.0, sequential[1])] {
        let (delta, t) = (0.2f64, 2.0f64);
        let wd = (c - delta * delta).sqrt();
        let exact = (-delta * t).exp() * ((wd * t).cos() + delta / wd * (wd * t).sin());
        assert!((phi - exact).abs() < 1e-4, "c = {c}: {phi} against {exact}");
    }
}

#[test]
fn a_model_sent_to_another_thread_compiles_there() {
    isolated(sent);
}

fn sent() {
    let model = oscillator(4.0);
    let here = phi_at_2(&model);
    let there = std::thread::spawn(move || phi_at_2(&model)).join().unwrap();
    assert_eq!(here, there);
}
