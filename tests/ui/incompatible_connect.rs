use multibody::electrical::Resistor;
use multibody::prelude::*;
use multibody::rotational::Inertia;

fn main() {
    let _model = system! {
        resistor = Resistor::default();
        inertia = Inertia::default();
        connect(resistor.p, inertia.flange_a);
    };
}
