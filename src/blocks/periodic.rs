//! Periodic sources of time (MSL `Blocks.Sources.Pulse`, `SawTooth`, `Trapezoid`):
//! each period starts at a sample instant (a time event), and the edges within it are
//! time events of their relations.

use super::interfaces::RealOutput;
use crate::prelude::*;

/// Whether the periodic source is past its last period: `nperiod >= 0` periods done
/// (`count >= nperiod`; `nperiod < 0` never ends).
fn finished(nperiod: Expr, count: Expr) -> Expr {
    ge(nperiod, 0.0) * ge(count, nperiod)
}

component! {
    /// A pulse train (MSL `Blocks.Sources.Pulse`): `offset + amplitude` for the first
    /// `width` percent of each `period` from `start_time`, `offset` otherwise, for
    /// `nperiod` periods (`< 0`: without end). The initial time must not be later than
    /// `start_time`.
    #[type_name = "Blocks.Pulse"]
    pub struct Pulse {
        /// Amplitude of the pulse, default 1.
        parameter amplitude: f64 = 1.0;
        /// Width of the pulse in % of the period (0 to 100), default 50.
        parameter width(min = 0.0, max = 100.0): f64 = 50.0;
        /// Period \[s\] (greater than 0), default 1.
        parameter period(min = 0.0): f64 = 1.0;
        /// Number of periods (an integer; `< 0`: without end), default -1.
        parameter nperiod: f64 = -1.0;
        /// Offset of the output, default 0.
        parameter offset: f64 = 0.0;
        /// Start of the first period \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        /// Start of the current period \[s\].
        variable t_start(start = start_time): Real;
        /// Periods completed.
        variable count(start = 0.0): Real;
        equation {
            assert(gt(period, 0.0), "the period must be greater than 0");
            when sample(start_time + period, period) {
                count = pre(count) + 1.0;
                t_start = time;
            }
            let on = if_else(lt(time, t_start + period * width / 100.0), amplitude, 0.0);
            y = offset
                + if_else(lt(time, start_time), 0.0, if_else(finished(nperiod, count), 0.0, on));
        }
    }
}

component! {
    /// A saw tooth (MSL `Blocks.Sources.SawTooth`): rising from `offset` to
    /// `offset + amplitude` over each `period` from `start_time`, for `nperiod` periods
    /// (`< 0`: without end). The initial time must not be later than `start_time`.
    #[type_name = "Blocks.SawTooth"]
    pub struct SawTooth {
        /// Amplitude of the saw tooth, default 1.
        parameter amplitude: f64 = 1.0;
        /// Period \[s\] (greater than 0), default 1.
        parameter period(min = 0.0): f64 = 1.0;
        /// Number of periods (an integer; `< 0`: without end), default -1.
        parameter nperiod: f64 = -1.0;
        /// Offset of the output, default 0.
        parameter offset: f64 = 0.0;
        /// Start of the first period \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        /// Start of the current period \[s\].
        variable t_start(start = start_time): Real;
        /// Periods completed.
        variable count(start = 0.0): Real;
        equation {
            assert(gt(period, 0.0), "the period must be greater than 0");
            when sample(start_time + period, period) {
                count = pre(count) + 1.0;
                t_start = time;
            }
            let rising = amplitude * (time - t_start) / period;
            y = offset
                + if_else(lt(time, start_time), 0.0, if_else(finished(nperiod, count), 0.0, rising));
        }
    }
}

component! {
    /// A trapezoid train (MSL `Blocks.Sources.Trapezoid`): in each `period` from
    /// `start_time`, rising from `offset` to `offset + amplitude` over `rising`, holding
    /// for `width`, falling back over `falling`, then `offset` until the period ends; for
    /// `nperiod` periods (`< 0`: without end). The initial time must not be later than
    /// `start_time`.
    #[type_name = "Blocks.Trapezoid"]
    pub struct Trapezoid {
        /// Amplitude of the trapezoid, default 1.
        parameter amplitude: f64 = 1.0;
        /// Rising duration \[s\] (at least 0), default 0.
        parameter rising(min = 0.0): f64 = 0.0;
        /// Duration at `offset + amplitude` \[s\] (at least 0), default 0.5.
        parameter width(min = 0.0): f64 = 0.5;
        /// Falling duration \[s\] (at least 0), default 0.
        parameter falling(min = 0.0): f64 = 0.0;
        /// Period \[s\] (greater than 0), default 1.
        parameter period(min = 0.0): f64 = 1.0;
        /// Number of periods (an integer; `< 0`: without end), default -1.
        parameter nperiod: f64 = -1.0;
        /// Offset of the output, default 0.
        parameter offset: f64 = 0.0;
        /// Start of the first period \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        /// Start of the current period \[s\].
        variable t_start(start = start_time): Real;
        /// Periods completed.
        variable count(start = 0.0): Real;
        equation {
            assert(gt(period, 0.0), "the period must be greater than 0");
            when sample(start_time + period, period) {
                count = pre(count) + 1.0;
                t_start = time;
            }
            let (t_rising, t_width) = (rising, rising + width);
            let t_falling = t_width + falling;
            // A zero duration's branch is never taken; its denominator stays finite.
            let up = amplitude * (time - t_start) / if_else(gt(rising, 0.0), rising, 1.0);
            let down = amplitude * (t_start + t_falling - time) / if_else(gt(falling, 0.0), falling, 1.0);
            let shape = if_else(
                lt(time, t_start + t_rising),
                up,
                if_else(
                    lt(time, t_start + t_width),
                    amplitude,
                    if_else(lt(time, t_start + t_falling), down, 0.0),
                ),
            );
            y = offset
                + if_else(lt(time, start_time), 0.0, if_else(finished(nperiod, count), 0.0, shape));
        }
    }
}

component! {
    /// A signal interpolated linearly in a table of `(time, value)` rows (MSL
    /// `Blocks.Sources.TimeTable`): the first row at time 0, times increasing, a jump
    /// where two rows share their time; extrapolated through the last two rows; `offset`
    /// before `start_time`, and the table's times counted from `shift_time`. Every row's
    /// time is a time event, so the integrator never steps across a corner.
    #[type_name = "Blocks.TimeTable"]
    pub struct TimeTable {
        /// Rows `[time, value]` (time in s), at least one; default empty (an error).
        structural table: Vec<[f64; 2]> = Vec::new();
        /// Offset of the output, default 0.
        parameter offset: f64 = 0.0;
        /// Output `offset` before this time \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Time the table's times are counted from \[s\], default 0.
        parameter shift_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        equation {
            assert(!table.is_empty(), "the table needs at least one row");
            assert(
                table.first().is_none_or(|r| r[0] == 0.0) || table.len() == 1,
                format!("the first time of the table must be 0, not {}", table.first().map_or(0.0, |r| r[0]))
            );
            assert(
                table.windows(2).all(|w| w[1][0] >= w[0][0]) && table.iter().flatten().all(|x| x.is_finite()),
                "the times of the table must be finite and increasing"
            );
            if !table.is_empty() {
                let curve = crate::tables::interpolate(&table, time - shift_time, true);
                y = offset + if_else(lt(time, start_time), 0.0, curve);
            } else {
                y = offset;
            }
        }
    }
}
