//! Reference motions for point-to-point moves (MSL `Blocks.Sources.KinematicPTP2`).

use super::interfaces::RealOutput;
use crate::prelude::*;

/// The common time profile of a point-to-point move of several axes (MSL
/// `KinematicPTP2`): the path parameter `s` goes from 0 to 1 with at most the speed and
/// acceleration every axis allows, accelerating, at constant speed (unless the move is
/// too short for it) and braking.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Profile {
    /// Maximum path speed [1/s].
    sd_max: f64,
    /// Path acceleration [1/s2].
    sdd_max: f64,
    /// End of the acceleration phase [s] (from the start).
    ta: f64,
    /// Start of the braking phase [s].
    tv: f64,
    /// End of the move [s].
    te: f64,
    /// Path parameter at the end of the acceleration phase.
    s1: f64,
    /// Path parameter at the start of the braking phase.
    s2: f64,
    /// Path parameter at the end (1 up to rounding).
    s_end: f64,
    /// Whether there is no phase of constant speed.
    no_w_phase: bool,
}

/// Below this a move is no move (MSL's `10 eps`).
const EPS: f64 = 10.0 * f64::EPSILON;

/// The profile of moves `dq` with the speed and acceleration limits `qd_max`,
/// `qdd_max`; `None` when nothing moves.
fn profile(dq: &[f64], qd_max: &[f64], qdd_max: &[f64]) -> Option<Profile> {
    let max_ratio = |limits: &[f64]| {
        dq.iter()
            .zip(limits)
            .map(|(d, l)| (d / l).abs())
            .fold(0.0, f64::max)
    };
    let (sd_inv, sdd_inv) = (max_ratio(qd_max), max_ratio(qdd_max));
    if sd_inv <= EPS || sdd_inv <= EPS {
        return None;
    }
    let (sd_max, sdd_max) = (1.0 / sd_inv, 1.0 / sdd_inv);
    let ta1 = (1.0 / sdd_max).sqrt();
    let ta2 = sd_max / sdd_max;
    let no_w_phase = ta2 >= ta1;
    let (ta, tv, te) = if no_w_phase {
        (ta1, ta1, 2.0 * ta1)
    } else {
        (ta2, 1.0 / sd_max, 1.0 / sd_max + ta2)
    };
    let sd_peak = sdd_max * ta;
    let s1 = sdd_max * ta * ta / 2.0;
    // Braking starts at tv (= ta without a phase of constant speed) at the path speed
    // sd_peak (= sd_max with one).
    let s2 = s1 + sd_peak * (tv - ta);
    let s_end = s2 + sd_peak * (te - tv) - sdd_max / 2.0 * (te - tv) * (te - tv);
    Some(Profile {
        sd_max: if no_w_phase { sd_peak } else { sd_max },
        sdd_max,
        ta,
        tv,
        te,
        s1,
        s2,
        s_end,
        no_w_phase,
    })
}

/// The path parameter `s`, its speed and its acceleration at `time` for the move of
/// `p` from `start`, and whether it still moves (1 or 0): expressions whose phase
/// changes (accelerating, at constant speed, braking, arrived) are time events.
fn path(p: &Profile, time: Expr, start: Expr) -> [Expr; 4] {
    let t = time - start;
    let (a, v) = (p.sdd_max, p.sd_max);
    let (cruise, braking) = (t - p.ta, t - p.tv);
    let before = lt(time, start);
    let accelerating = lt(time, start + p.ta);
    let cruising = lt(time, start + p.tv);
    let moving = lt(time, start + p.te);
    let phases = |acc: Expr, cru: Expr, brk: Expr, end: f64| {
        if_else(
            before,
            0.0,
            if_else(
                accelerating,
                acc,
                if_else(cruising, cru, if_else(moving, brk, end)),
            ),
        )
    };
    [
        phases(
            a / 2.0 * t * t,
            p.s1 + v * cruise,
            p.s2 + v * braking - a / 2.0 * braking * braking,
            p.s_end,
        ),
        phases(a * t, Expr::from(v), v - a * braking, 0.0),
        phases(Expr::from(a), Expr::from(0.0), Expr::from(-a), 0.0),
        if_else(moving, 1.0, 0.0),
    ]
}

/// Expands a vector of one element to `n`.
fn expanded(v: &[f64], n: usize) -> Vec<f64> {
    if v.len() == 1 {
        vec![v[0]; n]
    } else {
        v.to_vec()
    }
}

/// The number of axes of the four vectors (the longest; the others of that length or 1).
fn axes(vectors: [&[f64]; 4]) -> Option<usize> {
    let n = vectors.iter().map(|v| v.len()).max()?;
    vectors
        .iter()
        .all(|v| v.len() == n || v.len() == 1)
        .then_some(n)
}

component! {
    /// The reference of one axis of a point-to-point move (MSL
    /// `Blocks.Sources.KinematicPTP2`): all axes of the vectors start at `start_time` and
    /// arrive together, each within its speed and acceleration limits (the slowest axis
    /// sets the time); `q`, `qd`, `qdd` are those of axis `axis` (from 0). The corners of
    /// the profile are time events. A vector of one element applies to every axis.
    #[type_name = "Blocks.KinematicPTP2"]
    pub struct KinematicPTP2 {
        /// Start positions of the axes, default `[0]`.
        structural q_begin: Vec<f64> = vec![0.0];
        /// End positions of the axes, default `[1]`.
        structural q_end: Vec<f64> = vec![1.0];
        /// Maximum speeds (positive), default `[1]`.
        structural qd_max: Vec<f64> = vec![1.0];
        /// Maximum accelerations (positive), default `[1]`.
        structural qdd_max: Vec<f64> = vec![1.0];
        /// The axis this block outputs (from 0), default 0.
        structural axis: usize = 0;
        /// Time the move starts [s], default 0.
        parameter start_time: f64 = 0.0;
        /// Reference position.
        connector q: RealOutput;
        /// Reference speed.
        connector qd: RealOutput;
        /// Reference acceleration.
        connector qdd: RealOutput;
        /// 1 while the axis moves (it moves at all and `time < end_time`), else 0.
        connector moving: RealOutput;
        /// Time the move ends [s].
        connector end_time: RealOutput;
        equation {
            let n = axes([&q_begin, &q_end, &qd_max, &qdd_max]);
            assert(n.is_some(), "q_begin, q_end, qd_max and qdd_max need equal lengths (or 1)");
            assert(
                qd_max.iter().chain(&qdd_max).all(|&x| x > 0.0 && x.is_finite()),
                "qd_max and qdd_max must be positive"
            );
            assert(axis < n.unwrap_or(0), "axis must be one of the vectors' axes");
            let n = n.unwrap_or(1).max(axis + 1);
            let (qb, qe) = (expanded(&q_begin, n), expanded(&q_end, n));
            let dq: Vec<f64> = qb.iter().zip(&qe).map(|(b, e)| e - b).collect();
            let p = profile(&dq, &expanded(&qd_max, n), &expanded(&qdd_max, n));
            let (q0, d) = (qb.get(axis).copied().unwrap_or(0.0), dq.get(axis).copied().unwrap_or(0.0));
            match p {
                None => {
                    q = q0;
                    qd = 0.0;
                    qdd = 0.0;
                    end_time = start_time;
                    moving = 0.0;
                }
                Some(p) => {
                    let [s, sd, sdd, moving_now] = path(&p, time, start_time.into());
                    q = q0 + d * s;
                    qd = d * sd;
                    qdd = d * sdd;
                    end_time = start_time + p.te;
                    moving = if d.abs() > EPS { moving_now } else { Expr::from(0.0) };
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_of_msl_one_axis() {
        // OneAxis: 0 to 120 deg at 3 rad/s and 10 rad/s2: accelerating 0.3 s, braking
        // from 0.6981317 s, arriving at 0.9981317 s (MSL's reference).
        let dq = 120f64.to_radians();
        let p = profile(&[dq], &[3.0], &[10.0]).unwrap();
        assert!(!p.no_w_phase);
        assert!((p.ta - 0.3).abs() < 1e-15);
        assert!((p.tv - 0.6981317007977317).abs() < 1e-14);
        assert!((p.te - 0.9981317007977317).abs() < 1e-14);
        // s arrives at 1: s2 plus the braking distance.
        assert!((p.s_end - 1.0).abs() < 1e-14);
    }

    #[test]
    fn a_short_move_has_no_phase_of_constant_speed() {
        // 0.1 rad at most 1 rad/s and 1 rad/s2: a triangle of 2 sqrt(0.1) s.
        let p = profile(&[0.1], &[1.0], &[1.0]).unwrap();
        assert!(p.no_w_phase);
        assert!((p.te - 2.0 * 0.1f64.sqrt()).abs() < 1e-15);
        assert!((p.s_end - 1.0).abs() < 1e-14);
        assert!(profile(&[0.0], &[1.0], &[1.0]).is_none());
    }
}

component! {
    /// The acceleration of one axis of a point-to-point move over the distances `deltaq`
    /// (MSL `Blocks.Sources.KinematicPTP`): the profile of [`KinematicPTP2`], whose
    /// integral twice is the position. A vector of one element applies to every axis.
    #[type_name = "Blocks.KinematicPTP"]
    pub struct KinematicPTP {
        /// Distances to move, default `[1]`.
        structural deltaq: Vec<f64> = vec![1.0];
        /// Maximum speeds (positive), default `[1]`.
        structural qd_max: Vec<f64> = vec![1.0];
        /// Maximum accelerations (positive), default `[1]`.
        structural qdd_max: Vec<f64> = vec![1.0];
        /// The axis this block outputs (from 0), default 0.
        structural axis: usize = 0;
        /// Time the move starts [s], default 0.
        parameter start_time: f64 = 0.0;
        /// Reference acceleration.
        connector y: RealOutput;
        equation {
            let zero = [0.0];
            let n = axes([&deltaq, &zero, &qd_max, &qdd_max]);
            assert(n.is_some(), "deltaq, qd_max and qdd_max need equal lengths (or 1)");
            assert(
                qd_max.iter().chain(&qdd_max).all(|&x| x > 0.0 && x.is_finite()),
                "qd_max and qdd_max must be positive"
            );
            assert(axis < n.unwrap_or(0), "axis must be one of the vectors' axes");
            let n = n.unwrap_or(1).max(axis + 1);
            let dq = expanded(&deltaq, n);
            let d = dq.get(axis).copied().unwrap_or(0.0);
            match profile(&dq, &expanded(&qd_max, n), &expanded(&qdd_max, n)) {
                None => {
                    y = 0.0;
                }
                Some(p) => {
                    let [_, _, sdd, _] = path(&p, time, start_time.into());
                    y = d * sdd;
                }
            }
        }
    }
}
