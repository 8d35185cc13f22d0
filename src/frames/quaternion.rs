//! Quaternions `Q = {n sin(phi/2), cos(phi/2)}` (scalar last, as MSL), used by free
//! bodies and joints that need orientation states without singularities.

use multibody_core::expr::{Expr, Mat3, Vec3};

use super::orientation::Orientation;

/// A quaternion `[q1, q2, q3, q4]`: vector part first, scalar part last.
pub type Quaternion = [Expr; 4];

/// The transformation matrix of a unit quaternion:
/// `T = (2 q4^2 - 1) I + 2 qv qv' - 2 q4 skew(qv)`.
pub fn quaternion_to_t(q: Quaternion) -> Mat3 {
    let qv = Vec3([q[0], q[1], q[2]]);
    Mat3::identity().scale(q[3] * q[3] * 2.0 - 1.0) + qv.outer(qv).scale(2.0)
        - qv.skew().scale(q[3] * 2.0)
}

/// The angular velocity (resolved in frame 2) from a quaternion and its derivative:
/// `w = 2 G2(Q) der(Q)`.
pub fn quaternion_angular_velocity2(q: Quaternion, dq: Quaternion) -> Vec3 {
    let g = [
        [q[3], q[2], -q[1], -q[0]],
        [-q[2], q[3], q[0], -q[1]],
        [q[1], -q[0], q[3], -q[2]],
    ];
    let row = |r: [Expr; 4]| (r[0] * dq[0] + r[1] * dq[1] + r[2] * dq[2] + r[3] * dq[3]) * 2.0;
    Vec3([row(g[0]), row(g[1]), row(g[2])])
}

/// The orientation of a unit quaternion with angular velocity `w` (resolved in frame 2).
pub fn from_q(q: Quaternion, w: Vec3) -> Orientation {
    Orientation::new(quaternion_to_t(q), w)
}

/// The unit quaternion of a rotation matrix (numeric), with the sign that makes it
/// nearest `guess` (`Q . guess >= 0`).
pub fn to_q(t: [[f64; 3]; 3], guess: [f64; 4]) -> [f64; 4] {
    let (t11, t12, t13) = (t[0][0], t[0][1], t[0][2]);
    let (t21, t22, t23) = (t[1][0], t[1][1], t[1][2]);
    let (t31, t32, t33) = (t[2][0], t[2][1], t[2][2]);
    let (s, mut q) = if t33 < 0.0 {
        if t11 > t22 {
            let s = 1.0 + t11 - t22 - t33;
            (s, [s, t12 + t21, t31 + t13, t23 - t32])
        } else {
            let s = 1.0 - t11 + t22 - t33;
            (s, [t12 + t21, s, t23 + t32, t31 - t13])
        }
    } else if t11 < -t22 {
        let s = 1.0 - t11 - t22 + t33;
        (s, [t31 + t13, t23 + t32, s, t12 - t21])
    } else {
        let s = 1.0 + t11 + t22 + t33;
        (s, [t23 - t32, t31 - t13, t12 - t21, s])
    };
    let k = 0.5 / s.sqrt();
    for x in q.iter_mut() {
        *x *= k;
    }
    let d: f64 = (0..4).map(|i| q[i] * guess[i]).sum();
    if d < 0.0 {
        for x in q.iter_mut() {
            *x = -*x;
        }
    }
    q
}
