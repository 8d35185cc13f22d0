use multibody::prelude::*;

component! {
    /// `reinit` without a `when` clause around it.
    pub struct Reset {
        variable x(start = 1.0, fixed = true): Real;
        equation {
            der(x) = -x;
            reinit(x, 1.0);
        }
    }
}

fn main() {}
