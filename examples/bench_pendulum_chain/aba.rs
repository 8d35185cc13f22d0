//! The baseline for the explicit methods of the benchmark: the forward dynamics
//! `v' = qdd(q, v)` of the chain of [`rne`](super::rne) (same links, joint rotations,
//! frames and gravity, no joint torques) by Featherstone's articulated-body algorithm
//! (ABA) in 3-D, O(N), written the way one would in C.
//!
//! Spatial quantities are pairs of 3-vectors (angular, linear) about a link's origin (its
//! joint) in the link frame; accelerations are the classical ones of the origin, as in
//! `rne.rs`, so the velocity-product terms depend on the angular velocities only. An
//! articulated inertia is the symmetric 6x6 matrix `[[A, B], [B^T, M]]` kept as its three
//! 3x3 blocks.

use multibody_core::solve::ida::EvalError;
use multibody_core::solve::ode::OdeFunctions;

use super::rne::{Link, M3, V3, add, cross, dot, mul, mul_t, rotation, scale};

/// `A B`.
fn mm(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}
/// `A^T`.
fn transpose(a: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[j][i];
        }
    }
    c
}
/// `R^T X R`: a block of an inertia in frame_b resolved in frame_a.
fn rot_t(r: &M3, x: &M3) -> M3 {
    mm(&transpose(r), &mm(x, r))
}
/// `[r x]`.
fn skew(r: V3) -> M3 {
    [[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]]
}
/// `A + s B`.
fn add_m(a: &M3, s: f64, b: &M3) -> M3 {
    let mut c = *a;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] += s * b[i][j];
        }
    }
    c
}
/// `X + s a b^T`.
fn add_outer(x: &M3, s: f64, a: V3, b: V3) -> M3 {
    let mut c = *x;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] += s * a[i] * b[j];
        }
    }
    c
}

/// Per-link scratch of one evaluation.
#[derive(Clone, Copy, Default)]
struct Work {
    /// The joint rotation, `v_b = R v_a`.
    rot: M3,
    /// Velocity-product accelerations (angular, of the origin) the joint adds.
    c_w: V3,
    c_a: V3,
    /// Articulated inertia blocks `[A, B, M]` and bias wrench (moment, force).
    ia: [M3; 3],
    p_n: V3,
    p_f: V3,
    /// `U = I^A S` with `S = (axis, 0)`, `D = S^T U`, `u = tau - S^T p` (tau = 0).
    u_n: V3,
    u_f: V3,
    d: f64,
    u: f64,
}

/// The chain of [`Link`]s of [`Rne`](super::rne::Rne) and the scratch memory of the
/// articulated-body algorithm.
pub struct Aba {
    /// The links, base first.
    pub links: Vec<Link>,
    /// Gravity acceleration in the world frame.
    pub g: V3,
    work: Vec<Work>,
}

impl Aba {
    /// The chain `links` (base first) under gravity `g` (world frame), as [`Rne::new`].
    ///
    /// [`Rne::new`]: super::rne::Rne::new
    pub fn new(links: Vec<Link>, g: V3) -> Aba {
        let n = links.len();
        Aba {
            links,
            g,
            work: vec![Work::default(); n],
        }
    }

    /// Joint accelerations `qdd` at positions `q` and velocities `v` with no joint
    /// torques: `M(q) qdd + h(q, v) = 0`, i.e. `Rne::torques(q, v, qdd) = 0`.
    pub fn accelerations(&mut self, q: &[f64], v: &[f64], qdd: &mut [f64]) {
        let n = self.links.len();
        // Pass 1, base to tip: rotations, angular velocities, velocity-product terms,
        // rigid-body inertias about the joint and their bias wrenches.
        let (mut w, mut prev_r) = ([0.0; 3], [0.0; 3]);
        for i in 0..n {
            let l = self.links[i];
            let wk = &mut self.work[i];
            wk.rot = rotation(l.axis, q[i]);
            let w_rot = mul(&wk.rot, w);
            let wj = scale(v[i], l.axis);
            wk.c_w = cross(w_rot, wj);
            wk.c_a = mul(&wk.rot, cross(w, cross(w, prev_r)));
            w = add(w_rot, wj);
            prev_r = l.r;
            // I_O = [[Ic - m [c x]^2, m [c x]], [-m [c x], m 1]] with c = r_cm.
            let sc = skew(l.r_cm);
            let mut m1 = [[0.0; 3]; 3];
            for k in 0..3 {
                m1[k][k] = l.m;
            }
            let b = add_m(&[[0.0; 3]; 3], l.m, &sc);
            wk.ia = [add_m(&l.inertia, -l.m, &mm(&sc, &sc)), b, m1];
            wk.p_f = scale(l.m, cross(w, cross(w, l.r_cm)));
            wk.p_n = add(cross(w, mul(&l.inertia, w)), cross(l.r_cm, wk.p_f));
        }
        // Pass 2, tip to base: articulated inertias and bias wrenches.
        for i in (0..n).rev() {
            let axis = self.links[i].axis;
            let mut wk = self.work[i];
            let [a, b, m] = wk.ia;
            wk.u_n = mul(&a, axis);
            wk.u_f = mul_t(&b, axis);
            wk.d = dot(axis, wk.u_n);
            wk.u = -dot(axis, wk.p_n);
            self.work[i] = wk;
            if i == 0 {
                break;
            }
            // I^a = I^A - U U^T / D, p^a = p^A + I^a c + U u / D.
            let s = -1.0 / wk.d;
            let a = add_outer(&a, s, wk.u_n, wk.u_n);
            let b = add_outer(&b, s, wk.u_n, wk.u_f);
            let m = add_outer(&m, s, wk.u_f, wk.u_f);
            let k = wk.u / wk.d;
            let p_n = add(
                add(wk.p_n, scale(k, wk.u_n)),
                add(mul(&a, wk.c_w), mul(&b, wk.c_a)),
            );
            let p_f = add(
                add(wk.p_f, scale(k, wk.u_f)),
                add(mul_t(&b, wk.c_w), mul(&m, wk.c_a)),
            );
            // To the parent: resolve in its frame (R^T X R), then shift from this joint to
            // the parent's by r: [A + [r x] B^T - K [r x], K = B + [r x] M, M].
            let (a, b, m) = (rot_t(&wk.rot, &a), rot_t(&wk.rot, &b), rot_t(&wk.rot, &m));
            let (p_n, p_f) = (mul_t(&wk.rot, p_n), mul_t(&wk.rot, p_f));
            let r = self.links[i - 1].r;
            let sr = skew(r);
            let k = add_m(&b, 1.0, &mm(&sr, &m));
            let a = add_m(
                &add_m(&a, 1.0, &mm(&sr, &transpose(&b))),
                -1.0,
                &mm(&k, &sr),
            );
            let p = &mut self.work[i - 1];
            p.ia = [
                add_m(&p.ia[0], 1.0, &a),
                add_m(&p.ia[1], 1.0, &k),
                add_m(&p.ia[2], 1.0, &m),
            ];
            p.p_n = add(p.p_n, add(p_n, cross(r, p_f)));
            p.p_f = add(p.p_f, p_f);
        }
        // Pass 3, base to tip: accelerations (the base accelerates with -g).
        let (mut dw, mut acc, mut prev_r) = ([0.0; 3], scale(-1.0, self.g), [0.0; 3]);
        for i in 0..n {
            let wk = &self.work[i];
            let l = &self.links[i];
            let dw_i = add(mul(&wk.rot, dw), wk.c_w);
            acc = add(mul(&wk.rot, add(acc, cross(dw, prev_r))), wk.c_a);
            qdd[i] = (wk.u - dot(wk.u_n, dw_i) - dot(wk.u_f, acc)) / wk.d;
            dw = add(dw_i, scale(qdd[i], l.axis));
            prev_r = l.r;
        }
    }
}

impl OdeFunctions for Aba {
    fn len(&self) -> usize {
        2 * self.links.len()
    }
    fn rhs(&mut self, _t: f64, y: &[f64], ydot: &mut [f64]) -> Result<(), EvalError> {
        let n = self.links.len();
        let (q, v) = y.split_at(n);
        let (qd, qdd) = ydot.split_at_mut(n);
        qd.copy_from_slice(v);
        self.accelerations(q, v, qdd);
        Ok(())
    }
}
