//! The robot's mechanical structure.

use crate::interfaces::Frame;
use crate::joints::Revolute;
use crate::parts::BodyShape;
use crate::prelude::*;
use crate::rotational::Flange;

component! {
    /// The six-joint arm of the r3 robot (MSL `RobotR3.Utilities.MechanicalStructure`):
    /// a serial chain of revolute joints about y, x, x, y, x, y, driven through their
    /// axis flanges, with MSL's bodies and a load of `mLoad` at `rLoad` from the last
    /// flange, on a base `frame_a` (MSL's structure has a world of its own, with gravity
    /// 9.81 along -y, where [`super::FullRobot`] connects it).
    #[type_name = "RobotR3.MechanicalStructure"]
    pub struct MechanicalStructure {
        /// Mass of the load [kg], default 15.
        structural mLoad: f64 = 15.0;
        /// Position of the load's centre of mass from the last flange [m], default
        /// {0, 0.25, 0}.
        structural rLoad: [f64; 3] = [0.0, 0.25, 0.0];
        /// The robot's base, fixed to the world.
        connector frame_a: Frame;
        /// Drive flange of joint 1.
        connector axis1: Flange;
        /// Drive flange of joint 2.
        connector axis2: Flange;
        /// Drive flange of joint 3.
        connector axis3: Flange;
        /// Drive flange of joint 4.
        connector axis4: Flange;
        /// Drive flange of joint 5.
        connector axis5: Flange;
        /// Drive flange of joint 6.
        connector axis6: Flange;
        /// Joint 1 (about y).
        component r1: Revolute = Revolute { n: [0.0, 1.0, 0.0], axisflange: true, ..Revolute::default() };
        /// Joint 2 (about x).
        component r2: Revolute = Revolute { n: [1.0, 0.0, 0.0], axisflange: true, ..Revolute::default() };
        /// Joint 3 (about x).
        component r3: Revolute = Revolute { n: [1.0, 0.0, 0.0], axisflange: true, ..Revolute::default() };
        /// Joint 4 (about y).
        component r4: Revolute = Revolute { n: [0.0, 1.0, 0.0], axisflange: true, ..Revolute::default() };
        /// Joint 5 (about x).
        component r5: Revolute = Revolute { n: [1.0, 0.0, 0.0], axisflange: true, ..Revolute::default() };
        /// Joint 6 (about y).
        component r6: Revolute = Revolute { n: [0.0, 1.0, 0.0], axisflange: true, ..Revolute::default() };
        /// The base.
        component b0: BodyShape = BodyShape {
            r: [0.0, 0.351, 0.0], r_CM: Some([0.0, 0.0, 0.0]), m: 1.0, color: [0.0, 0.0, 1.0],
            ..BodyShape::default()
        };
        /// Link 1.
        component b1: BodyShape = BodyShape {
            r: [0.0, 0.324, 0.3], r_CM: Some([0.0, 0.0, 0.0]), m: 1.0,
            I_diag: [0.001, 1.16, 0.001], color: [1.0, 0.0, 0.0], ..BodyShape::default()
        };
        /// Link 2 (the upper arm).
        component b2: BodyShape = BodyShape {
            r: [0.0, 0.65, 0.0], r_CM: Some([0.172, 0.205, 0.0]), m: 56.5,
            I_diag: [2.58, 0.64, 2.73], I_offdiag: [-0.46, 0.0, 0.0],
            color: [1.0, 0.7, 0.0], ..BodyShape::default()
        };
        /// Link 3.
        component b3: BodyShape = BodyShape {
            r: [0.0, 0.414, -0.155], r_CM: Some([0.064, -0.034, 0.0]), m: 26.4,
            I_diag: [0.279, 0.245, 0.413], I_offdiag: [-0.070, 0.0, 0.0],
            color: [1.0, 0.0, 0.0], ..BodyShape::default()
        };
        /// Link 4 (the forearm).
        component b4: BodyShape = BodyShape {
            r: [0.0, 0.186, 0.0], r_CM: Some([0.0, 0.0, 0.0]), m: 28.7,
            I_diag: [1.67, 0.081, 1.67], color: [1.0, 0.7, 0.0], ..BodyShape::default()
        };
        /// Link 5.
        component b5: BodyShape = BodyShape {
            r: [0.0, 0.125, 0.0], r_CM: Some([0.0, 0.0, 0.0]), m: 5.2,
            I_diag: [1.25, 0.81, 1.53], color: [0.0, 0.0, 1.0], ..BodyShape::default()
        };
        /// Link 6 (the flange).
        component b6: BodyShape = BodyShape {
            r: [0.0, 0.0, 0.0], r_CM: Some([0.05, 0.05, 0.05]), m: 0.5,
            color: [0.0, 0.0, 1.0], ..BodyShape::default()
        };
        /// The load.
        component load: BodyShape = BodyShape {
            r: [0.0, 0.0, 0.0], r_CM: Some(self.rLoad), m: self.mLoad,
            color: [1.0, 0.0, 0.0], ..BodyShape::default()
        };
        equation {
            connect(load.frame_a, b6.frame_b);
            connect(frame_a, b0.frame_a);
            connect(b0.frame_b, r1.frame_a);
            connect(b1.frame_b, r2.frame_a);
            connect(r1.frame_b, b1.frame_a);
            connect(r2.frame_b, b2.frame_a);
            connect(b2.frame_b, r3.frame_a);
            connect(r2.axis, axis2);
            connect(r1.axis, axis1);
            connect(r3.frame_b, b3.frame_a);
            connect(b3.frame_b, r4.frame_a);
            connect(r3.axis, axis3);
            connect(r4.axis, axis4);
            connect(r4.frame_b, b4.frame_a);
            connect(b4.frame_b, r5.frame_a);
            connect(r5.axis, axis5);
            connect(r5.frame_b, b5.frame_a);
            connect(b5.frame_b, r6.frame_a);
            connect(r6.axis, axis6);
            connect(r6.frame_b, b6.frame_a);
        }
    }
}
