//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007), built from
//! bodies, joints and rolling contacts (`examples/bicycle.rs`): its linearization in
//! upright, straight running against the paper's lean-steer matrices, eigenvalues and
//! weave and capsize speeds (all to 1e-10 or better), and its nonlinear motion against
//! an independent model (1e-7).

use multibody::nalgebra::{DMatrix, Matrix2};
use multibody::prelude::*;
use multibody::{LinearModel, SimplifyOptions, linearize_in, structural_simplify_with};

#[path = "../examples/bicycle.rs"]
#[allow(dead_code)]
mod bicycle_example;
use bicycle_example::{R_REAR, STATES, bicycle, straight_run};

const G: f64 = 9.81;

/// The paper's lean-steer matrices (Table 2): M, C1, K0, K2 (rows lean, steer).
const M: [[f64; 2]; 2] = [
    [80.81722, 2.31941332208709],
    [2.31941332208709, 0.29784188199686],
];
const C1: [[f64; 2]; 2] = [
    [0.0, 33.86641391492494],
    [-0.85035641456978, 1.68540397397560],
];
const K0: [[f64; 2]; 2] = [
    [-80.95, -2.59951685249872],
    [-2.59951685249872, -0.80329488458618],
];
const K2: [[f64; 2]; 2] = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];

fn simplified() -> SimplifiedSystem {
    let options = SimplifyOptions {
        open_inputs: true,
        ..SimplifyOptions::default()
    };
    structural_simplify_with(&bicycle(), &options).unwrap()
}

/// The bicycle linearized in upright, straight running at `speed`.
fn linear_at(ssys: &SimplifiedSystem, speed: f64) -> LinearModel {
    let problem = DaeProblem::new(ssys, &straight_run(speed, 0.0), (0.0, 1.0)).unwrap();
    let inputs = ["lean_torque.tau", "steer_torque.tau"];
    linearize_in(ssys, &problem.operating_point(), &inputs, &[], &STATES).unwrap()
}

/// The lean-steer block: `(M, K(v), C(v))` with `M q'' + C(v) q' + K(v) q = T`.
fn lean_steer(lin: &LinearModel) -> (Matrix2<f64>, Matrix2<f64>, Matrix2<f64>) {
    let b = Matrix2::new(lin.b[(2, 0)], lin.b[(2, 1)], lin.b[(3, 0)], lin.b[(3, 1)]);
    let m = b.try_inverse().expect("the input matrix is invertible");
    let a = |i: usize, j: usize| lin.a[(i, j)];
    let k = -m * Matrix2::new(a(2, 0), a(2, 1), a(3, 0), a(3, 1));
    let c = -m * Matrix2::new(a(2, 2), a(2, 3), a(3, 2), a(3, 3));
    (m, k, c)
}

/// The eigenvalues of the lean-steer block of `lin`.
fn eigenvalues(lin: &LinearModel) -> Vec<multibody::nalgebra::Complex<f64>> {
    let a = DMatrix::from_fn(4, 4, |i, j| lin.a[(i, j)]);
    let mut e: Vec<_> = a.complex_eigenvalues().iter().copied().collect();
    e.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    e
}

fn assert_close(name: &str, got: Matrix2<f64>, want: [[f64; 2]; 2], tol: f64) {
    for i in 0..2 {
        for j in 0..2 {
            let (g, w) = (got[(i, j)], want[i][j]);
            assert!(
                (g - w).abs() <= tol * w.abs().max(1.0),
                "{name}[{i},{j}] = {g}, paper {w}"
            );
        }
    }
}

#[test]
fn the_lean_steer_matrices_are_the_papers() {
    let ssys = simplified();
    let at_rest = linear_at(&ssys, 0.0);
    let at_5 = linear_at(&ssys, 5.0);
    let (m, k_rest, _) = lean_steer(&at_rest);
    let (m5, k5, c5) = lean_steer(&at_5);
    assert_close("M", m, M, 1e-10);
    assert_close("M at 5 m/s", m5, M, 1e-10);
    assert_close("K0", k_rest / G, K0, 1e-10);
    assert_close("K2", (k5 - k_rest) / 25.0, K2, 1e-10);
    assert_close("C1", c5 / 5.0, C1, 1e-10);
    // Lean and steer do not feel the speed, the position or the heading at first order.
    for row in 2..4 {
        for col in 4..10 {
            assert!(
                at_5.a[(row, col)].abs() < 1e-8,
                "A[{row},{col}] = {}",
                at_5.a[(row, col)]
            );
        }
    }
}

#[test]
fn the_eigenvalues_are_the_papers() {
    // Table 2 of the paper at 0, 2, 5 and 8 m/s (the weave a complex pair from 0.68 m/s).
    let table: [(f64, [(f64, f64); 4]); 4] = [
        (
            0.0,
            [
                (-5.53094371765393, 0.0),
                (-3.13164324790656, 0.0),
                (3.13164324790656, 0.0),
                (5.53094371765393, 0.0),
            ],
        ),
        (
            2.0,
            [
                (-8.67387984831735, 0.0),
                (-3.07158645641514, 0.0),
                (2.68234517512745, -1.68066296590675),
                (2.68234517512745, 1.68066296590675),
            ],
        ),
        (
            5.0,
            [
                (-14.0783896927982, 0.0),
                (-0.77534188219585, -4.46486771378823),
                (-0.77534188219585, 4.46486771378823),
                (-0.32286642900409, 0.0),
            ],
        ),
        (
            8.0,
            [
                (-20.27940894394569, 0.0),
                (-2.69348683581097, -8.46037971396931),
                (-2.69348683581097, 8.46037971396931),
                (0.14327879765713, 0.0),
            ],
        ),
    ];
    let ssys = simplified();
    for (speed, want) in table {
        let got = eigenvalues(&linear_at(&ssys, speed));
        for (g, (re, im)) in got.iter().zip(want) {
            let scale = (re * re + im * im).sqrt().max(1.0);
            assert!(
                (g.re - re).abs() < 1e-10 * scale && (g.im - im).abs() < 1e-10 * scale,
                "v = {speed}: {got:?}"
            );
        }
    }
}

/// The speed in `(lo, hi)` where `unstable` changes, by bisection.
fn crossing(lo: f64, hi: f64, unstable: impl Fn(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let at_lo = unstable(lo);
    assert_ne!(at_lo, unstable(hi));
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if unstable(mid) == at_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn the_weave_and_capsize_speeds_are_the_papers() {
    let ssys = simplified();
    let eig = |v: f64| eigenvalues(&linear_at(&ssys, v));
    // The weave pair's real part, the capsize root.
    let weave = crossing(4.0, 4.5, |v| {
        eig(v).iter().any(|e| e.im.abs() > 1e-9 && e.re > 0.0)
    });
    let capsize = crossing(5.5, 6.5, |v| {
        eig(v).iter().any(|e| e.im.abs() <= 1e-9 && e.re > 0.0)
    });
    assert!(
        (weave - 4.29238253634111).abs() < 1e-9,
        "weave speed {weave}"
    );
    assert!(
        (capsize - 6.02426201538837).abs() < 1e-9,
        "capsize speed {capsize}"
    );
}

#[test]
fn it_rides_itself_upright_at_4_6_m_s_and_capsizes_slowly_at_8() {
    // The paper's figure 4 (4.6 m/s, a lean-rate kick of 0.5 rad/s) and the IFToMM
    // benchmark's third case (8 m/s, 0.05 rad/s), against an independent nonlinear model
    // (Kane's equations of the same bicycle, integrated to 1e-11).
    let ssys = simplified();
    let ride = |speed: f64, kick: f64| {
        DaeProblem::new(&ssys, &straight_run(speed, kick), (0.0, 5.0))
            .unwrap()
            .solve(&SolverOptions {
                rtol: 1e-10,
                atol: 1e-12,
                output_times: Some((0..=50).map(|k| 0.1 * k as f64).collect()),
                ..SolverOptions::default()
            })
            .unwrap()
    };
    let check = |sol: &Solution, t: f64, want: [f64; 5]| {
        let got = [
            sol.at("lean.phi", t).unwrap(),
            sol.at("lean.w", t).unwrap(),
            sol.at("steer.phi", t).unwrap(),
            sol.at("steer.w", t).unwrap(),
            R_REAR * sol.at("rear_spin.w", t).unwrap(),
        ];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-7, "t = {t}: {got:?}, reference {want:?}");
        }
    };
    let recovering = ride(4.6, 0.5);
    check(
        &recovering,
        1.0,
        [
            -0.0412938697,
            -0.2111017343,
            -0.0399884870,
            -0.3224040101,
            4.6216858189,
        ],
    );
    check(
        &recovering,
        2.5,
        [
            -0.0088048396,
            -0.1474630346,
            -0.0019421588,
            -0.1973883349,
            4.6203491619,
        ],
    );
    check(
        &recovering,
        5.0,
        [
            0.0103424406,
            0.0399265379,
            0.0081856710,
            0.0614073508,
            4.6225355604,
        ],
    );
    let capsizing = ride(8.0, 0.05);
    check(
        &capsizing,
        5.0,
        [
            0.0062207915,
            0.0008913104,
            0.0010028179,
            0.0001436505,
            8.0001873700,
        ],
    );
    // Past the weave its lean settles; past the capsize speed it keeps growing.
    let lean_at = |sol: &Solution, t: f64| sol.at("lean.phi", t).unwrap();
    assert!(lean_at(&recovering, 5.0).abs() < 0.1 * lean_at(&recovering, 0.5).abs());
    assert!(lean_at(&capsizing, 5.0) > lean_at(&capsizing, 3.0));
}
