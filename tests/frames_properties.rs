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
