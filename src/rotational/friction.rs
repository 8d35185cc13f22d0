//! Friction with stuck and sliding modes (MSL `Rotational.Interfaces.PartialFriction`
//! and the elements built on it): a discrete `mode` switches between sliding forward,
//! sliding backward and stuck, with the torque that holds the element stuck computed
//! from the rest of the model (the event iteration settles the mode and the torques
//! together).

use super::interfaces::*;
use crate::blocks::RealInput;
use crate::prelude::*;
use crate::tables::{interpolate, interpolate_at, valid};

/// The values of a friction element's `mode` (MSL's constants of `PartialFriction`).
pub mod friction_mode {
    /// The mode is not known yet (the start value).
    pub const UNKNOWN: f64 = 3.0;
    /// The element is not active (a clutch or brake without normal force).
    pub const FREE: f64 = 2.0;
    /// Sliding forward, `w_relfric > 0`.
    pub const FORWARD: f64 = 1.0;
    /// `w_relfric = 0`: stuck, or starting to slide forward or backward.
    pub const STUCK: f64 = 0.0;
    /// Sliding backward, `w_relfric < 0`.
    pub const BACKWARD: f64 = -1.0;
}

use friction_mode::{BACKWARD, FORWARD, FREE, STUCK};

component! {
    /// The stuck/sliding logic of a friction element (MSL
    /// `Rotational.Interfaces.PartialFriction`): an element extends it and gives
    /// `w_relfric`, `a_relfric`, `tau0`, `tau0_max` and `free`, and its friction torque
    /// from `locked`, `startForward`, `startBackward` and `mode` (`sa` when locked).
    #[type_name = "Rotational.PartialFriction"]
    pub struct PartialFriction {
        /// Relative angular velocity near zero, where a `reinit` of the velocity may jump
        /// across zero [rad/s], default 1e10 (no such jumps).
        parameter w_small: f64 = 1.0e10;
        /// Relative angular velocity between the frictional surfaces [rad/s].
        variable w_relfric: Real;
        /// Relative angular acceleration between the frictional surfaces [rad/s2].
        variable a_relfric: Real;
        /// Friction torque for w = 0 and forward sliding [N.m].
        variable tau0: Real;
        /// Maximum friction torque for w = 0 and locked [N.m].
        variable tau0_max: Real;
        /// 1 if the element is not active (discrete).
        variable free(discrete = true, start = 0.0): Real;
        /// Path parameter of the friction characteristic `tau = f(a_relfric)` [1].
        variable sa: Real;
        /// 1 if `w_relfric = 0` and forward sliding starts (discrete).
        variable startForward(discrete = true, start = 0.0): Real;
        /// 1 if `w_relfric = 0` and backward sliding starts (discrete).
        variable startBackward(discrete = true, start = 0.0): Real;
        /// 1 if `w_relfric = 0` and not sliding (discrete).
        variable locked(discrete = true, start = 0.0): Real;
        /// The mode, one of [`friction_mode`] (discrete; starts unknown).
        variable mode(discrete = true, start = friction_mode::UNKNOWN): Real;
        equation {
            let stuck = eq(pre(mode), STUCK);
            let was_forward = eq(pre(mode), FORWARD);
            let was_backward = eq(pre(mode), BACKWARD);
            startForward = or(
                and(stuck, or(gt(sa, tau0_max), and(pre(startForward), gt(sa, tau0)))),
                or(
                    and(was_backward, gt(w_relfric, w_small)),
                    and(initial(), gt(w_relfric, 0.0)),
                ),
            );
            startBackward = or(
                and(stuck, or(lt(sa, -tau0_max), and(pre(startBackward), lt(sa, -tau0)))),
                or(
                    and(was_forward, lt(w_relfric, -w_small)),
                    and(initial(), lt(w_relfric, 0.0)),
                ),
            );
            locked = and(
                not(free),
                not(or(or(was_forward, startForward), or(was_backward, startBackward))),
            );
            a_relfric = if_else(
                locked,
                0.0,
                if_else(
                    free,
                    sa,
                    if_else(
                        startForward,
                        sa - tau0_max,
                        if_else(
                            startBackward,
                            sa + tau0_max,
                            if_else(was_forward, sa - tau0_max, sa + tau0_max),
                        ),
                    ),
                ),
            );
            let from_free = eq(pre(mode), FREE);
            mode = if_else(
                free,
                FREE,
                if_else(
                    and(or(or(was_forward, from_free), startForward), gt(w_relfric, 0.0)),
                    FORWARD,
                    if_else(
                        and(or(or(was_backward, from_free), startBackward), lt(w_relfric, 0.0)),
                        BACKWARD,
                        STUCK,
                    ),
                ),
            );
        }
    }
}

/// The sliding value of a friction characteristic `table` (rows `[w, value]`, `w >= 0`)
/// at `w`: `f(w)` when sliding forward or starting to, `-f(-w)` backward.
fn sliding(
    table: &[[f64; 2]],
    w: Expr,
    start_forward: Expr,
    start_backward: Expr,
    mode: Expr,
) -> Expr {
    let forward = interpolate(table, w, false);
    let backward = -interpolate(table, -w, false);
    if_else(
        start_forward,
        forward,
        if_else(
            start_backward,
            backward,
            if_else(eq(pre(mode), FORWARD), forward, backward),
        ),
    )
}

/// Checks of a friction characteristic.
fn characteristic_ok(table: &[[f64; 2]]) -> bool {
    valid(table) && table[0][0] == 0.0
}

component! {
    /// Coulomb friction in a bearing (MSL `Rotational.Components.BearingFriction`): the
    /// friction torque `tau_pos(w)` opposes the rotation of the flanges relative to the
    /// support; at rest the element sticks until the torque on it exceeds
    /// `peak * tau_pos(0)`.
    #[type_name = "Rotational.BearingFriction"]
    pub struct BearingFriction {
        /// Positive sliding friction characteristic, rows `[w (rad/s), tau (N.m)]` for
        /// `w >= 0` from `w = 0`, linear between the rows and beyond the last two;
        /// default `[[0, 1]]`.
        structural tau_pos: Vec<[f64; 2]> = vec![[0.0, 1.0]];
        /// Peak of the friction torque at w = 0, `tau0_max = peak * tau_pos(0)` (at least
        /// 1), default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Whether the housing is a connector (`support`) rather than fixed, default false.
        structural use_support: bool = false;
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange (rigidly connected to `flange_a`).
        connector flange_b: Flange;
        /// Housing (used only with `use_support`).
        connector support: Flange;
        extends PartialFriction { w_relfric, a_relfric, tau0, tau0_max, free, sa, startForward, startBackward, locked, mode };
        /// Angle of the flanges relative to the support [rad].
        variable phi: Real;
        /// Angular velocity relative to the support [rad/s].
        variable w: Real;
        /// Angular acceleration relative to the support [rad/s2].
        variable a: Real;
        /// Friction torque [N.m].
        variable tau: Real;
        equation {
            assert(
                characteristic_ok(&tau_pos),
                "tau_pos needs rows [w, tau] from w = 0, finite, w increasing"
            );
            tau0 = interpolate_at(&tau_pos, 0.0);
            tau0_max = peak * tau0;
            free = 0.0;
            phi = flange_a.phi - support.phi;
            flange_b.phi = flange_a.phi;
            w = der(phi);
            a = der(w);
            w_relfric = w;
            a_relfric = a;
            0.0 = flange_a.tau + flange_b.tau - tau;
            tau = if_else(locked, sa, sliding(&tau_pos, w, startForward, startBackward, mode));
            if use_support {
                support.tau = -flange_a.tau - flange_b.tau;
            } else {
                support.phi = 0.0;
            }
        }
    }
}

component! {
    /// A brake between the flanges and the support (MSL `Rotational.Components.Brake`):
    /// the normal force `f_n = fn_max * f_normalized` presses the surfaces together, the
    /// friction torque is `cgeo * f_n * mu_pos(w)` sliding and at most
    /// `peak * cgeo * f_n * mu_pos(0)` stuck; free without normal force.
    #[type_name = "Rotational.Brake"]
    pub struct Brake {
        /// Positive sliding friction coefficient, rows `[w (rad/s), mu (1)]` for `w >= 0`
        /// from `w = 0`; default `[[0, 0.5]]`.
        structural mu_pos: Vec<[f64; 2]> = vec![[0.0, 0.5]];
        /// Peak of the friction coefficient at w = 0 (at least 1), default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Geometry constant of the friction distribution [m], default 1.
        parameter cgeo(min = 0.0): f64 = 1.0;
        /// Maximum normal force [N], default 1.
        parameter fn_max(min = 0.0): f64 = 1.0;
        /// Whether the housing is a connector (`support`) rather than fixed, default false.
        structural use_support: bool = false;
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange (rigidly connected to `flange_a`).
        connector flange_b: Flange;
        /// Housing (used only with `use_support`).
        connector support: Flange;
        /// Normalized normal force (0..1).
        connector f_normalized: RealInput;
        extends PartialFriction { w_relfric, a_relfric, tau0, tau0_max, free, sa, startForward, startBackward, locked, mode };
        /// Angle of the flanges relative to the support [rad].
        variable phi: Real;
        /// Angular velocity relative to the support [rad/s].
        variable w: Real;
        /// Angular acceleration relative to the support [rad/s2].
        variable a: Real;
        /// Friction torque [N.m].
        variable tau: Real;
        /// Normal force (MSL's `fn`) [N].
        variable f_n: Real;
        equation {
            assert(
                characteristic_ok(&mu_pos),
                "mu_pos needs rows [w, mu] from w = 0, finite, w increasing"
            );
            let mu0 = interpolate_at(&mu_pos, 0.0);
            phi = flange_a.phi - support.phi;
            flange_b.phi = flange_a.phi;
            w = der(phi);
            a = der(w);
            w_relfric = w;
            a_relfric = a;
            0.0 = flange_a.tau + flange_b.tau - tau;
            f_n = fn_max * f_normalized;
            tau0 = mu0 * cgeo * f_n;
            tau0_max = peak * tau0;
            free = le(f_n, 0.0);
            tau = if_else(
                locked,
                sa,
                if_else(free, 0.0, cgeo * f_n * sliding(&mu_pos, w, startForward, startBackward, mode)),
            );
            if use_support {
                support.tau = -flange_a.tau - flange_b.tau;
            } else {
                support.phi = 0.0;
            }
        }
    }
}

component! {
    /// A clutch between two flanges (MSL `Rotational.Components.Clutch`): the normal
    /// force `f_n = fn_max * f_normalized` presses the plates together; the torque is
    /// `cgeo * f_n * mu_pos(w_rel)` sliding and at most `peak * cgeo * f_n * mu_pos(0)`
    /// locked; free without normal force.
    #[type_name = "Rotational.Clutch"]
    pub struct Clutch {
        /// Positive sliding friction coefficient, rows `[w (rad/s), mu (1)]` for `w >= 0`
        /// from `w = 0`; default `[[0, 0.5]]`.
        structural mu_pos: Vec<[f64; 2]> = vec![[0.0, 0.5]];
        /// Peak of the friction coefficient at w = 0 (at least 1), default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Geometry constant of the friction distribution [m], default 1.
        parameter cgeo(min = 0.0): f64 = 1.0;
        /// Maximum normal force [N], default 1.
        parameter fn_max(min = 0.0): f64 = 1.0;
        /// Normalized normal force (0..1).
        connector f_normalized: RealInput;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, phi_rel, w_rel, a_rel, tau };
        extends PartialFriction { w_relfric, a_relfric, tau0, tau0_max, free, sa, startForward, startBackward, locked, mode };
        /// Normal force (MSL's `fn`) [N].
        variable f_n: Real;
        equation {
            assert(
                characteristic_ok(&mu_pos),
                "mu_pos needs rows [w, mu] from w = 0, finite, w increasing"
            );
            let mu0 = interpolate_at(&mu_pos, 0.0);
            w_relfric = w_rel;
            a_relfric = a_rel;
            f_n = fn_max * f_normalized;
            free = le(f_n, 0.0);
            tau0 = mu0 * cgeo * f_n;
            tau0_max = peak * tau0;
            tau = if_else(
                locked,
                sa,
                if_else(free, 0.0, cgeo * f_n * sliding(&mu_pos, w_rel, startForward, startBackward, mode)),
            );
        }
    }
}

component! {
    /// A freewheel in parallel with a clutch (MSL `Rotational.Components.OneWayClutch`):
    /// `flange_b` may overrun `flange_a` (`w_rel = w_b - w_a >= 0`, sliding against the
    /// clutch's friction `mu_pos(w_rel) cgeo fn`), while torque that would turn it
    /// backwards relative to `flange_a` locks the freewheel; a locked freewheel opens
    /// once its torque exceeds `peak cgeo fn mu_pos(0)` (a tiny value without normal
    /// force). `w_rel` must not start negative.
    #[type_name = "Rotational.OneWayClutch"]
    pub struct OneWayClutch {
        /// Positive sliding friction coefficient, rows `[w (rad/s), mu (1)]` for `w >= 0`
        /// from `w = 0`; default `[[0, 0.5]]`.
        structural mu_pos: Vec<[f64; 2]> = vec![[0.0, 0.5]];
        /// Peak of the friction coefficient at w = 0 (at least 1), default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Geometry constant of the friction distribution [m], default 1.
        parameter cgeo(min = 0.0): f64 = 1.0;
        /// Maximum normal force [N], default 1.
        parameter fn_max(min = 0.0): f64 = 1.0;
        /// Relative speed above which the freewheel opens whatever the torque [rad/s],
        /// default 1e10.
        parameter w_small: f64 = 1.0e10;
        /// Normalized normal force of the clutch (0..1).
        connector f_normalized: RealInput;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, phi_rel, w_rel, a_rel, tau };
        /// Normal force (MSL's `fn`) [N].
        variable f_n: Real;
        /// Friction coefficient at `w_rel` [1].
        variable mu: Real;
        /// Path parameter of the characteristic [1]: the torque while locked.
        variable sa: Real;
        /// 1 without normal force (discrete).
        variable free(discrete = true, start = 0.0): Real;
        /// 1 if `w_rel = 0` and forward sliding starts (discrete).
        variable startForward(discrete = true, start = 0.0): Real;
        /// 1 if `w_rel = 0` and not sliding (discrete).
        variable locked(discrete = true, start = 0.0): Real;
        /// 1 if `w_rel = 0`, locked or starting to slide (discrete).
        variable stuck(discrete = true, start = 0.0): Real;
        equation {
            assert(
                characteristic_ok(&mu_pos),
                "mu_pos needs rows [w, mu] from w = 0, finite, w increasing"
            );
            let mu0 = interpolate_at(&mu_pos, 0.0);
            free = le(f_normalized, 0.0);
            f_n = if_else(free, 0.0, fn_max * f_normalized);
            let tau0 = mu0 * cgeo * f_n;
            let tau0_max = if_else(free, 1e-4 * mu0 * cgeo * fn_max, max(peak, 1.0 + 1e-4) * tau0);
            startForward = or(
                and(pre(stuck), or(or(gt(sa, tau0_max), and(pre(startForward), gt(sa, tau0))), gt(w_rel, w_small))),
                and(initial(), gt(w_rel, 0.0)),
            );
            locked = and(pre(stuck), not(startForward));
            mu = interpolate(&mu_pos, w_rel, false);
            a_rel = if_else(locked, 0.0, sa - tau0);
            tau = if_else(locked, sa, if_else(free, 0.0, mu * cgeo * f_n));
            stuck = or(locked, le(w_rel, 0.0));
        }
    }
}

component! {
    /// A spring and damper with backlash `b` (MSL `Rotational.Components.ElastoBacklash`):
    /// no torque within `|phi_rel - phi_rel0| <= b/2`; beyond, the spring `c` and the
    /// damper `d`, the damping limited so that the element never pulls and its torque is
    /// continuous at contact. Unlike MSL, the initialization uses the same
    /// characteristic (MSL smooths the gap there).
    #[type_name = "Rotational.ElastoBacklash"]
    pub struct ElastoBacklash {
        /// Spring constant [N.m/rad], default 1e5.
        parameter c(min = 0.0): f64 = 1.0e5;
        /// Damping constant [N.m.s/rad], default 0.
        parameter d(min = 0.0): f64 = 0.0;
        /// Total backlash [rad] (at least 0), default 0.
        parameter b(min = 0.0): f64 = 0.0;
        /// Unstretched spring angle [rad], default 0.
        parameter phi_rel0: f64 = 0.0;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, phi_rel, w_rel, tau };
        /// Spring torque [N.m].
        variable tau_c: Real;
        /// Damping torque [N.m].
        variable tau_d: Real;
        equation {
            let phi_diff = phi_rel - phi_rel0;
            let b_max = b / 2.0;
            let no_gap = le(abs(b), 1e-10);
            let above = gt(phi_diff, b_max);
            let below = lt(phi_diff, -b_max);
            tau_c = if_else(no_gap, c * phi_diff, if_else(above, c * (phi_diff - b_max),
                if_else(below, c * (phi_diff + b_max), 0.0)));
            tau_d = d * w_rel;
            let pushing = no_event(if_else(le(tau_c + tau_d, 0.0), 0.0, tau_c + min(tau_c, tau_d)));
            let pulling = no_event(if_else(ge(tau_c + tau_d, 0.0), 0.0, tau_c + max(tau_c, tau_d)));
            tau = if_else(no_gap, tau_c + tau_d, if_else(above, pushing, if_else(below, pulling, 0.0)));
        }
    }
}
