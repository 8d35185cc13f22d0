use multibody::prelude::*;

component! {
    /// A mass with a comparison where an equation belongs.
    pub struct Broken {
        variable x: Real;
        variable v: Real;
        equation {
            der(x) = v;
            der(v) == -x;
        }
    }
}

fn main() {}
