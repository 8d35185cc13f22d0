//! Mechanical quantities read from solutions: vectors and rotations of frames by name,
//! and the energy of bodies (each test file includes this module and uses what it needs).

#![allow(dead_code)]

use multibody::prelude::*;

/// The three components `name[1..3]` at every reported time.
pub fn vector(sol: &Solution, name: &str) -> Vec<[f64; 3]> {
    let names: Vec<String> = (1..=3).map(|i| format!("{name}[{i}]")).collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let s = sol.get_many(&refs).expect("a vector of the model");
    (0..sol.t().len())
        .map(|k| [s[0][k], s[1][k], s[2][k]])
        .collect()
}

/// The rotation matrix `T` (world to frame) of `frame` at every reported time.
pub fn rotation(sol: &Solution, frame: &str) -> Vec<[[f64; 3]; 3]> {
    let names: Vec<String> = (1..=3)
        .flat_map(|i| (1..=3).map(move |j| format!("{frame}.R.T[{i},{j}]")))
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let s = sol.get_many(&refs).expect("a frame of the model");
    (0..sol.t().len())
        .map(|k| std::array::from_fn(|i| std::array::from_fn(|j| s[3 * i + j][k])))
        .collect()
}

/// `T' v`: a vector given in a frame, resolved in the world.
pub fn to_world(t: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|j| t[j][i] * v[j]).sum())
}

/// `a x b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a . b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Mass properties of a body: mass, centre of mass from `frame_a` (in `frame_a`) and
/// inertia about the centre of mass (in `frame_a`).
#[derive(Clone, Copy, Debug)]
pub struct MassProps {
    /// Mass [kg].
    pub m: f64,
    /// Centre of mass [m].
    pub r_cm: [f64; 3],
    /// Inertia [kg.m2].
    pub inertia: [[f64; 3]; 3],
}

/// Kinetic plus potential energy of the `Body` at path `body` in gravity `g` along `n`
/// (a unit vector), at every reported time.
pub fn body_energy(sol: &Solution, body: &str, p: MassProps, g: f64, n: [f64; 3]) -> Vec<f64> {
    let t = rotation(sol, &format!("{body}.frame_a"));
    let w = vector(sol, &format!("{body}.w_a"));
    let v0 = vector(sol, &format!("{body}.v_0"));
    let r0 = vector(sol, &format!("{body}.r_0"));
    (0..sol.t().len())
        .map(|k| {
            let w = w[k];
            let v_cm = {
                let v = to_world(&t[k], cross(w, p.r_cm));
                [v0[k][0] + v[0], v0[k][1] + v[1], v0[k][2] + v[2]]
            };
            let r_cm = {
                let r = to_world(&t[k], p.r_cm);
                [r0[k][0] + r[0], r0[k][1] + r[1], r0[k][2] + r[2]]
            };
            let iw: [f64; 3] = std::array::from_fn(|i| dot(p.inertia[i], w));
            0.5 * p.m * dot(v_cm, v_cm) + 0.5 * dot(w, iw) - p.m * g * dot(n, r_cm)
        })
        .collect()
}

/// The largest deviation of `total` from its first value, relative to `scale`.
pub fn relative_drift(total: &[f64], scale: f64) -> f64 {
    total
        .iter()
        .map(|e| (e - total[0]).abs())
        .fold(0.0, f64::max)
        / scale
}
