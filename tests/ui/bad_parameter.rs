use multibody::prelude::*;
use multibody::rotational::Inertia;

fn main() {
    let _model = system! {
        inertia = Inertia { JJ: 2.0 };
    };
}
