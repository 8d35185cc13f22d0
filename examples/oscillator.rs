//! A rotational spring-damper oscillator: the smallest complete model.

use multibody::prelude::*;
use multibody::rotational::{Damper, Fixed, Inertia, Spring};

fn main() -> Result<(), multibody::Error> {
    let model = system! {
        name: "oscillator";
        fixed = Fixed::default();
        spring = Spring { c: 4.0 };
        damper = Damper { d: 0.4 };
        inertia = Inertia { J: 1.0, phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, inertia.flange_a);
    };
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    for e in ssys.equations() {
        println!("  {e}");
    }
    let prob = DaeProblem::new(&ssys, &[], (0.0, 10.0))?;
    println!("init: {:?}", prob.init_report());
    let sol = prob.solve(&SolverOptions::default())?;
    println!("{:?}", sol.statistics());
    plot(
        &sol,
        &[model.inertia.phi, model.inertia.w],
        "oscillator.png",
    )?;
    Ok(())
}
