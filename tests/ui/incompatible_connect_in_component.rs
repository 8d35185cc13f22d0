use multibody::electrical::Pin;
use multibody::prelude::*;
use multibody::rotational::Inertia;

component! {
    /// Connects an electrical pin to a rotational flange.
    pub struct Mixed {
        connector p: Pin;
        component inertia: Inertia;
        equation {
            connect(p, inertia.flange_a);
        }
    }
}

fn main() {}
