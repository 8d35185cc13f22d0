use multibody::prelude::*;

component! {
    /// A misspelt start attribute.
    pub struct Typo {
        variable x(strat = 1.0): Real;
        equation {
            der(x) = -x;
        }
    }
}

fn main() {}
