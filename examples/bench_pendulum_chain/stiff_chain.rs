//! The stiff model of the benchmark (and of `tests/integrators.rs`): masses in a row on
//! spring-dampers.

use multibody::blocks::Constant;
use multibody::prelude::*;
use multibody::translational::{Damper, Fixed, Force, Mass, Spring};

/// `n` masses of 1 kg in a row from a fixed wall, each joined to the one before by a
/// spring `c` \[N/m\] and a damper `d` \[N s/m\] in parallel, the last pulled by a
/// constant force `force` \[N\]. At rest, mass `k` is at `k force / c`.
pub fn stiff_chain(n: usize, c: f64, d: f64, force: f64) -> System {
    let mut m = System::new(format!("stiff_chain{n}"));
    let wall = m.add_typed("wall", &Fixed::default());
    let mut prev = wall.flange;
    for k in 1..=n {
        let spring = m.add_typed(
            &format!("spring{k}"),
            &Spring {
                c,
                ..Default::default()
            },
        );
        let damper = m.add_typed(&format!("damper{k}"), &Damper { d });
        let mass = m.add_typed(&format!("mass{k}"), &Mass::default());
        m.connect_handles(&prev, &spring.flange_a);
        m.connect_handles(&prev, &damper.flange_a);
        m.connect_handles(&spring.flange_b, &mass.flange_a);
        m.connect_handles(&damper.flange_b, &mass.flange_a);
        prev = mass.flange_b;
    }
    let pull = m.add_typed("pull", &Force::default());
    let value = m.add_typed("value", &Constant { k: force });
    m.connect_handles(&value.y, &pull.f);
    m.connect_handles(&pull.flange, &prev);
    m
}
