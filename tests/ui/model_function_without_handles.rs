use multibody::prelude::*;

system! {
    pub fn one_inertia() {
        a = multibody::rotational::Inertia { J: 1.0 };
    }
}

fn main() {}
