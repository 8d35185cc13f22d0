//! Continuous blocks: integrator, first-order lag, derivative, PI, PID and the limited
//! PID controller of MSL.

use super::interfaces::*;
use crate::prelude::*;

/// The acceleration by which MSL's position sources (`Rotational` and
/// `Translational.Sources.Position`) follow their reference through a critically
/// damped 2nd-order Bessel filter of cut-off frequency `f_crit` \[Hz\]
/// (`af = 1.3617`, `bf = 0.6180`): from the position error `error` and the speed
/// `speed`.
pub(crate) fn bessel_follow(error: Expr, speed: Expr, f_crit: Expr) -> Expr {
    let w = 2.0 * PI * f_crit;
    (error * w - 1.3617 * speed) * (w / 0.6180)
}

component! {
    /// Output the integral of the input times a gain (MSL `Blocks.Continuous.Integrator`).
    #[type_name = "Blocks.Integrator"]
    pub struct Integrator {
        /// Integrator gain [1/s].
        parameter k: f64 = 1.0;
        /// Start value of the output.
        parameter y_start: f64 = 0.0;
        /// Initialization (MSL default: the output starts at `y_start`).
        structural init: Init = Init::InitialState;
        /// Input.
        connector u: RealInput;
        /// Output (starts at `y_start`: fixed by `init`, otherwise a guess).
        connector y(start = y_start): RealOutput;
        equation {
            der(y) = k * u;
        }
        initial_equation {
            match init {
                Init::InitialState | Init::InitialOutput => { y = y_start; }
                Init::SteadyState => { der(y) = 0.0; }
                Init::NoInit => {}
            }
        }
    }
}

component! {
    /// A first-order lag `T der(y) + y = k u` (MSL `Blocks.Continuous.FirstOrder`).
    #[type_name = "Blocks.FirstOrder"]
    pub struct FirstOrder {
        /// Gain.
        parameter k: f64 = 1.0;
        /// Time constant [s].
        parameter T: f64 = 1.0;
        /// Start value of the output.
        parameter y_start: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Input.
        connector u: RealInput;
        /// Output (starts at `y_start`: fixed by `init`, otherwise a guess).
        connector y(start = y_start): RealOutput;
        equation {
            der(y) = (k * u - y) / T;
        }
        initial_equation {
            match init {
                Init::InitialState | Init::InitialOutput => { y = y_start; }
                Init::SteadyState => { der(y) = 0.0; }
                Init::NoInit => {}
            }
        }
    }
}

component! {
    /// An approximated derivative `y = k/T (u - x)`, `der(x) = (u - x)/T` (MSL
    /// `Blocks.Continuous.Derivative`).
    #[type_name = "Blocks.Derivative"]
    pub struct Derivative {
        /// Gain.
        parameter k: f64 = 1.0;
        /// Time constant of the approximation [s] (must be positive).
        parameter T: f64 = 0.01;
        /// Start value of the state.
        parameter x_start: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// State of the block.
        variable x(start = x_start): Real;
        equation {
            der(x) = (u - x) / T;
            y = k / T * (u - x);
        }
        initial_equation {
            match init {
                Init::InitialState => { x = x_start; }
                Init::SteadyState => { der(x) = 0.0; }
                Init::InitialOutput | Init::NoInit => {}
            }
        }
    }
}

component! {
    /// A proportional-integral controller `y = k (x + u)`, `der(x) = u / T` (MSL
    /// `Blocks.Continuous.PI`).
    #[type_name = "Blocks.PI"]
    pub struct PI {
        /// Gain.
        parameter k: f64 = 1.0;
        /// Time constant of the integrator [s].
        parameter T: f64 = 1.0;
        /// Start value of the state.
        parameter x_start: f64 = 0.0;
        /// Start value of the output.
        parameter y_start: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// State of the integrator.
        variable x(start = x_start): Real;
        equation {
            der(x) = u / T;
            y = k * (x + u);
        }
        initial_equation {
            match init {
                Init::InitialState => { x = x_start; }
                Init::SteadyState => { der(x) = 0.0; }
                Init::InitialOutput => { y = y_start; }
                Init::NoInit => {}
            }
        }
    }
}

component! {
    /// A PID controller `y = k (u + xi + Nd (u - xd))` with `der(xi) = u / Ti` and the
    /// derivative filtered by `der(xd) = (u - xd) / (Td / Nd)` (MSL
    /// `Blocks.Continuous.PID`).
    #[type_name = "Blocks.PID"]
    pub struct PID {
        /// Gain.
        parameter k: f64 = 1.0;
        /// Time constant of the integrator [s].
        parameter Ti: f64 = 0.5;
        /// Time constant of the derivative [s].
        parameter Td: f64 = 0.1;
        /// The derivative acts like a high-pass filter below frequency `Nd / Td`.
        parameter Nd: f64 = 10.0;
        /// Start value of the integrator state.
        parameter xi_start: f64 = 0.0;
        /// Start value of the derivative state.
        parameter xd_start: f64 = 0.0;
        /// Start value of the output.
        parameter y_start: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Input (control error).
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// Integrator state.
        variable xi(start = xi_start): Real;
        /// Derivative filter state.
        variable xd(start = xd_start): Real;
        equation {
            der(xi) = u / Ti;
            der(xd) = (u - xd) * Nd / Td;
            y = k * (u + xi + Nd * (u - xd));
        }
        initial_equation {
            match init {
                Init::InitialState => { xi = xi_start; xd = xd_start; }
                Init::SteadyState => { der(xi) = 0.0; der(xd) = 0.0; }
                Init::InitialOutput => { y = y_start; der(xd) = 0.0; }
                Init::NoInit => {}
            }
        }
    }
}

/// Which parts a [`LimPID`] uses (MSL `SimpleController`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ControllerType {
    /// Proportional only.
    P,
    /// Proportional and integral.
    PI,
    /// Proportional and derivative.
    PD,
    /// All three.
    #[default]
    PID,
}

impl ControllerType {
    fn integral(self) -> bool {
        matches!(self, ControllerType::PI | ControllerType::PID)
    }
    fn derivative(self) -> bool {
        matches!(self, ControllerType::PD | ControllerType::PID)
    }
}

component! {
    /// The PID controller of MSL with set-point weighting, a limited output and
    /// anti-windup by tracking (MSL `Blocks.Continuous.LimPID`):
    /// `y = min(max(k (P + I + D), y_min), y_max)` with `P = wp u_s - u_m`,
    /// `der(I) = (u_s - u_m + (y - k (P + I + D)) / (k Ni)) / Ti`, and
    /// `D = Td / T_D (wd u_s - u_m - xd)`, `der(xd) = (wd u_s - u_m - xd) / T_D`,
    /// `T_D = max(Td / Nd, 1e-14)`.
    #[type_name = "Blocks.LimPID"]
    pub struct LimPID {
        /// Which parts are used.
        structural controller_type: ControllerType = ControllerType::PID;
        /// Gain.
        parameter k: f64 = 1.0;
        /// Time constant of the integrator [s].
        parameter Ti: f64 = 0.5;
        /// Time constant of the derivative [s].
        parameter Td: f64 = 0.1;
        /// Upper limit of the output.
        parameter y_max: f64 = 1.0;
        /// Lower limit of the output.
        parameter y_min: f64 = -1.0;
        /// Set-point weight of the proportional part.
        parameter wp: f64 = 1.0;
        /// Set-point weight of the derivative part.
        parameter wd: f64 = 0.0;
        /// `Ni Ti` is the time constant of the anti-windup compensation.
        parameter Ni: f64 = 0.9;
        /// The derivative acts like a high-pass filter below frequency `Nd / Td`.
        parameter Nd: f64 = 10.0;
        /// Start value of the integrator state.
        parameter xi_start: f64 = 0.0;
        /// Start value of the derivative state.
        parameter xd_start: f64 = 0.0;
        /// Start value of the output.
        parameter y_start: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Set point.
        connector u_s: RealInput;
        /// Measurement.
        connector u_m: RealInput;
        /// Limited output.
        connector y: RealOutput;
        /// Control error `u_s - u_m`.
        variable control_error: Real;
        /// Output before the limiter.
        variable y_unlimited: Real;
        /// Integral part.
        variable xi(start = xi_start): Real;
        /// Derivative filter state.
        variable xd(start = xd_start): Real;
        /// Derivative part.
        variable d_part: Real;
        equation {
            control_error = u_s - u_m;
            y_unlimited = k * (wp * u_s - u_m + xi + d_part);
            y = min(max(y_unlimited, y_min), y_max);
            if controller_type.integral() {
                der(xi) = (control_error + (y - y_unlimited) / (k * Ni)) / Ti;
            } else {
                xi = 0.0;
            }
            if controller_type.derivative() {
                der(xd) = (wd * u_s - u_m - xd) / max(Td / Nd, 1e-14);
                d_part = Td / max(Td / Nd, 1e-14) * (wd * u_s - u_m - xd);
            } else {
                xd = 0.0;
                d_part = 0.0;
            }
        }
        initial_equation {
            match init {
                Init::InitialState => {
                    if controller_type.integral() { xi = xi_start; }
                    if controller_type.derivative() { xd = xd_start; }
                }
                Init::SteadyState => {
                    if controller_type.integral() { der(xi) = 0.0; }
                    if controller_type.derivative() { der(xd) = 0.0; }
                }
                Init::InitialOutput => {
                    y = y_start;
                    if controller_type.derivative() { der(xd) = 0.0; }
                }
                Init::NoInit => {}
            }
        }
    }
}
