use multibody::prelude::*;
use multibody::rotational::Inertia;

fn main() {
    let m = system! {
        a = Inertia { J: 1.0 };
    };
    // An inertia has `phi`, `w` and `a`, no `omega`.
    let _ = m.a.omega;
}
