//! Joints made of elementary joints in series: universal, cylindrical and planar.

use super::{JOINT_STATE_PRIORITY, Prismatic, Revolute};
use crate::interfaces::Frame;
use crate::numeric::cross;
use crate::prelude::*;

/// Sub-joints do not compete for states: the composite joint's own variables do.
const NEVER: f64 = -100.0;

component! {
    /// A universal (Cardan) joint (MSL `Joints.Universal`): a rotation about `n_a`
    /// (resolved in `frame_a`) followed by a rotation about `n_b` (resolved in
    /// `frame_b`). With `iscut` the second rotation closes a kinematic loop.
    #[type_name = "MultiBody.Joints.Universal"]
    pub struct Universal {
        /// First axis, resolved in `frame_a`.
        structural n_a: [f64; 3] = [1.0, 0.0, 0.0];
        /// Second axis, resolved in `frame_b`.
        structural n_b: [f64; 3] = [0.0, 1.0, 0.0];
        /// Priority of the angles and speeds as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// The joint is a cut of a kinematic loop.
        structural iscut: bool = false;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Rotation about `n_a`.
        component revolute_a: Revolute = Revolute { n: self.n_a, state_priority: NEVER, ..Revolute::default() };
        /// Rotation about `n_b`.
        component revolute_b: Revolute = Revolute { n: self.n_b, state_priority: NEVER, iscut: self.iscut, ..Revolute::default() };
        /// Angle about `n_a` \[rad\].
        variable phi_a(state_priority = state_priority): Real;
        /// Angle about `n_b` \[rad\].
        variable phi_b(state_priority = state_priority): Real;
        /// `der(phi_a)` \[rad/s\].
        variable w_a(state_priority = state_priority): Real;
        /// `der(phi_b)` \[rad/s\].
        variable w_b(state_priority = state_priority): Real;
        /// `der(w_a)` \[rad/s2\].
        variable a_a: Real;
        /// `der(w_b)` \[rad/s2\].
        variable a_b: Real;
        equation {
            connect(frame_a, revolute_a.frame_a);
            connect(revolute_a.frame_b, revolute_b.frame_a);
            connect(revolute_b.frame_b, frame_b);
            phi_a = revolute_a.phi;
            phi_b = revolute_b.phi;
            w_a = revolute_a.w;
            w_b = revolute_b.w;
            a_a = der(w_a);
            a_b = der(w_b);
        }
    }
}

component! {
    /// A cylindrical joint (MSL `Joints.Cylindrical`): a translation along `n` and a
    /// rotation about it.
    #[type_name = "MultiBody.Joints.Cylindrical"]
    pub struct Cylindrical {
        /// Axis, resolved in `frame_a`.
        structural n: [f64; 3] = [1.0, 0.0, 0.0];
        /// Priority of the coordinates and speeds as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Translation along `n`.
        component prismatic: Prismatic = Prismatic { n: self.n, state_priority: NEVER, ..Prismatic::default() };
        /// Rotation about `n`.
        component revolute: Revolute = Revolute { n: self.n, state_priority: NEVER, ..Revolute::default() };
        /// Distance along `n` \[m\].
        variable s(state_priority = state_priority): Real;
        /// Angle about `n` \[rad\].
        variable phi(state_priority = state_priority): Real;
        /// `der(s)` \[m/s\].
        variable v(state_priority = state_priority): Real;
        /// `der(phi)` \[rad/s\].
        variable w(state_priority = state_priority): Real;
        /// `der(v)` \[m/s2\].
        variable a: Real;
        /// `der(w)` \[rad/s2\].
        variable wd: Real;
        equation {
            connect(frame_a, prismatic.frame_a);
            connect(prismatic.frame_b, revolute.frame_a);
            connect(revolute.frame_b, frame_b);
            s = prismatic.s;
            phi = revolute.phi;
            v = prismatic.v;
            w = revolute.w;
            a = der(v);
            wd = der(w);
        }
    }
}

component! {
    /// A planar joint (MSL `Joints.Planar`): translations along two axes of the plane
    /// with normal `n` (x along `n_x`) and a rotation about `n`.
    #[type_name = "MultiBody.Joints.Planar"]
    pub struct Planar {
        /// Normal of the plane, resolved in `frame_a`.
        structural n: [f64; 3] = [0.0, 0.0, 1.0];
        /// x direction in the plane, resolved in `frame_a`.
        structural n_x: [f64; 3] = [1.0, 0.0, 0.0];
        /// Priority of the coordinates and speeds as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Translation along x.
        component prismatic_x: Prismatic = Prismatic { n: cross(cross(self.n, self.n_x), self.n), state_priority: NEVER, ..Prismatic::default() };
        /// Translation along y.
        component prismatic_y: Prismatic = Prismatic { n: cross(self.n, self.n_x), state_priority: NEVER, ..Prismatic::default() };
        /// Rotation about `n`.
        component revolute: Revolute = Revolute { n: self.n, state_priority: NEVER, ..Revolute::default() };
        /// Distance along x \[m\].
        variable s_x(state_priority = state_priority): Real;
        /// Distance along y \[m\].
        variable s_y(state_priority = state_priority): Real;
        /// Angle about `n` \[rad\].
        variable phi(state_priority = state_priority): Real;
        /// `der(s_x)` \[m/s\].
        variable v_x(state_priority = state_priority): Real;
        /// `der(s_y)` \[m/s\].
        variable v_y(state_priority = state_priority): Real;
        /// `der(phi)` \[rad/s\].
        variable w(state_priority = state_priority): Real;
        /// `der(v_x)` \[m/s2\].
        variable a_x: Real;
        /// `der(v_y)` \[m/s2\].
        variable a_y: Real;
        /// `der(w)` \[rad/s2\].
        variable wd: Real;
        equation {
            connect(frame_a, prismatic_x.frame_a);
            connect(prismatic_x.frame_b, prismatic_y.frame_a);
            connect(prismatic_y.frame_b, revolute.frame_a);
            connect(revolute.frame_b, frame_b);
            s_x = prismatic_x.s;
            s_y = prismatic_y.s;
            phi = revolute.phi;
            v_x = prismatic_x.v;
            v_y = prismatic_y.v;
            w = revolute.w;
            a_x = der(v_x);
            a_y = der(v_y);
            wd = der(w);
        }
    }
}
