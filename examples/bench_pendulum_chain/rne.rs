//! The baseline of the pendulum-chain benchmark: a hand-written residual in minimal
//! coordinates, `0 = [q' - v; tau(q, v, v')]`, with the inverse dynamics `tau` by the
//! recursive Newton-Euler equations in 3-D (link frames, rotation matrices, cross
//! products), written the way one would in C for a serial chain of revolute joints.

use multibody_core::solve::ida::{DaeFunctions, EvalError};

pub(crate) type V3 = [f64; 3];
pub(crate) type M3 = [[f64; 3]; 3];

pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn scale(s: f64, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// `R v`.
pub(crate) fn mul(r: &M3, v: V3) -> V3 {
    [dot(r[0], v), dot(r[1], v), dot(r[2], v)]
}
/// `R^T v`.
pub(crate) fn mul_t(r: &M3, v: V3) -> V3 {
    [
        r[0][0] * v[0] + r[1][0] * v[1] + r[2][0] * v[2],
        r[0][1] * v[0] + r[1][1] * v[1] + r[2][1] * v[2],
        r[0][2] * v[0] + r[1][2] * v[1] + r[2][2] * v[2],
    ]
}
/// The rotation from a joint's frame_a to its frame_b by angle `q` about the unit axis
/// `n`: `v_b = R v_a` with `R = n n^T + (I - n n^T) cos q - [n x] sin q`.
pub(crate) fn rotation(n: V3, q: f64) -> M3 {
    let (s, c) = q.sin_cos();
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let id = if i == j { 1.0 } else { 0.0 };
            r[i][j] = n[i] * n[j] + (id - n[i] * n[j]) * c;
        }
    }
    // -[n x] s
    r[0][1] += n[2] * s;
    r[0][2] -= n[1] * s;
    r[1][0] -= n[2] * s;
    r[1][2] += n[0] * s;
    r[2][0] += n[1] * s;
    r[2][1] -= n[0] * s;
    r
}

/// One link: joint axis (in the joint's frame), vector from the joint to the next joint
/// and to the centre of mass (in the link frame), mass and inertia about the centre of
/// mass.
#[derive(Clone, Copy, Debug)]
pub struct Link {
    pub axis: V3,
    pub r: V3,
    pub r_cm: V3,
    pub m: f64,
    pub inertia: M3,
}

/// The chain and its scratch memory.
pub struct Rne {
    pub links: Vec<Link>,
    /// Gravity acceleration in the world frame.
    pub g: V3,
    rot: Vec<M3>,
    omega: Vec<V3>,
    force: Vec<V3>,
    moment: Vec<V3>,
}

impl Rne {
    pub fn new(links: Vec<Link>, g: V3) -> Rne {
        let n = links.len();
        Rne {
            links,
            g,
            rot: vec![[[0.0; 3]; 3]; n],
            omega: vec![[0.0; 3]; n],
            force: vec![[0.0; 3]; n],
            moment: vec![[0.0; 3]; n],
        }
    }

    /// Joint torques that produce the accelerations `a` at positions `q` and velocities
    /// `v` (the base accelerates with `-g`, which adds gravity to every link).
    pub fn torques(&mut self, q: &[f64], v: &[f64], a: &[f64], tau: &mut [f64]) {
        let n = self.links.len();
        let (mut w, mut dw) = ([0.0; 3], [0.0; 3]);
        let mut acc = scale(-1.0, self.g); // acceleration of the joint origin
        let mut prev_r = [0.0; 3];
        for i in 0..n {
            let l = self.links[i];
            let rot = rotation(l.axis, q[i]);
            // Acceleration of this joint's origin (the previous link's frame_b).
            let acc_joint = add(acc, add(cross(dw, prev_r), cross(w, cross(w, prev_r))));
            let wj = scale(v[i], l.axis);
            let w_i = add(mul(&rot, w), wj);
            let dw_i = add(
                add(mul(&rot, dw), scale(a[i], l.axis)),
                cross(mul(&rot, w), wj),
            );
            let acc_i = mul(&rot, acc_joint);
            let acc_cm = add(
                acc_i,
                add(cross(dw_i, l.r_cm), cross(w_i, cross(w_i, l.r_cm))),
            );
            self.force[i] = scale(l.m, acc_cm);
            let iw = mul(&l.inertia, w_i);
            self.moment[i] = add(mul(&l.inertia, dw_i), cross(w_i, iw));
            self.rot[i] = rot;
            self.omega[i] = w_i;
            w = w_i;
            dw = dw_i;
            acc = acc_i;
            prev_r = l.r;
        }
        let (mut f_next, mut n_next) = ([0.0; 3], [0.0; 3]);
        for i in (0..n).rev() {
            let l = self.links[i];
            // Child wrench resolved in this link's frame.
            let (fc, nc) = if i + 1 < n {
                (
                    mul_t(&self.rot[i + 1], f_next),
                    mul_t(&self.rot[i + 1], n_next),
                )
            } else {
                ([0.0; 3], [0.0; 3])
            };
            let f = add(self.force[i], fc);
            let moment = add(
                add(self.moment[i], cross(l.r_cm, self.force[i])),
                add(nc, cross(l.r, fc)),
            );
            tau[i] = dot(l.axis, moment);
            f_next = f;
            n_next = moment;
        }
    }
}

impl DaeFunctions for Rne {
    fn len(&self) -> usize {
        2 * self.links.len()
    }
    fn residual(
        &mut self,
        _t: f64,
        y: &[f64],
        yp: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        let n = self.links.len();
        for k in 0..n {
            out[k] = yp[k] - y[n + k];
        }
        let (q, v) = y.split_at(n);
        let (_, tau) = out.split_at_mut(n);
        self.torques(q, v, &yp[n..], tau);
        Ok(())
    }
    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        None
    }
    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _yp: &[f64],
        _cj: f64,
        _values: &mut [f64],
    ) -> Result<(), EvalError> {
        Err(EvalError {
            message: "the baseline uses IDA's difference-quotient Jacobian".into(),
            recoverable: false,
        })
    }
}
