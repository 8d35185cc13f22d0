//! A sliding mass with hard stops and Stribeck friction (MSL
//! `Translational.Components.MassWithStopAndFriction`): stuck, sliding forward or
//! backward, the stops' impacts fully inelastic.

use super::Flange;
use crate::prelude::*;
use crate::rotational::friction_mode::{BACKWARD, FORWARD, FREE, STUCK, UNKNOWN};

component! {
    /// A mass of length `L` sliding between the stops `smin` and `smax` (its ends reach
    /// them) with Stribeck friction against the ground (MSL
    /// `Translational.Components.MassWithStopAndFriction`): sliding at `v` the friction
    /// force is `F_prop v + sign(v) (F_Coulomb + F_Stribeck exp(-fexp |v|))`; at rest it
    /// sticks until the force on it exceeds `1.001 (F_Coulomb + F_Stribeck)`. At a stop
    /// the mass stops dead (`reinit` of position and velocity) and stays there while it is
    /// pushed against it.
    #[type_name = "Translational.MassWithStopAndFriction"]
    pub struct MassWithStopAndFriction {
        /// Mass [kg], default 1.
        parameter m(min = 0.0): f64 = 1.0;
        /// Length of the mass [m], default 0.
        parameter L: f64 = 0.0;
        /// Right stop for the right end of the mass [m], default 25.
        parameter smax: f64 = 25.0;
        /// Left stop for the left end of the mass [m], default -25.
        parameter smin: f64 = -25.0;
        /// Velocity near zero where a `reinit` may jump across zero [m/s], default 1e-3.
        parameter v_small: f64 = 1e-3;
        /// Velocity dependent friction [N.s/m], default 1.
        parameter F_prop(min = 0.0): f64 = 1.0;
        /// Constant (Coulomb) friction [N], default 5.
        parameter F_Coulomb: f64 = 5.0;
        /// Stribeck friction at rest over the Coulomb friction [N], default 10.
        parameter F_Stribeck: f64 = 10.0;
        /// Exponential decay of the Stribeck friction [s/m] (at least 0), default 2.
        parameter fexp(min = 0.0): f64 = 2.0;
        /// Start value of the position of the centre [m], default 0.
        structural s_start: f64 = 0.0;
        /// Start value of the velocity [m/s], default 0.
        structural v_start: f64 = 0.0;
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Position of the centre [m].
        variable s(start = s_start, state_priority = StateSelect::Always.priority()): Real;
        /// Velocity [m/s].
        variable v(start = v_start, state_priority = StateSelect::Always.priority()): Real;
        /// Acceleration [m/s2].
        variable a: Real;
        /// Friction force, positive against positive velocity [N].
        variable f: Real;
        /// Path parameter of the friction characteristic `f = f(a)` [1].
        variable sa: Real;
        /// 1 if the friction is not active (no friction at all, away from the stops).
        variable free(discrete = true, start = 0.0): Real;
        /// 1 if at rest and forward sliding starts.
        variable startForward(discrete = true, start = 0.0): Real;
        /// 1 if at rest and backward sliding starts.
        variable startBackward(discrete = true, start = 0.0): Real;
        /// 1 if at rest and not sliding.
        variable locked(discrete = true, start = 0.0): Real;
        /// The mode, one of [`friction_mode`](crate::rotational::friction_mode).
        variable mode(discrete = true, start = UNKNOWN): Real;
        /// -1 at the left stop, 1 at the right one, 0 between.
        variable stopped(discrete = true, start = 0.0): Real;
        equation {
            let f0 = F_Coulomb + F_Stribeck;
            let f0_max = 1.001 * f0;
            let below_max = lt(s, smax - L / 2.0);
            let above_min = gt(s, smin + L / 2.0);
            let stuck = eq(pre(mode), STUCK);
            let was_forward = eq(pre(mode), FORWARD);
            let was_backward = eq(pre(mode), BACKWARD);
            flange_a.s = s - L / 2.0;
            flange_b.s = s + L / 2.0;
            v = der(s);
            a = der(v);
            free = and(and(le(f0, 0.0), le(F_prop, 0.0)), and(above_min, below_max));
            startForward = or(
                and(stuck, or(
                    and(gt(sa, f0_max), below_max),
                    and(and(pre(startForward), gt(sa, f0)), below_max),
                )),
                or(and(was_backward, gt(v, v_small)), and(initial(), gt(v, 0.0))),
            );
            startBackward = or(
                and(stuck, or(
                    and(lt(sa, -f0_max), above_min),
                    and(and(pre(startBackward), lt(sa, -f0)), above_min),
                )),
                or(and(was_forward, lt(v, -v_small)), and(initial(), lt(v, 0.0))),
            );
            locked = and(
                not(free),
                not(or(or(was_forward, startForward), or(was_backward, startBackward))),
            );
            a = if_else(locked, 0.0, if_else(free, sa, if_else(startForward, sa - f0_max,
                if_else(startBackward, sa + f0_max, if_else(was_forward, sa - f0_max, sa + f0_max)))));
            let from_free = eq(pre(mode), FREE);
            mode = if_else(free, FREE, if_else(
                and(and(or(or(was_forward, from_free), startForward), gt(v, 0.0)), below_max),
                FORWARD,
                if_else(
                    and(and(or(or(was_backward, from_free), startBackward), lt(v, 0.0)), above_min),
                    BACKWARD,
                    STUCK,
                ),
            ));
            0.0 = flange_a.f + flange_b.f - f - m * der(v);
            let stribeck = F_Coulomb + F_Stribeck * exp(-fexp * abs(v));
            f = if_else(locked, sa, if_else(free, 0.0, if_else(startForward, F_prop * v + f0,
                if_else(startBackward, F_prop * v - f0, if_else(was_forward,
                    F_prop * v + stribeck, F_prop * v - stribeck)))));
            stopped = if_else(le(s, smin + L / 2.0), -1.0, if_else(ge(s, smax - L / 2.0), 1.0, 0.0));
            when ne(stopped, 0.0) {
                reinit(s, if_else(lt(stopped, 0.0), smin + L / 2.0, smax - L / 2.0));
                reinit(v, 0.0);
            }
        }
    }
}
