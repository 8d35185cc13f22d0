//! The 1-D test models shared by the analytic, algebraic-loop and golden-structure
//! tests (each test file includes this module and uses what it needs).

#![allow(dead_code)]

use multibody::electrical::{Capacitor, ConstantVoltage, Ground, OnePort, Resistor};
use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia, Spring, SpringDamper};
use multibody::translational;

system! {
    /// A mass `m` on a spring `c` and a damper `d` to a fixed point, starting at 0.1 m.
    pub fn mass_spring_damper(m: f64, c: f64, d: f64) -> MassSpringDamper {
        name: "mass_spring";
        fixed = translational::Fixed::default();
        spring = translational::Spring { c };
        damper = translational::Damper { d };
        mass = translational::Mass { m, s_start: 0.1 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, mass.flange_a);
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, mass.flange_a);
    }
}

system! {
    /// A 10 V source charging 1 mF through 1 kOhm.
    pub fn rc_circuit() -> RcCircuit {
        name: "rc";
        source = ConstantVoltage { V: 10.0 };
        resistor = Resistor { R: 1000.0 };
        capacitor = Capacitor { C: 1e-3 };
        ground = Ground::default();
        connect(source.p, resistor.p);
        connect(resistor.n, capacitor.p);
        connect(capacitor.n, source.n);
        connect(source.n, ground.p);
    }
}

system! {
    /// Two free inertias `j1`, `j2` coupled by a spring-damper `c`, `d`.
    pub fn two_inertias(j1: f64, j2: f64, c: f64, d: f64) -> TwoInertias {
        name: "chain";
        inertia1 = Inertia { J: j1 };
        coupling = SpringDamper { c, d };
        inertia2 = Inertia { J: j2 };
        connect(inertia1.flange_b, coupling.flange_a);
        connect(coupling.flange_b, inertia2.flange_a);
    }
}

system! {
    /// A unit inertia on a spring `c` to a fixed point, starting at 1 rad.
    pub fn undamped_oscillator(c: f64) -> UndampedOscillator {
        name: "undamped";
        fixed = Fixed::default();
        spring = Spring { c };
        inertia = Inertia { J: 1.0, phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    }
}

system! {
    /// A Wheatstone bridge driven by 10 V with a capacitor across its outputs.
    pub fn bridge() -> Bridge {
        name: "bridge";
        source = ConstantVoltage { V: 10.0 };
        r1 = Resistor { R: 100.0 };
        r2 = Resistor { R: 200.0 };
        r3 = Resistor { R: 300.0 };
        r4 = Resistor { R: 400.0 };
        r5 = Resistor { R: 500.0 };
        c = Capacitor { C: 1e-3 };
        ground = Ground::default();
        // top node: source.p; left branch r1 (top-a), r3 (a-bottom); right r2 (top-b),
        // r4 (b-bottom); r5 and the capacitor bridge a and b.
        connect(source.p, r1.p);
        connect(source.p, r2.p);
        connect(r1.n, r3.p);
        connect(r2.n, r4.p);
        connect(r3.n, source.n);
        connect(r4.n, source.n);
        connect(r1.n, r5.p);
        connect(r5.n, r2.n);
        connect(r1.n, c.p);
        connect(c.n, r2.n);
        connect(source.n, ground.p);
    }
}

component! {
    /// A resistor with a cubic characteristic `v = R0 i + a i^3`.
    pub struct CubicResistor {
        /// Linear resistance [Ohm].
        parameter R0: f64 = 1.0;
        /// Cubic coefficient [V/A3].
        parameter a: f64 = 1.0;
        extends OnePort { p, n, v, i };
        equation {
            v = R0 * i + a * i * i * i;
        }
    }
}

system! {
    /// 5 V through a cubic resistor (R0 = 1, a = 2) into 2 Ohm parallel to 0.1 F: a
    /// nonlinear algebraic loop.
    pub fn cubic_loop() -> CubicLoop {
        name: "cubic_loop";
        source = ConstantVoltage { V: 5.0 };
        nonlinear = CubicResistor { R0: 1.0, a: 2.0 };
        load = Resistor { R: 2.0 };
        c = Capacitor { C: 0.1 };
        ground = Ground::default();
        connect(source.p, nonlinear.p);
        connect(nonlinear.n, load.p);
        connect(load.n, source.n);
        connect(nonlinear.n, c.p);
        connect(c.n, source.n);
        connect(source.n, ground.p);
    }
}
