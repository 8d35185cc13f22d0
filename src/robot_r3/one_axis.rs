//! MSL's one-axis test of the robot.

use super::{AxisType1, PathPlanning1};
use crate::prelude::*;
use crate::rotational::Inertia;

component! {
    /// One axis of the robot moving a load of `mLoad` from 0 to 120 degrees (MSL
    /// `RobotR3.OneAxis`); it terminates half a second after the move, at 1.4981317 s.
    /// The axis starts at rest with its friction stuck (see `AxisType1::start_stuck`).
    #[type_name = "RobotR3.OneAxis"]
    pub struct OneAxis {
        /// Mass of the load [kg], default 15.
        parameter mLoad(min = 0.0): f64 = 15.0;
        /// Gain of the position controller [1], default 5.
        parameter kp: f64 = 5.0;
        /// Gain of the speed controller [1], default 0.5.
        parameter ks: f64 = 0.5;
        /// Time constant of the speed controller's integrator [s], default 0.05.
        parameter Ts: f64 = 0.05;
        /// The axis.
        component axis: AxisType1 = AxisType1 {
            w: 5500.0,
            ratio: 210.0,
            c: 8.0,
            cd: 0.01,
            Rv0: 0.5,
            Rv1: 0.1 / 130.0,
            kp: self.kp,
            ks: self.ks,
            Ts: self.Ts,
            start_stuck: true,
            ..AxisType1::default()
        };
        /// The load inertia, 1.3 mLoad.
        component load: Inertia = Inertia { J: 1.3 * self.mLoad, ..Inertia::default() };
        /// The reference motion of the axis.
        component pathPlanning: PathPlanning1 = PathPlanning1 {
            swingTime: 0.5,
            angleBegDeg: 0.0,
            angleEndDeg: 120.0,
            speedMax: 3.0,
            accMax: 10.0,
            ..PathPlanning1::default()
        };
        equation {
            connect(axis.flange, load.flange_a);
            connect(pathPlanning.angle_ref, axis.angle_ref);
            connect(pathPlanning.speed_ref, axis.speed_ref);
        }
    }
}
