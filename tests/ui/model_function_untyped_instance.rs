use multibody::prelude::*;
use multibody::rotational::Inertia;

fn make_inertia() -> Inertia {
    Inertia { J: 2.0, ..Default::default() }
}

system! {
    /// A model function whose instance's type cannot be read from its value.
    pub fn two_inertias() -> TwoInertias {
        a = Inertia { J: 1.0 };
        b = make_inertia();
        connect(a.flange_b, b.flange_a);
    }
}

fn main() {}
