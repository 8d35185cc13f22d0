//! The robot's motor with its analog current controller.

use crate::blocks::{Gain, RealInput, RealOutput};
use crate::electrical::{
    Capacitor, CurrentSensor, EMF, Ground, IdealOpAmp, Inductor, Resistor, SignalVoltage,
};
use crate::prelude::*;
use crate::rotational::{AngleSensor, Flange, Inertia, SpeedSensor};

component! {
    /// A DC motor driven by a current controller built from operational amplifiers (MSL
    /// `RobotR3.Utilities.Motor`): the difference of the reference and the measured
    /// current is integrated (`C`) and amplified to the armature voltage; `w` and `D` set
    /// the controller's bandwidth and damping. Starts in a steady state.
    #[type_name = "RobotR3.Motor"]
    pub struct Motor {
        /// Moment of inertia of the motor [kg.m2], default 0.0013.
        parameter J(min = 0.0): f64 = 0.0013;
        /// Gain of the motor [N.m/A], default 1.1616.
        parameter k(min = 0.0): f64 = 1.1616;
        /// Time constant of the current controller [rad/s], default 4590.
        parameter w(min = 0.0): f64 = 4590.0;
        /// Damping of the current controller [1], default 0.6.
        parameter D(min = 0.0): f64 = 0.6;
        /// Flange of the motor's shaft.
        connector flange_motor: Flange;
        /// Reference current [A].
        connector current_ref: RealInput;
        /// Measured current [A].
        connector current: RealOutput;
        /// Motor angle [rad].
        connector motorAngle: RealOutput;
        /// Motor speed [rad/s].
        connector motorSpeed: RealOutput;
        /// Voltage source of the reference current signal.
        component Vs: SignalVoltage;
        /// Difference amplifier of the reference and the measured current.
        component diff: IdealOpAmp;
        /// Power amplifier driving the armature.
        component power: IdealOpAmp;
        /// Electromotive force of the motor.
        component emf: EMF = EMF { k: self.k, ..EMF::default() };
        /// Armature inductance.
        component La: Inductor = Inductor { L: 250.0 / (2.0 * self.D * self.w) };
        /// Armature resistance.
        component Ra: Resistor = Resistor { R: 250.0 };
        /// Input resistor of the difference amplifier.
        component Rd2: Resistor = Resistor { R: 100.0 };
        /// Capacitor of the current integrator.
        component C: Capacitor = Capacitor { C: 0.004 * self.D / self.w };
        /// Integrating amplifier.
        component OpI: IdealOpAmp;
        /// Feedback resistor of the difference amplifier.
        component Rd1: Resistor = Resistor { R: 100.0 };
        /// Input resistor of the integrator.
        component Ri: Resistor = Resistor { R: 10.0 };
        /// Feedback resistor of the power amplifier.
        component Rp1: Resistor = Resistor { R: 200.0 };
        /// Ground resistor of the power amplifier.
        component Rp2: Resistor = Resistor { R: 50.0 };
        /// Lower resistor of the measured-current divider.
        component Rd4: Resistor = Resistor { R: 100.0 };
        /// Voltage source of the measured current signal.
        component hall2: SignalVoltage;
        /// Upper resistor of the measured-current divider.
        component Rd3: Resistor = Resistor { R: 100.0 };
        /// Ground.
        component g1: Ground;
        /// Ground.
        component g2: Ground;
        /// Ground.
        component g3: Ground;
        /// Current sensor (the Hall sensor).
        component hall1: CurrentSensor;
        /// Ground.
        component g4: Ground;
        /// Ground.
        component g5: Ground;
        /// Motor angle sensor.
        component phi: AngleSensor;
        /// Motor speed sensor.
        component speed: SpeedSensor;
        /// Motor inertia.
        component Jmotor: Inertia = Inertia { J: self.J, ..Inertia::default() };
        /// Measured current to voltage (gain 1).
        component convert1: Gain;
        /// Reference current to voltage (gain 1).
        component convert2: Gain;
        equation {
            connect(La.n, emf.p);
            connect(Ra.n, La.p);
            connect(Rd2.n, diff.n1);
            connect(C.n, OpI.p2);
            connect(OpI.p2, power.p1);
            connect(Vs.p, Rd2.p);
            connect(diff.n1, Rd1.p);
            connect(Rd1.n, diff.p2);
            connect(diff.p2, Ri.p);
            connect(Ri.n, OpI.n1);
            connect(OpI.n1, C.p);
            connect(power.n1, Rp1.p);
            connect(power.p2, Rp1.n);
            connect(Rp1.p, Rp2.p);
            connect(power.p2, Ra.p);
            connect(Rd3.p, hall2.p);
            connect(Rd3.n, diff.p1);
            connect(Rd3.n, Rd4.p);
            connect(Vs.n, g1.p);
            connect(g2.p, hall2.n);
            connect(Rd4.n, g3.p);
            connect(g3.p, OpI.p1);
            connect(g5.p, Rp2.n);
            connect(emf.n, hall1.p);
            connect(hall1.n, g4.p);
            connect(OpI.n2, power.n2);
            connect(OpI.p1, OpI.n2);
            connect(OpI.p1, diff.n2);
            connect(emf.flange, phi.flange);
            connect(emf.flange, speed.flange);
            connect(emf.flange, Jmotor.flange_a);
            connect(Jmotor.flange_b, flange_motor);
            connect(convert1.y, hall2.v_ref);
            connect(convert2.y, Vs.v_ref);
            connect(hall1.i, convert1.u);
            connect(hall1.i, current);
            connect(current_ref, convert2.u);
            connect(phi.phi, motorAngle);
            connect(speed.w, motorSpeed);
        }
        initial_equation {
            der(C.v) = 0.0;
            der(La.i) = 0.0;
        }
    }
}
