//! The seed's DC motor circuit: a voltage source driven by a speed controller feeds a
//! resistor, an inductor and an EMF; the motor inertia drives a load inertia through an
//! ideal gear, and a speed sensor closes the loop.
//!
//! `cargo run --release --example dc_motor` writes `dc_motor.png`.

use multibody::blocks::{ControllerType, LimPID, Step};
use multibody::electrical::{EMF, Ground, Inductor, Resistor, SignalVoltage};
use multibody::prelude::*;
use multibody::rotational::{Fixed, IdealGear, Inertia, SpeedSensor};

system! {
    /// The model: reference load speed 1 rad/s from t = 0.5 s.
    pub fn dc_motor() -> DcMotor {
        name: "dc_motor";
        resistor = Resistor { R: 10.0 };
        inductor = Inductor { L: 0.05 };
        emf = EMF { k: 1.0, use_support: true };
        source = SignalVoltage::default();
        ground = Ground::default();
        controller = LimPID {
            controller_type: ControllerType::PI,
            k: 100.0,
            Ti: 0.1,
            y_max: 200.0,
            y_min: -200.0,
        };
        motor_inertia = Inertia { J: 1e-3 };
        gear = IdealGear { ratio: 100.0 };
        fixed = Fixed::default();
        load_inertia = Inertia { J: 5.0 };
        sensor = SpeedSensor::default();
        reference = Step { height: 1.0, start_time: 0.5 };
        connect(source.p, resistor.p);
        connect(resistor.n, inductor.p);
        connect(inductor.n, emf.p);
        connect(emf.n, source.n);
        connect(source.n, ground.p);
        connect(fixed.flange, emf.support);
        connect(emf.flange, motor_inertia.flange_a);
        connect(motor_inertia.flange_b, gear.flange_a);
        connect(gear.flange_b, load_inertia.flange_a);
        connect(load_inertia.flange_b, sensor.flange);
        connect(reference.y, controller.u_s);
        connect(sensor.w, controller.u_m);
        connect(controller.y, source.v_ref);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = dc_motor();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    let sol = DaeProblem::builder(&ssys, (0.0, 3.0))
        .build()?
        .solve(&SolverOptions::default())?;
    println!(
        "load speed at 3 s: {:.6} rad/s (reference 1), {} steps",
        sol.final_value(model.load_inertia.w)?,
        sol.statistics().steps
    );
    Figure::new()
        .title("DC motor with a PI speed controller")
        .panel(&sol, &[model.reference.y.into(), model.load_inertia.w])
        .panel(&sol, &[model.controller.y])
        .panel(&sol, &[model.inductor.i])
        .options(PlotOptions {
            columns: 3,
            ..PlotOptions::default()
        })
        .save("dc_motor.png")?;
    println!("wrote dc_motor.png");
    Ok(())
}
