use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia};

fn main() {
    let _model = system! {
        fixed = Fixed::default();
        inertia = Inertia::default();
        connect(fixed.flange, inertia.flange_c);
    };
}
