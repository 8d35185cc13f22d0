use multibody::prelude::*;
use multibody::rotational::PartialCompliant;

component! {
    /// A spring that acts only when stretched by more than 0.1 rad: `if` picks
    /// equations when the model is built, so it cannot test a variable.
    pub struct SlackSpring {
        /// Stiffness [N.m/rad].
        parameter c: f64 = 1.0;
        extends PartialCompliant { flange_a, flange_b, phi_rel, tau };
        equation {
            if phi_rel > 0.1 {
                tau = c * phi_rel;
            } else {
                tau = 0.0;
            }
        }
    }
}

fn main() {}
