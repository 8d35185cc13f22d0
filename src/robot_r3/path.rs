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

component! {
    /// The synchronized reference motion of the robot's six axes from `angleBegDeg` to
    /// `angleEndDeg` (MSL `RobotR3.Utilities.PathPlanning6`, its bus signals as
    /// connectors: `angle_ref1` ... `angle_ref6`, `speed_ref1` ... `speed_ref6`): every
    /// axis starts and stops together, the slowest setting the pace; the simulation
    /// terminates `swingTime` after the move ends.
    #[type_name = "RobotR3.PathPlanning6"]
    pub struct PathPlanning6 {
        /// Start angles [deg], default 0.
        structural angleBegDeg: [f64; 6] = [0.0; 6];
        /// End angles [deg], default 1.
        structural angleEndDeg: [f64; 6] = [1.0; 6];
        /// Maximum axis speeds [rad/s], default 3.
        structural speedMax: [f64; 6] = [3.0; 6];
        /// Maximum axis accelerations [rad/s2], default 2.5.
        structural accMax: [f64; 6] = [2.5; 6];
        /// Start time of the movement [s], default 0.
        parameter startTime: f64 = 0.0;
        /// Time after the move at which the simulation terminates [s], default 0.5.
        parameter swingTime: f64 = 0.5;
        /// Reference angle of axis 1 [rad].
        connector angle_ref1: RealOutput;
        /// Reference speed of axis 1 [rad/s].
        connector speed_ref1: RealOutput;
        /// Reference angle of axis 2 [rad].
        connector angle_ref2: RealOutput;
        /// Reference speed of axis 2 [rad/s].
        connector speed_ref2: RealOutput;
        /// Reference angle of axis 3 [rad].
        connector angle_ref3: RealOutput;
        /// Reference speed of axis 3 [rad/s].
        connector speed_ref3: RealOutput;
        /// Reference angle of axis 4 [rad].
        connector angle_ref4: RealOutput;
        /// Reference speed of axis 4 [rad/s].
        connector speed_ref4: RealOutput;
        /// Reference angle of axis 5 [rad].
        connector angle_ref5: RealOutput;
        /// Reference speed of axis 5 [rad/s].
        connector speed_ref5: RealOutput;
        /// Reference angle of axis 6 [rad].
        connector angle_ref6: RealOutput;
        /// Reference speed of axis 6 [rad/s].
        connector speed_ref6: RealOutput;
        /// The reference motion of axis 1 (MSL `path`, its element 1).
        component path1: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 0,
            start_time: self.startTime,
        };
        /// The reference motion of axis 2 (MSL `path`, its element 2).
        component path2: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 1,
            start_time: self.startTime,
        };
        /// The reference motion of axis 3 (MSL `path`, its element 3).
        component path3: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 2,
            start_time: self.startTime,
        };
        /// The reference motion of axis 4 (MSL `path`, its element 4).
        component path4: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 3,
            start_time: self.startTime,
        };
        /// The reference motion of axis 5 (MSL `path`, its element 5).
        component path5: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 4,
            start_time: self.startTime,
        };
        /// The reference motion of axis 6 (MSL `path`, its element 6).
        component path6: KinematicPTP2 = KinematicPTP2 {
            q_begin: self.angleBegDeg.iter().map(|a| a.to_radians()).collect(),
            q_end: self.angleEndDeg.iter().map(|a| a.to_radians()).collect(),
            qd_max: self.speedMax.to_vec(),
            qdd_max: self.accMax.to_vec(),
            axis: 5,
            start_time: self.startTime,
        };
        equation {
            connect(path1.q, angle_ref1);
            connect(path1.qd, speed_ref1);
            connect(path2.q, angle_ref2);
            connect(path2.qd, speed_ref2);
            connect(path3.q, angle_ref3);
            connect(path3.qd, speed_ref3);
            connect(path4.q, angle_ref4);
            connect(path4.qd, speed_ref4);
            connect(path5.q, angle_ref5);
            connect(path5.qd, speed_ref5);
            connect(path6.q, angle_ref6);
            connect(path6.qd, speed_ref6);
            when ge(time, path1.end_time + swingTime) {
                terminate("PathPlanning6: end condition reached");
            }
        }
    }
}
