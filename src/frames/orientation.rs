//! The orientation object and its functions.

use multibody_core::expr::{Expr, Mat3, Vec3};
use multibody_core::model::{
    Equate, OverdeterminedType, PathId, System, VarKind, Variable, VariableType,
};

fn c(x: f64) -> Expr {
    Expr::constant(x)
}

/// An orientation: the transformation matrix `T` (frame 1 to frame 2) and the angular
/// velocity `w` of frame 2 relative to frame 1, resolved in frame 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(non_snake_case)]
pub struct Orientation {
    /// Transformation matrix: `v2 = T v1`.
    pub T: Mat3,
    /// Angular velocity of frame 2 relative to frame 1, resolved in frame 2 \[rad/s\].
    pub w: Vec3,
    /// The full path when the orientation is a declared variable (`j1.frame_a.R`).
    pub path: Option<PathId>,
}

impl Orientation {
    /// An orientation from `T` and `w` (MSL `from_T`).
    #[allow(non_snake_case)]
    pub fn new(T: Mat3, w: Vec3) -> Orientation {
        Orientation { T, w, path: None }
    }

    /// The twelve scalars: `T` row by row, then `w`.
    pub fn scalars(&self) -> Vec<Expr> {
        let mut v: Vec<Expr> = self.T.elements().to_vec();
        v.extend(self.w.0);
        v
    }

    /// Rebuilds an orientation from its twelve scalars.
    pub fn from_scalars(s: &[Expr]) -> Orientation {
        let t = |i: usize, j: usize| s[3 * i + j];
        Orientation::new(
            Mat3(std::array::from_fn(|i| std::array::from_fn(|j| t(i, j)))),
            Vec3([s[9], s[10], s[11]]),
        )
    }
}

fn t_name(path: &str, i: usize, j: usize) -> String {
    format!("{path}.T[{},{}]", i + 1, j + 1)
}

fn w_name(path: &str, i: usize) -> String {
    format!("{path}.w[{}]", i + 1)
}

impl VariableType for Orientation {
    fn declare(s: &mut System, template: Variable) -> Self {
        let local = template.name.clone();
        let mut t = [[c(0.0); 3]; 3];
        for (i, row) in t.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                let v = template
                    .clone()
                    .description("transformation matrix from world frame to local frame")
                    .start(if i == j { 1.0 } else { 0.0 });
                *x = s.variable_at(&format!("{local}.T[{},{}]", i + 1, j + 1), v);
            }
        }
        let mut w = [c(0.0); 3];
        for (i, x) in w.iter_mut().enumerate() {
            let v = template
                .clone()
                .description("absolute angular velocity of local frame, resolved in local frame")
                .unit("rad/s");
            *x = s.variable_at(&format!("{local}.w[{}]", i + 1), v);
        }
        let (t, w) = (Mat3(t), Vec3(w));
        // der(T) = -skew(w) T: the entries of T never get derivative unknowns.
        let dt = -(w.skew().mul_mat(t));
        for i in 0..3 {
            for j in 0..3 {
                s.derivative_rule(t.0[i][j], dt.0[i][j]);
            }
        }
        Orientation {
            T: t,
            w,
            path: Some(PathId::new(&s.full(&local))),
        }
    }

    fn at(path: &str) -> Self {
        Orientation {
            T: Mat3(std::array::from_fn(|i| {
                std::array::from_fn(|j| Expr::var(&t_name(path, i, j)))
            })),
            w: Vec3(std::array::from_fn(|i| Expr::var(&w_name(path, i)))),
            path: Some(PathId::new(path)),
        }
    }
}

impl OverdeterminedType for Orientation {
    fn scalars(&self) -> Vec<Expr> {
        Orientation::scalars(self)
    }

    fn residue(a: &[Expr], b: &[Expr]) -> Vec<Expr> {
        equality_constraint(&Orientation::from_scalars(a), &Orientation::from_scalars(b))
            .0
            .to_vec()
    }

    fn node_path(&self) -> String {
        self.path.map(|p| p.as_string()).unwrap_or_default()
    }
}

impl Equate<Orientation> for Orientation {
    fn pairs(self, rhs: Orientation) -> Vec<(Expr, Expr)> {
        self.scalars().into_iter().zip(rhs.scalars()).collect()
    }
}

/// Declares an orientation variable that is not a connector's (its kind is internal).
pub fn declare_orientation(s: &mut System, name: &str) -> Orientation {
    Orientation::declare(s, Variable::new(name.to_string()).kind(VarKind::Internal))
}

/// The null rotation: `T = I`, `w = 0`.
pub fn null_rotation() -> Orientation {
    Orientation::new(Mat3::identity(), Vec3::zero())
}

/// Resolves a vector given in frame 2 in frame 1: `T' v2`.
pub fn resolve1(r: &Orientation, v2: Vec3) -> Vec3 {
    r.T.transpose().mul_vec(v2)
}

/// Resolves a vector given in frame 1 in frame 2: `T v1`.
pub fn resolve2(r: &Orientation, v1: Vec3) -> Vec3 {
    r.T.mul_vec(v1)
}

/// Resolves `v1` (in frame 1 of `r1`) in frame 2 of `r2`, both orientations relative to
/// the same frame 0: `T2 T1' v1`.
pub fn resolve_relative(v1: Vec3, r1: &Orientation, r2: &Orientation) -> Vec3 {
    resolve2(r2, resolve1(r1, v1))
}

/// Resolves a tensor given in frame 2 in frame 1: `T' D2 T`.
pub fn resolve_dyade1(r: &Orientation, d2: Mat3) -> Mat3 {
    r.T.transpose().mul_mat(d2).mul_mat(r.T)
}

/// Resolves a tensor given in frame 1 in frame 2: `T D1 T'`.
pub fn resolve_dyade2(r: &Orientation, d1: Mat3) -> Mat3 {
    r.T.mul_mat(d1).mul_mat(r.T.transpose())
}

/// The inverse rotation (frame 2 into frame 1): `T'`, `w = -T' w`.
pub fn inverse_rotation(r: &Orientation) -> Orientation {
    Orientation::new(r.T.transpose(), -resolve1(r, r.w))
}

/// The rotation from frame 1 to frame 2 of two orientations relative to frame 0:
/// `T_rel = T2 T1'`, `w_rel = w2 - T2 T1' w1`.
pub fn relative_rotation(r1: &Orientation, r2: &Orientation) -> Orientation {
    Orientation::new(
        r2.T.mul_mat(r1.T.transpose()),
        r2.w - resolve2(r2, resolve1(r1, r1.w)),
    )
}

/// The orientation of frame 2 from that of frame 1 and the rotation 1 to 2:
/// `T2 = T_rel T1`, `w2 = T_rel w1 + w_rel`.
pub fn absolute_rotation(r1: &Orientation, r_rel: &Orientation) -> Orientation {
    Orientation::new(r_rel.T.mul_mat(r1.T), resolve2(r_rel, r1.w) + r_rel.w)
}

/// The rotation by `angle` about the unit axis `e` (right-hand rule):
/// `T = e e' + (I - e e') cos(angle) - skew(e) sin(angle)`, `w = e der_angle`.
pub fn planar_rotation(e: Vec3, angle: Expr, der_angle: Expr) -> Orientation {
    let ee = e.outer(e);
    let t = ee + (Mat3::identity() - ee).scale(angle.cos()) - e.skew().scale(angle.sin());
    Orientation::new(t, e.scale(der_angle))
}

/// The angle of the planar rotation about `e` that turns `v1` into `v2`
/// (`v2 = resolve2(planar_rotation(e, angle), v1)`), in `[-pi, pi]`.
pub fn planar_rotation_angle(e: Vec3, v1: Vec3, v2: Vec3) -> Expr {
    let y = -(e.cross(v1).dot(v2));
    let x = v1.dot(v2) - e.dot(v1) * e.dot(v2);
    y.atan2(x)
}

/// The unit vector along axis `i` (1, 2 or 3; the x axis for anything else).
pub fn axis(i: usize) -> Vec3 {
    let mut v = [0.0; 3];
    v[i.clamp(1, 3) - 1] = 1.0;
    Vec3::constant(v)
}

/// Whether `sequence` is a sequence of rotation axes: each 1, 2 or 3, and no two
/// consecutive ones equal.
pub fn valid_sequence(sequence: [usize; 3]) -> bool {
    sequence.iter().all(|i| (1..=3).contains(i))
        && sequence[0] != sequence[1]
        && sequence[1] != sequence[2]
}

/// `sequence` when it is [`valid_sequence`], otherwise `[1, 2, 3]` (for components that
/// assert their sequence is valid and go on building).
pub fn usable_sequence(sequence: [usize; 3]) -> [usize; 3] {
    if valid_sequence(sequence) {
        sequence
    } else {
        [1, 2, 3]
    }
}

/// The message of a component whose axis sequence `name` is not [`valid_sequence`].
pub fn invalid_sequence(name: &str, sequence: [usize; 3]) -> String {
    format!(
        "the axis sequence {name} = {sequence:?} must have axes 1, 2 or 3 with no two \
         consecutive ones equal"
    )
}

/// The rotation by `angle` about coordinate axis `i` (1, 2 or 3).
pub fn axis_rotation(i: usize, angle: Expr, der_angle: Expr) -> Orientation {
    planar_rotation(axis(i), angle, der_angle)
}

/// The rotation about the body-fixed axes `sequence` (1, 2 or 3 each; `[1, 2, 3]` are
/// Cardan angles, `[3, 1, 3]` Euler angles) by `angles`, with their derivatives:
/// `T = A3 A2 A1`, `w = e3 d3 + A3 e2 d2 + A3 A2 e1 d1`.
pub fn axes_rotations(
    sequence: [usize; 3],
    angles: [Expr; 3],
    der_angles: [Expr; 3],
) -> Orientation {
    let a: Vec<Orientation> = (0..3)
        .map(|k| axis_rotation(sequence[k], angles[k], c(0.0)))
        .collect();
    let t = a[2].T.mul_mat(a[1].T).mul_mat(a[0].T);
    let e = |k: usize| axis(sequence[k]);
    let w = e(2).scale(der_angles[2])
        + a[2].T.mul_vec(e(1)).scale(der_angles[1])
        + a[2].T.mul_mat(a[1].T).mul_vec(e(0)).scale(der_angles[0]);
    Orientation::new(t, w)
}

/// The angles of the rotation sequence `sequence` that give `r` (the inverse of
/// [`axes_rotations`]), numerically. Of the two solutions the one whose first angle is
/// nearer `guess_angle1` is returned; in gimbal lock the first angle is `guess_angle1`.
///
/// # Panics
/// If `sequence` is not [`valid_sequence`].
pub fn axes_rotations_angles(
    t: [[f64; 3]; 3],
    sequence: [usize; 3],
    guess_angle1: f64,
) -> [f64; 3] {
    assert!(
        valid_sequence(sequence),
        "axes_rotations_angles: {}",
        invalid_sequence("sequence", sequence)
    );
    let unit = |i: usize| {
        let mut v = [0.0; 3];
        v[i - 1] = 1.0;
        v
    };
    use crate::numeric::{cross, dot};
    let mat_vec = |m: [[f64; 3]; 3], v: [f64; 3]| [dot(m[0], v), dot(m[1], v), dot(m[2], v)];
    let transpose = |m: [[f64; 3]; 3]| {
        [
            [m[0][0], m[1][0], m[2][0]],
            [m[0][1], m[1][1], m[2][1]],
            [m[0][2], m[1][2], m[2][2]],
        ]
    };
    let planar = |e: [f64; 3], angle: f64| -> [[f64; 3]; 3] {
        let (ca, sa) = (angle.cos(), angle.sin());
        let mut m = [[0.0; 3]; 3];
        let sk = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                let id = if i == j { 1.0 } else { 0.0 };
                m[i][j] = e[i] * e[j] + (id - e[i] * e[j]) * ca - sk[i][j] * sa;
            }
        }
        m
    };
    let angle_of = |e: [f64; 3], v1: [f64; 3], v2: [f64; 3]| {
        (-dot(cross(e, v1), v2)).atan2(dot(v1, v2) - dot(e, v1) * dot(e, v2))
    };
    let e1_1 = unit(sequence[0]);
    let e2_1a = unit(sequence[1]);
    let e3_1 = t[sequence[2] - 1];
    let e3_2 = unit(sequence[2]);
    let a = dot(e2_1a, e3_1);
    let b = dot(cross(e1_1, e2_1a), e3_1);
    let a1 = if a.abs() <= 1e-12 && b.abs() <= 1e-12 {
        guess_angle1
    } else {
        let a1a = a.atan2(-b);
        let a1b = (-a).atan2(b);
        if (a1a - guess_angle1).abs() <= (a1b - guess_angle1).abs() {
            a1a
        } else {
            a1b
        }
    };
    let t_1a = planar(e1_1, a1);
    let a2 = angle_of(e2_1a, mat_vec(t_1a, e3_1), e3_2);
    let a3 = angle_of(e3_2, e2_1a, mat_vec(t, mat_vec(transpose(t_1a), e2_1a)));
    [a1, a2, a3]
}

/// The angles of the rotation sequence `sequence` that give the rotation matrix `t`,
/// symbolically (the inverse of [`axes_rotations`], as [`axes_rotations_angles`]): of
/// the two solutions, the one whose first angle is nearer `guess_angle1`.
///
/// # Panics
/// If `sequence` is not [`valid_sequence`].
pub fn axes_rotations_angles_expr(t: Mat3, sequence: [usize; 3], guess_angle1: f64) -> Vec3 {
    assert!(
        valid_sequence(sequence),
        "axes_rotations_angles_expr: {}",
        invalid_sequence("sequence", sequence)
    );
    let e1_1 = axis(sequence[0]);
    let e2_1a = axis(sequence[1]);
    let e3_1 = t.row(sequence[2] - 1);
    let e3_2 = axis(sequence[2]);
    let a = e2_1a.dot(e3_1);
    let b = e1_1.cross(e2_1a).dot(e3_1);
    let a1a = a.atan2(-b);
    let a1b = (-a).atan2(b);
    let g = c(guess_angle1);
    let a1 = Expr::if_else((a1a - g).abs().le((a1b - g).abs()), a1a, a1b).no_event();
    let t_1a = planar_rotation(e1_1, a1, c(0.0)).T;
    let a2 = planar_rotation_angle(e2_1a, t_1a.mul_vec(e3_1), e3_2);
    let a3 = planar_rotation_angle(e3_2, e2_1a, t.mul_vec(t_1a.transpose().mul_vec(e2_1a)));
    Vec3([a1, a2, a3])
}

/// Rotation angles about the axes of frame 1 for a small rotation:
/// `{T[2,3], -T[1,3], T[1,2]}`.
pub fn small_rotation(r: &Orientation) -> Vec3 {
    let t = r.T.0;
    Vec3([t[1][2], -t[0][2], t[0][1]])
}

/// The orientation whose x axis points along `n_x` and whose y axis is as close as
/// possible to `n_y` (both resolved in frame 1; `w = 0`). Numeric (for structural
/// parameters): when the two are parallel another y axis is chosen, as MSL does.
pub fn from_nxy(n_x: [f64; 3], n_y: [f64; 3]) -> Orientation {
    Orientation::new(Mat3::constant(t_from_nxy(n_x, n_y)), Vec3::zero())
}

/// The transformation matrix of [`from_nxy`].
pub fn t_from_nxy(n_x: [f64; 3], n_y: [f64; 3]) -> [[f64; 3]; 3] {
    use crate::numeric::{cross, norm, scale};
    let e_x = if norm(n_x) < 1e-10 {
        [1.0, 0.0, 0.0]
    } else {
        scale(n_x, 1.0 / norm(n_x))
    };
    let e_y = if norm(n_y) < 1e-10 {
        [0.0, 1.0, 0.0]
    } else {
        scale(n_y, 1.0 / norm(n_y))
    };
    let n_z_aux = cross(e_x, e_y);
    let n_y_aux = if norm(n_z_aux).powi(2) > 1e-6 {
        e_y
    } else if e_x[0].abs() > 1e-6 {
        [0.0, 1.0, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let z = cross(e_x, n_y_aux);
    let e_z = scale(z, 1.0 / norm(z));
    [e_x, cross(e_z, e_x), e_z]
}

/// The orientation whose x axis points along `n_x` and whose z axis is as close as
/// possible to `n_z` (numeric, `w = 0`).
pub fn from_nxz(n_x: [f64; 3], n_z: [f64; 3]) -> Orientation {
    use crate::numeric::{cross, norm, scale};
    let e_x = if norm(n_x) < 1e-10 {
        [1.0, 0.0, 0.0]
    } else {
        scale(n_x, 1.0 / norm(n_x))
    };
    let e_z = if norm(n_z) < 1e-10 {
        [0.0, 0.0, 1.0]
    } else {
        scale(n_z, 1.0 / norm(n_z))
    };
    let n_y_aux = cross(e_z, e_x);
    let n_z_aux = if norm(n_y_aux).powi(2) > 1e-6 {
        e_z
    } else if e_x[0].abs() > 1e-6 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let y = cross(n_z_aux, e_x);
    let e_y = scale(y, 1.0 / norm(y));
    Orientation::new(Mat3::constant([e_x, e_y, cross(e_x, e_y)]), Vec3::zero())
}

/// An orientation from a transformation matrix and an angular velocity (MSL `from_T`).
#[allow(non_snake_case)]
pub fn from_t(T: Mat3, w: Vec3) -> Orientation {
    Orientation::new(T, w)
}

/// The angular velocity of frame 2 relative to frame 1, resolved in frame 1.
pub fn angular_velocity1(r: &Orientation) -> Vec3 {
    resolve1(r, r.w)
}

/// The angular velocity of frame 2 relative to frame 1, resolved in frame 2.
pub fn angular_velocity2(r: &Orientation) -> Vec3 {
    r.w
}

/// The three residues that vanish when two orientations (relative to the same frame)
/// agree: `atan2` of the off-diagonal entries of `T_rel = T2 T1'` over the diagonal
/// ones (MSL `Orientation.equalityConstraint`). They close a kinematic loop.
pub fn equality_constraint(r1: &Orientation, r2: &Orientation) -> Vec3 {
    let (t1, t2) = (r1.T, r2.T);
    let n = t1.row(0).cross(t1.row(1));
    Vec3([
        n.dot(t2.row(1)).atan2(t1.row(0).dot(t2.row(0))),
        (-n.dot(t2.row(0))).atan2(t1.row(1).dot(t2.row(1))),
        t1.row(1).dot(t2.row(0)).atan2(t1.row(2).dot(t2.row(2))),
    ])
}

/// The six orthonormality residues of `T`'s columns.
pub fn orientation_constraint(r: &Orientation) -> [Expr; 6] {
    let col = |j: usize| r.T.col(j);
    [
        col(0).dot(col(0)) - 1.0,
        col(1).dot(col(1)) - 1.0,
        col(2).dot(col(2)) - 1.0,
        col(0).dot(col(1)),
        col(0).dot(col(2)),
        col(1).dot(col(2)),
    ]
}
