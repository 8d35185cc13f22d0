//! The robot's path planning.

use crate::blocks::{KinematicPTP2, RealOutput};
use crate::prelude::*;

component! {
    /// The reference motion of one axis from `angleBegDeg` to `angleEndDeg` (MSL
    /// `RobotR3.Utilities.PathPlanning1`); the simulation terminates `swingTime` after
    /// the move ends.
    #[type_name = "RobotR3.PathPlanning1"]
    pub struct PathPlanning1 {
        /// Start angle [deg], default 0.
        structural angleBegDeg: f64 = 0.0;
        /// End angle [deg], default 1.
        structural angleEndDeg: f64 = 1.0;
        /// Maximum axis speed [rad/s], default 3.
        structural speedMax: f64 = 3.0;
        /// Maximum axis acceleration [rad/s2], default 2.5.
        structural accMax: f64 = 2.5;
        /// Start time of the movement [s], default 0.
        parameter startTime: f64 = 0.0;
        /// Time after the move at which the simulation terminates [s], default 0.5.
        parameter swingTime: f64 = 0.5;
        /// Reference angle [rad].
        connector angle_ref: RealOutput;
        /// Reference speed [rad/s].
        connector speed_ref: RealOutput;
        /// Reference acceleration [rad/s2].
        connector acceleration_ref: RealOutput;
        /// 1 while the axis moves.
        connector motion_ref: RealOutput;
        /// The reference motion (MSL `path`).
        component ptp: KinematicPTP2 = KinematicPTP2 {
            q_begin: vec![self.angleBegDeg.to_radians()],
            q_end: vec![self.angleEndDeg.to_radians()],
            qd_max: vec![self.speedMax],
            qdd_max: vec![self.accMax],
            axis: 0,
            start_time: self.startTime,
        };
        equation {
            connect(ptp.q, angle_ref);
            connect(ptp.qd, speed_ref);
            connect(ptp.qdd, acceleration_ref);
            connect(ptp.moving, motion_ref);
            when ge(time, ptp.end_time + swingTime) {
                terminate("PathPlanning1: end condition reached");
            }
        }
    }
}
