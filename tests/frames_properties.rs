//! Property tests of the orientation functions: the identities MSL's Frames satisfy.

use multibody::frames::*;
use multibody::prelude::*;
use proptest::prelude::*;

fn c(x: f64) -> Expr {
    Expr::constant(x)
}

fn m(r: &Orientation) -> [[f64; 3]; 3] {
    r.T.as_f64().expect("constant matrix")
}

fn v(x: Vec3) -> [f64; 3] {
    x.as_f64().expect("constant vector")
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn assert_mat(a: [[f64; 3]; 3], b: [[f64; 3]; 3], tol: f64) {
    for i in 0..3 {
        for j in 0..3 {
            assert!(close(a[i][j], b[i][j], tol), "{a:?} vs {b:?}");
        }
    }
}

fn assert_vec(a: [f64; 3], b: [f64; 3], tol: f64) {
    for i in 0..3 {
        assert!(close(a[i], b[i], tol), "{a:?} vs {b:?}");
    }
}

/// An orientation with angular velocity from Cardan angles and their rates.
fn orientation(angles: [f64; 3], rates: [f64; 3]) -> Orientation {
    axes_rotations([1, 2, 3], angles.map(c), rates.map(c))
}

const ID: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn inverse_is_transpose_and_undoes_the_rotation(
        a in prop::array::uniform3(-3.0f64..3.0),
        w in prop::array::uniform3(-2.0f64..2.0),
    ) {
        let r = orientation(a, w);
        let inv = inverse_rotation(&r);
        let t = m(&r);
        let ti = m(&inv);
        for i in 0..3 { for j in 0..3 { prop_assert!(close(ti[i][j], t[j][i], 1e-14)); } }
        // R followed by its inverse is the null rotation.
        let back = absolute_rotation(&r, &inv);
        assert_mat(m(&back), ID, 1e-12);
        assert_vec(v(back.w), [0.0; 3], 1e-12);
        // T is orthonormal.
        for res in orientation_constraint(&r) {
            prop_assert!(res.as_f64().unwrap().abs() < 1e-13);
        }
    }

    #[test]
    fn composition_and_relative_rotation_agree(
        a1 in prop::array::uniform3(-3.0f64..3.0),
        a2 in prop::array::uniform3(-3.0f64..3.0),
        w1 in prop::array::uniform3(-2.0f64..2.0),
        w2 in prop::array::uniform3(-2.0f64..2.0),
        x in prop::array::uniform3(-5.0f64..5.0),
    ) {
        let (r1, r2) = (orientation(a1, w1), orientation(a2, w2));
        let rel = relative_rotation(&r1, &r2);
        let again = absolute_rotation(&r1, &rel);
        assert_mat(m(&again), m(&r2), 1e-12);
        assert_vec(v(again.w), v(r2.w), 1e-12);
        // Resolving there and back.
        let xv = Vec3::constant(x);
        assert_vec(v(resolve1(&r1, resolve2(&r1, xv))), x, 1e-12);
        assert_vec(v(resolve_relative(xv, &r1, &r2)), v(resolve2(&rel, xv)), 1e-12);
        // The residue of identical orientations vanishes.
        assert_vec(v(equality_constraint(&r2, &again)), [0.0; 3], 1e-12);
    }

    #[test]
    fn cardan_angles_round_trip_away_from_gimbal_lock(
        a1 in -3.1f64..3.1, a2 in -1.4f64..1.4, a3 in -3.1f64..3.1,
    ) {
        let r = orientation([a1, a2, a3], [0.0; 3]);
        let back = axes_rotations_angles(m(&r), [1, 2, 3], 0.0);
        let again = orientation(back, [0.0; 3]);
        assert_mat(m(&again), m(&r), 1e-12);
        // With the right guess the same angles come back.
        let exact = axes_rotations_angles(m(&r), [1, 2, 3], a1);
        assert_vec(exact, [a1, a2, a3], 1e-10);
        // The symbolic version agrees.
        let sym = axes_rotations_angles_expr(r.T, [1, 2, 3], a1);
        assert_vec(v(sym), [a1, a2, a3], 1e-10);
    }

    #[test]
    fn euler_angles_round_trip(
        a1 in -3.1f64..3.1, a2 in 0.1f64..3.0, a3 in -3.1f64..3.1,
    ) {
        let r = axes_rotations([3, 1, 3], [c(a1), c(a2), c(a3)], [c(0.0); 3]);
        let back = axes_rotations_angles(m(&r), [3, 1, 3], a1);
        assert_vec(back, [a1, a2, a3], 1e-10);
    }

    #[test]
    fn quaternions_round_trip(
        a in prop::array::uniform3(-3.0f64..3.0),
    ) {
        let r = orientation(a, [0.0; 3]);
        let q = to_q(m(&r), [0.0, 0.0, 0.0, 1.0]);
        let n: f64 = q.iter().map(|x| x * x).sum();
        prop_assert!(close(n, 1.0, 1e-13));
        let t = quaternion_to_t(q.map(c));
        assert_mat(t.as_f64().unwrap(), m(&r), 1e-12);
        // The sign follows the guess.
        let q2 = to_q(m(&r), q.map(|x| -x));
        for i in 0..4 { prop_assert!(close(q2[i], -q[i], 1e-13)); }
    }

    #[test]
    fn planar_rotation_angle_inverts_planar_rotation(
        e in prop::array::uniform3(-1.0f64..1.0),
        angle in -3.1f64..3.1,
        x in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let l = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        prop_assume!(l > 0.1);
        let e = Vec3::constant([e[0] / l, e[1] / l, e[2] / l]);
        let xv = Vec3::constant(x);
        prop_assume!(v(e.cross(xv)).iter().map(|q| q * q).sum::<f64>() > 1e-2);
        let r = planar_rotation(e, c(angle), c(0.0));
        let back = planar_rotation_angle(e, xv, resolve2(&r, xv));
        prop_assert!(close(back.as_f64().unwrap(), angle, 1e-10));
    }

    #[test]
    fn angular_velocity_is_the_derivative_of_the_matrix(
        a in prop::array::uniform3(-1.4f64..1.4),
        rates in prop::array::uniform3(-2.0f64..2.0),
    ) {
        // skew(w) = T der(T'): check der(T) = -skew(w) T by finite differences.
        let h = 1e-6;
        let r = orientation(a, rates);
        let plus = orientation(std::array::from_fn(|i| a[i] + h * rates[i]), rates);
        let minus = orientation(std::array::from_fn(|i| a[i] - h * rates[i]), rates);
        let dt = (plus.T - minus.T).scale(1.0 / (2.0 * h));
        let expected = -(r.w.skew().mul_mat(r.T));
        assert_mat(dt.as_f64().unwrap(), expected.as_f64().unwrap(), 1e-7);
        // The quaternion kinematics agree: w = 2 G(Q) der(Q).
        let q = to_q(m(&r), [0.0, 0.0, 0.0, 1.0]);
        let qp = to_q(m(&plus), q);
        let qm = to_q(m(&minus), q);
        let dq: [f64; 4] = std::array::from_fn(|i| (qp[i] - qm[i]) / (2.0 * h));
        let w = quaternion_angular_velocity2(q.map(c), dq.map(c));
        assert_vec(v(w), v(r.w), 1e-6);
    }
}

#[test]
fn gimbal_lock_returns_the_guess_and_still_reproduces_the_matrix() {
    let r = orientation([0.4, std::f64::consts::FRAC_PI_2, -0.2], [0.0; 3]);
    let angles = axes_rotations_angles(m(&r), [1, 2, 3], 0.7);
    assert_eq!(angles[0], 0.7);
    let again = orientation(angles, [0.0; 3]);
    assert_mat(m(&again), m(&r), 1e-12);
}

#[test]
fn from_nxy_is_orthonormal_and_handles_parallel_axes() {
    for (nx, ny) in [
        ([1.0, 2.0, 0.5], [0.0, 1.0, 3.0]),
        ([0.0, 0.0, 2.0], [0.0, 0.0, 1.0]), // parallel: another y axis is chosen
        ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
    ] {
        let r = from_nxy(nx, ny);
        for res in orientation_constraint(&r) {
            assert!(res.as_f64().unwrap().abs() < 1e-13);
        }
        let t = m(&r);
        let l = (nx[0] * nx[0] + nx[1] * nx[1] + nx[2] * nx[2]).sqrt();
        assert_vec(t[0], nx.map(|x| x / l), 1e-14);
        let det = t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1])
            - t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0])
            + t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0]);
        assert!((det - 1.0).abs() < 1e-13);
    }
    let r = from_nxz([1.0, 0.0, 0.0], [0.0, 1.0, 1.0]);
    assert_vec(m(&r)[2], [0.0, 0.5f64.sqrt(), 0.5f64.sqrt()], 1e-14);
}

#[test]
fn small_rotation_reads_the_angles_of_a_small_rotation() {
    let r = orientation([1e-5, -2e-5, 3e-5], [0.0; 3]);
    assert_vec(v(small_rotation(&r)), [1e-5, -2e-5, 3e-5], 1e-9);
    assert_vec(
        v(equality_constraint(&null_rotation(), &r)),
        [1e-5, -2e-5, 3e-5],
        1e-9,
    );
}

// Pinned conventions: each function against MSL's closed form
// (`Modelica.Mechanics.MultiBody.Frames`, MSL 4), written out here entry by entry with
// plain numbers, so a transposed matrix or a flipped sign fails (by 0.1 or more;
// the tolerance, 1e-14 on entries of order 1, is round-off).

/// MSL `TransformationMatrices.axisRotation(axis, angle)`, entry by entry.
fn msl_axis_rotation(axis: usize, a: f64) -> [[f64; 3]; 3] {
    let (c, s) = (a.cos(), a.sin());
    match axis {
        1 => [[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]],
        2 => [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]],
        _ => [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

fn mat_mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn mat_vec(a: [[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * x[k]).sum())
}

fn unit(i: usize) -> [f64; 3] {
    std::array::from_fn(|k| if k + 1 == i { 1.0 } else { 0.0 })
}

#[test]
fn rotation_by_30_degrees_about_z_follows_the_msl_sign_convention() {
    // Frame 2 is frame 1 turned by +30 degrees about z (right-hand rule). MSL:
    // T = e e' + (I - e e') cos - skew(e) sin = [c, s, 0; -s, c, 0; 0, 0, 1], and
    // resolve2(R, v1) = T v1 gives frame-1 vectors in frame 2.
    let a = 30f64.to_radians();
    let (cs, sn) = (a.cos(), a.sin()); // 0.866..., 0.5
    let r = planar_rotation(Vec3::constant([0.0, 0.0, 1.0]), c(a), c(2.0));
    assert_mat(
        m(&r),
        [[cs, sn, 0.0], [-sn, cs, 0.0], [0.0, 0.0, 1.0]],
        1e-14,
    );
    // Frame 1's x axis, seen from frame 2, lies 30 degrees clockwise: (0.866, -0.5, 0).
    assert_vec(
        v(resolve2(&r, Vec3::constant([1.0, 0.0, 0.0]))),
        [cs, -sn, 0.0],
        1e-14,
    );
    // Frame 2's x axis, seen from frame 1, lies 30 degrees counter-clockwise.
    assert_vec(
        v(resolve1(&r, Vec3::constant([1.0, 0.0, 0.0]))),
        [cs, sn, 0.0],
        1e-14,
    );
    // Frame 1's y axis in frame 2: (0.5, 0.866, 0).
    assert_vec(
        v(resolve2(&r, Vec3::constant([0.0, 1.0, 0.0]))),
        [sn, cs, 0.0],
        1e-14,
    );
    // w = e der_angle, resolved in frame 2 (the axis is the same in both).
    assert_vec(v(r.w), [0.0, 0.0, 2.0], 1e-14);
    // The same through axis_rotation(3, ...) and the angle read back with its sign.
    assert_mat(m(&axis_rotation(3, c(a), c(0.0))), m(&r), 1e-14);
    let back = planar_rotation_angle(
        Vec3::constant([0.0, 0.0, 1.0]),
        Vec3::constant([1.0, 0.0, 0.0]),
        Vec3::constant([cs, -sn, 0.0]),
    );
    assert!(close(back.as_f64().unwrap(), a, 1e-14));
}

#[test]
fn planar_rotation_about_a_general_axis_is_msl_and_rodrigues() {
    // e = (1, 2, 2)/3, angle 0.7, der_angle -1.3.
    let e = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let (a, da) = (0.7f64, -1.3);
    let (ca, sa) = (a.cos(), a.sin());
    let skew = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    let expected: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            e[i] * e[j] + (id - e[i] * e[j]) * ca - skew[i][j] * sa
        })
    });
    let r = planar_rotation(Vec3::constant(e), c(a), c(da));
    assert_mat(m(&r), expected, 1e-14);
    assert_vec(v(r.w), e.map(|x| x * da), 1e-14);
    // Rodrigues: frame 2's axes are frame 1's turned by `a` about e, so a vector x2
    // fixed in frame 2 is, in frame 1, x cos a + (e x x) sin a + e (e.x)(1 - cos a).
    let x = [0.3, -1.1, 0.4];
    let ex = [
        e[1] * x[2] - e[2] * x[1],
        e[2] * x[0] - e[0] * x[2],
        e[0] * x[1] - e[1] * x[0],
    ];
    let edx: f64 = (0..3).map(|i| e[i] * x[i]).sum();
    let turned: [f64; 3] =
        std::array::from_fn(|i| x[i] * ca + ex[i] * sa + e[i] * edx * (1.0 - ca));
    assert_vec(v(resolve1(&r, Vec3::constant(x))), turned, 1e-14);
}

#[test]
fn axis_rotations_are_msls_matrices() {
    for axis_index in 1..=3 {
        let r = axis_rotation(axis_index, c(0.4), c(0.9));
        assert_mat(m(&r), msl_axis_rotation(axis_index, 0.4), 1e-14);
        assert_vec(v(r.w), unit(axis_index).map(|x| 0.9 * x), 1e-14);
    }
    // About x by +90 degrees: y2 = z1 and z2 = -y1, so frame 1's y axis is -z2.
    let r = axis_rotation(1, c(std::f64::consts::FRAC_PI_2), c(0.0));
    assert_vec(
        v(resolve2(&r, Vec3::constant([0.0, 1.0, 0.0]))),
        [0.0, 0.0, -1.0],
        1e-14,
    );
    // About y by +90 degrees: x2 = -z1 and z2 = x1, so frame 1's x axis is z2 and its
    // z axis is -x2.
    let r = axis_rotation(2, c(std::f64::consts::FRAC_PI_2), c(0.0));
    assert_vec(
        v(resolve2(&r, Vec3::constant([1.0, 0.0, 0.0]))),
        [0.0, 0.0, 1.0],
        1e-14,
    );
    assert_vec(
        v(resolve2(&r, Vec3::constant([0.0, 0.0, 1.0]))),
        [-1.0, 0.0, 0.0],
        1e-14,
    );
}

#[test]
fn axes_rotations_compose_in_msls_order() {
    // MSL axesRotations: T = axisRotation(seq[3], a3) axisRotation(seq[2], a2)
    // axisRotation(seq[1], a1), w = e3 d3 + A3 e2 d2 + A3 A2 e1 d1 (e_k = axis seq[k]).
    let angles = [0.3, -0.8, 1.9];
    let rates = [0.5, -1.5, 2.5];
    for sequence in [[1, 2, 3], [3, 1, 3], [2, 3, 1], [3, 2, 1]] {
        let r = axes_rotations(sequence, angles.map(c), rates.map(c));
        let a: Vec<[[f64; 3]; 3]> = (0..3)
            .map(|k| msl_axis_rotation(sequence[k], angles[k]))
            .collect();
        assert_mat(m(&r), mat_mul(a[2], mat_mul(a[1], a[0])), 1e-14);
        let e = |k: usize| unit(sequence[k]);
        let w2 = mat_vec(a[2], e(1));
        let w1 = mat_vec(mat_mul(a[2], a[1]), e(0));
        let w: [f64; 3] =
            std::array::from_fn(|i| e(2)[i] * rates[2] + w2[i] * rates[1] + w1[i] * rates[0]);
        assert_vec(v(r.w), w, 1e-14);
    }
    // Cardan angles (90, 90, 0) deg: first about x, then about the new y. Worked by
    // hand: T = A2(90) A1(90) = [0, 1, 0; 0, 0, 1; 1, 0, 0]: x2 = y1, y2 = z1, z2 = x1.
    // (The reverse order A1 A2 would give [0, 0, -1; 1, 0, 0; 0, -1, 0].)
    let h = std::f64::consts::FRAC_PI_2;
    let r = orientation([h, h, 0.0], [0.0; 3]);
    assert_mat(
        m(&r),
        [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]],
        1e-14,
    );
}

#[test]
fn resolve_and_compose_use_t_and_its_transpose_as_msl() {
    // A rotation whose matrix is not symmetric: T and T' differ.
    let r1 = axes_rotations([1, 2, 3], [c(0.2), c(0.5), c(-0.4)], [c(0.0); 3]);
    let t1 = m(&r1);
    let x = [1.0, -2.0, 0.5];
    // resolve2(R, v1) = T v1, resolve1(R, v2) = T' v2.
    assert_vec(v(resolve2(&r1, Vec3::constant(x))), mat_vec(t1, x), 1e-14);
    let t1t: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| t1[j][i]));
    assert_vec(v(resolve1(&r1, Vec3::constant(x))), mat_vec(t1t, x), 1e-14);
    // absoluteRotation(R1, R_rel): T2 = T_rel T1, w2 = T_rel w1 + w_rel.
    let r1 = axis_rotation(1, c(std::f64::consts::FRAC_PI_2), c(1.0));
    let rel = axis_rotation(3, c(std::f64::consts::FRAC_PI_2), c(2.0));
    let r2 = absolute_rotation(&r1, &rel);
    // Az(90) Ax(90) = [0, 1, 0; -1, 0, 0; 0, 0, 1] [1, 0, 0; 0, 0, 1; 0, -1, 0]
    //               = [0, 0, 1; -1, 0, 0; 0, -1, 0].
    assert_mat(
        m(&r2),
        [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]],
        1e-14,
    );
    // w1 = (1, 0, 0) in frame 1; T_rel w1 = (0, -1, 0); plus w_rel = (0, 0, 2).
    assert_vec(v(r2.w), [0.0, -1.0, 2.0], 1e-14);
    // relativeRotation(R1, R2): T_rel = T2 T1'.
    assert_mat(m(&relative_rotation(&r1, &r2)), m(&rel), 1e-14);
}

#[test]
fn quaternions_are_msls() {
    // MSL Quaternions: Q = {n sin(phi/2), cos(phi/2)} for a rotation by phi about n,
    // and to_T(Q) = [2(Q1^2 + Q4^2) - 1, 2(Q1 Q2 + Q3 Q4), 2(Q1 Q3 - Q2 Q4);
    //                2(Q2 Q1 - Q3 Q4), 2(Q2^2 + Q4^2) - 1, 2(Q2 Q3 + Q1 Q4);
    //                2(Q3 Q1 + Q2 Q4), 2(Q3 Q2 - Q1 Q4), 2(Q3^2 + Q4^2) - 1].
    let msl_to_t = |q: [f64; 4]| {
        [
            [
                2.0 * (q[0] * q[0] + q[3] * q[3]) - 1.0,
                2.0 * (q[0] * q[1] + q[2] * q[3]),
                2.0 * (q[0] * q[2] - q[1] * q[3]),
            ],
            [
                2.0 * (q[1] * q[0] - q[2] * q[3]),
                2.0 * (q[1] * q[1] + q[3] * q[3]) - 1.0,
                2.0 * (q[1] * q[2] + q[0] * q[3]),
            ],
            [
                2.0 * (q[2] * q[0] + q[1] * q[3]),
                2.0 * (q[2] * q[1] - q[0] * q[3]),
                2.0 * (q[2] * q[2] + q[3] * q[3]) - 1.0,
            ],
        ]
    };
    // 30 degrees about z: Q = (0, 0, sin 15, cos 15); T as the planar rotation above.
    let a = 30f64.to_radians();
    let q = [0.0, 0.0, (a / 2.0).sin(), (a / 2.0).cos()];
    let t = quaternion_to_t(q.map(c)).as_f64().unwrap();
    assert_mat(t, msl_to_t(q), 1e-14);
    assert_mat(
        t,
        [
            [a.cos(), a.sin(), 0.0],
            [-a.sin(), a.cos(), 0.0],
            [0.0, 0.0, 1.0],
        ],
        1e-14,
    );
    assert_vec(
        to_q(t, [0.0, 0.0, 0.0, 1.0])[..3].try_into().unwrap(),
        [0.0, 0.0, (a / 2.0).sin()],
        1e-14,
    );
    // A general axis: n = (2, -1, 2)/3, phi = 2.2 rad.
    let n = [2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0];
    let phi = 2.2f64;
    let (s, co) = ((phi / 2.0).sin(), (phi / 2.0).cos());
    let q = [n[0] * s, n[1] * s, n[2] * s, co];
    let t = quaternion_to_t(q.map(c)).as_f64().unwrap();
    assert_mat(t, msl_to_t(q), 1e-14);
    assert_mat(
        t,
        m(&planar_rotation(Vec3::constant(n), c(phi), c(0.0))),
        1e-14,
    );
    let back = to_q(t, [0.0, 0.0, 0.0, 1.0]);
    for i in 0..4 {
        assert!(close(back[i], q[i], 1e-14), "{back:?} vs {q:?}");
    }
    // MSL angularVelocity2: w = 2 [Q4, Q3, -Q2, -Q1; -Q3, Q4, Q1, -Q2; Q2, -Q1, Q4, -Q3]
    // der(Q). For a steady rotation at rate 1.7 about n: der(Q) = 1.7/2 (n cos, -sin),
    // and w = 1.7 n.
    let dq = [
        0.85 * n[0] * co,
        0.85 * n[1] * co,
        0.85 * n[2] * co,
        -0.85 * s,
    ];
    let w = quaternion_angular_velocity2(q.map(c), dq.map(c));
    assert_vec(v(w), n.map(|x| 1.7 * x), 1e-14);
}

#[test]
fn equality_constraint_is_msls_residue() {
    // MSL Orientation.equalityConstraint(R1, R2), with n = cross(T1[1,:], T1[2,:]):
    //   {atan2(n T2[2,:], T1[1,:] T2[1,:]), atan2(-n T2[1,:], T1[2,:] T2[2,:]),
    //    atan2(T1[2,:] T2[1,:], T1[3,:] T2[3,:])}.
    // With R1 = null and R2 a rotation by 0.5 rad about axis k, component k is
    // atan2(sin 0.5, 1) = atan(sin 0.5) = 0.4470 (not 0.5: exact only for small
    // angles), with the sign of the rotation, and the others vanish.
    for k in 1..=3 {
        for angle in [0.5, -0.5] {
            let r2 = axis_rotation(k, c(angle), c(0.0));
            let res = v(equality_constraint(&null_rotation(), &r2));
            let expected = unit(k).map(|x| x * f64::sin(angle).atan());
            assert_vec(res, expected, 1e-14);
        }
    }
}
