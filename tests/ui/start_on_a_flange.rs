// `start` on a connector that is not one value of its own (a flange) is refused.
use multibody::prelude::*;
use multibody::rotational::Flange;

component! {
    /// A part whose flange is given a start value.
    pub struct Part {
        /// Start angle [rad].
        parameter phi_start: f64 = 0.0;
        /// The flange.
        connector flange(start = phi_start): Flange;
        equation {
            flange.tau = 0.0;
        }
    }
}

fn main() {
    let _ = Part::default();
}
