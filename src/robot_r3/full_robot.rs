//! MSL's full robot.

use super::{AxisType1, AxisType2, MechanicalStructure, PathPlanning6};
use crate::prelude::*;
use crate::world::World;

component! {
    /// The six-axis robot with path planning, controllers, motors, gearboxes with
    /// friction and the arm (MSL `RobotR3.FullRobot`): it moves from
    /// {-60, 20, 90, 0, -110, 0} to {60, -70, -35, 45, 110, 45} degrees and terminates
    /// half a second after the move, at 1.8560450 s. Every axis starts at rest with its
    /// friction stuck and the motors holding the load (see `AxisType1::start_stuck`).
    #[type_name = "RobotR3.FullRobot"]
    pub struct FullRobot {
        /// Mass of the load [kg], default 15.
        structural mLoad: f64 = 15.0;
        /// Position of the load's centre of mass from the last flange [m], default
        /// {0.1, 0.25, 0.1}.
        structural rLoad: [f64; 3] = [0.1, 0.25, 0.1];
        /// Gravity acceleration [m/s2], default 9.81.
        structural g: f64 = 9.81;
        /// Gain of the position controllers [1], default 5.
        parameter kp: f64 = 5.0;
        /// Gain of the speed controllers [1], default 0.5.
        parameter ks: f64 = 0.5;
        /// Time constant of the speed controllers' integrators [s], default 0.05.
        parameter Ts: f64 = 0.05;
        /// The world: gravity `g` along -y.
        component world: World = World { g: self.g, n: [0.0, -1.0, 0.0], ..World::default() };
        /// The arm.
        component mechanics: MechanicalStructure = MechanicalStructure {
            mLoad: self.mLoad, rLoad: self.rLoad,
        };
        /// The reference motion.
        component pathPlanning: PathPlanning6 = PathPlanning6 {
            angleBegDeg: [-60.0, 20.0, 90.0, 0.0, -110.0, 0.0],
            angleEndDeg: [60.0, -70.0, -35.0, 45.0, 110.0, 45.0],
            speedMax: [3.0, 1.5, 5.0, 3.1, 3.1, 4.1],
            accMax: [15.0, 15.0, 15.0, 60.0, 60.0, 60.0],
            startTime: 0.0,
            swingTime: 0.5,
        };
        /// Axis 1.
        component axis1: AxisType1 = AxisType1 {
            w: 4590.0, ratio: -105.0, c: 43.0, cd: 0.005, Rv0: 0.4, Rv1: 0.13 / 160.0,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType1::default()
        };
        /// Axis 2.
        component axis2: AxisType1 = AxisType1 {
            w: 5500.0, ratio: 210.0, c: 8.0, cd: 0.01, Rv0: 0.5, Rv1: 0.1 / 130.0,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType1::default()
        };
        /// Axis 3.
        component axis3: AxisType1 = AxisType1 {
            w: 5500.0, ratio: 60.0, c: 58.0, cd: 0.04, Rv0: 0.7, Rv1: 0.2 / 130.0,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType1::default()
        };
        /// Axis 4.
        component axis4: AxisType2 = AxisType2 {
            k: 0.2365, w: 6250.0, D: 0.55, J: 1.6e-4, ratio: -99.0, Rv0: 21.8, Rv1: 9.8, peak: 26.7 / 21.8,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType2::default()
        };
        /// Axis 5.
        component axis5: AxisType2 = AxisType2 {
            k: 0.2608, w: 6250.0, D: 0.55, J: 1.8e-4, ratio: 79.2, Rv0: 30.1, Rv1: 0.03, peak: 39.6 / 30.1,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType2::default()
        };
        /// Axis 6.
        component axis6: AxisType2 = AxisType2 {
            k: 0.0842, w: 7400.0, D: 0.27, J: 4.3e-5, ratio: -99.0, Rv0: 10.9, Rv1: 3.92, peak: 16.8 / 10.9,
            kp: self.kp, ks: self.ks, Ts: self.Ts, start_stuck: true, ..AxisType2::default()
        };
        equation {
            connect(world.frame_b, mechanics.frame_a);
            connect(axis1.flange, mechanics.axis1);
            connect(pathPlanning.angle_ref1, axis1.angle_ref);
            connect(pathPlanning.speed_ref1, axis1.speed_ref);
            connect(axis2.flange, mechanics.axis2);
            connect(pathPlanning.angle_ref2, axis2.angle_ref);
            connect(pathPlanning.speed_ref2, axis2.speed_ref);
            connect(axis3.flange, mechanics.axis3);
            connect(pathPlanning.angle_ref3, axis3.angle_ref);
            connect(pathPlanning.speed_ref3, axis3.speed_ref);
            connect(axis4.flange, mechanics.axis4);
            connect(pathPlanning.angle_ref4, axis4.angle_ref);
            connect(pathPlanning.speed_ref4, axis4.speed_ref);
            connect(axis5.flange, mechanics.axis5);
            connect(pathPlanning.angle_ref5, axis5.angle_ref);
            connect(pathPlanning.speed_ref5, axis5.speed_ref);
            connect(axis6.flange, mechanics.axis6);
            connect(pathPlanning.angle_ref6, axis6.angle_ref);
            connect(pathPlanning.speed_ref6, axis6.speed_ref);
        }
    }
}
