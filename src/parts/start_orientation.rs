//! Start values of orientation states from angles (MSL's `R_start`, `Q_start`,
//! `phi_start` of `Parts.Body` and `Joints.FreeMotion`), computed numerically when the
//! model is built.

use crate::frames::{axes_rotations_angles, to_q, usable_sequence};

type M3 = [[f64; 3]; 3];

/// The transformation matrix of a rotation about coordinate axis `i` (1..3) by `angle`
/// (MSL `TransformationMatrices.axisRotation`: it maps vectors of the rotated frame's
/// parent into the rotated frame).
fn axis_rotation(i: usize, angle: f64) -> M3 {
    let (s, c) = angle.sin_cos();
    let mut t = [[0.0; 3]; 3];
    let (j, k) = (i % 3, (i + 1) % 3);
    let i = i - 1;
    t[i][i] = 1.0;
    t[j][j] = c;
    t[k][k] = c;
    t[j][k] = s;
    t[k][j] = -s;
    t
}

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn mv(a: &M3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn unit(i: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[i - 1] = 1.0;
    e
}

fn det(m: &M3) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// The start of a frame's orientation relative to its parent frame (the world for a
/// body, `frame_a` for a free motion joint), given as angles about the axes of a
/// sequence, with the angular velocity and acceleration resolved in the parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StartOrientation {
    /// `R_start.T` (parent-resolved vectors into the frame).
    pub t: M3,
    /// The angles of the state sequence (`phi_start`) \[rad\].
    pub phi: [f64; 3],
    /// Their derivatives, from the angular velocity (0 in gimbal lock) \[rad/s\].
    pub phi_d: [f64; 3],
    /// The quaternion `Q_start` (vector part first, scalar last).
    pub q: [f64; 4],
    /// The angular velocity resolved in the frame \[rad/s\].
    pub w: [f64; 3],
    /// The angular acceleration resolved in the frame \[rad/s2\].
    pub z: [f64; 3],
}

impl StartOrientation {
    /// MSL: `R_start = axesRotations(sequence_start, angles_start)`, `Q_start =
    /// to_Q(R_start)`, `phi_start = angles_start` when the sequences agree and
    /// `axesRotationsAngles(R_start, sequence_angleStates)` otherwise, and the frame's
    /// angular velocity and acceleration `resolve2(R_start, .)`. Invalid sequences are
    /// replaced by {1, 2, 3} (the components report them).
    pub fn new(
        sequence_start: [usize; 3],
        angles_start: [f64; 3],
        sequence_angle_states: [usize; 3],
        w_parent: [f64; 3],
        z_parent: [f64; 3],
    ) -> Self {
        let seq = usable_sequence(sequence_start);
        let states = usable_sequence(sequence_angle_states);
        let a = |k: usize, angles: [f64; 3], seq: [usize; 3]| axis_rotation(seq[k], angles[k]);
        let t = mul(
            &mul(&a(2, angles_start, seq), &a(1, angles_start, seq)),
            &a(0, angles_start, seq),
        );
        let phi = if seq == states {
            angles_start
        } else {
            axes_rotations_angles(t, states, 0.0)
        };
        let w = mv(&t, w_parent);
        // w = e3 d3 + A3 e2 d2 + A3 A2 e1 d1 (MSL axesRotations): solve for d.
        let a3 = a(2, phi, states);
        let a32 = mul(&a3, &a(1, phi, states));
        let cols = [
            mv(&a32, unit(states[0])),
            mv(&a3, unit(states[1])),
            unit(states[2]),
        ];
        let j: M3 = std::array::from_fn(|i| std::array::from_fn(|k| cols[k][i]));
        let d = det(&j);
        let phi_d = if d.abs() < 1e-12 {
            [0.0; 3]
        } else {
            // Cramer's rule.
            std::array::from_fn(|k| {
                let mut m = j;
                for (i, row) in m.iter_mut().enumerate() {
                    row[k] = w[i];
                }
                det(&m) / d
            })
        };
        StartOrientation {
            t,
            phi,
            phi_d,
            q: to_q(t, [0.0, 0.0, 0.0, 1.0]),
            w,
            z: mv(&t, z_parent),
        }
    }

    /// The vector part of [`q`](Self::q).
    pub fn q_v(&self) -> [f64; 3] {
        [self.q[0], self.q[1], self.q[2]]
    }
}

/// `v` as a start value unless it is zero (no start, as when none is given: the
/// initialization then takes 0 or what the rest of the model implies).
pub(crate) fn given(v: [f64; 3]) -> Option<[f64; 3]> {
    (v != [0.0; 3]).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// About x by 90 degrees: the rows of T are the frame's axes in the parent,
    /// x' = x, y' = z, z' = -y; Q = (sin 45, 0, 0, cos 45).
    #[test]
    fn a_quarter_turn_about_x() {
        let s = StartOrientation::new(
            [1, 2, 3],
            [std::f64::consts::FRAC_PI_2, 0.0, 0.0],
            [1, 2, 3],
            [1.0, 2.0, 3.0],
            [0.0; 3],
        );
        let want = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                assert!((s.t[i][j] - want[i][j]).abs() < 1e-15, "{:?}", s.t);
            }
        }
        let h = std::f64::consts::FRAC_1_SQRT_2;
        for (got, want) in s.q.iter().zip([h, 0.0, 0.0, h]) {
            assert!((got - want).abs() < 1e-15, "{:?}", s.q);
        }
        // w resolved in the frame: (1, 3, -2); rates about x, the new y, the newer z.
        for (got, want) in s.w.iter().zip([1.0, 3.0, -2.0]) {
            assert!((got - want).abs() < 1e-14, "{:?}", s.w);
        }
        for (got, want) in s.phi_d.iter().zip([1.0, 3.0, -2.0]) {
            assert!((got - want).abs() < 1e-14, "{:?}", s.phi_d);
        }
    }
}
