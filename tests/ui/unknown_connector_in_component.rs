use multibody::prelude::*;
use multibody::rotational::{Flange, Inertia};

component! {
    /// Connects to a connector its inertia does not have.
    pub struct Shaft {
        connector flange: Flange;
        component inertia: Inertia;
        equation {
            connect(flange, inertia.flange);
        }
    }
}

fn main() {}
