//! A source interpolated in a table given as rows or read from a file (MSL
//! `Blocks.Sources.CombiTimeTable`).

use std::path::PathBuf;

use super::interfaces::RealOutput;
use super::table_file::read_table;
use crate::prelude::*;
use crate::tables::interpolate;

/// How [`CombiTimeTable`] interpolates between its rows (MSL `Smoothness`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Smoothness {
    /// Linear between neighbouring rows (default).
    #[default]
    LinearSegments,
    /// The value of the row at or before the time.
    ConstantSegments,
}

/// How [`CombiTimeTable`] continues outside its rows (MSL `Extrapolation`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Extrapolation {
    /// The first or last row's value.
    HoldLastPoint,
    /// Linear through the first or last two rows (default).
    #[default]
    LastTwoPoints,
    /// The table repeats with the period of its time span.
    Periodic,
}

/// The `(time, value)` rows of `column` (1-based; column 1 is the time) of `rows`, or
/// what is wrong with them.
fn column_rows(rows: &[Vec<f64>], column: usize) -> Result<Vec<[f64; 2]>, String> {
    if rows.is_empty() {
        return Err("the table has no rows".into());
    }
    let width = rows[0].len();
    if width < 2 || rows.iter().any(|r| r.len() != width) {
        return Err(
            "the table's rows need a time and at least one value, all of one length".into(),
        );
    }
    if column < 2 || column > width {
        return Err(format!(
            "column {column} is not a value column (2 to {width})"
        ));
    }
    let out: Vec<[f64; 2]> = rows.iter().map(|r| [r[0], r[column - 1]]).collect();
    if !out.iter().flatten().all(|v| v.is_finite()) {
        return Err("the table has values that are not finite".into());
    }
    if out.windows(2).any(|w| w[1][0] < w[0][0]) {
        return Err("the table's times must not decrease".into());
    }
    Ok(out)
}

/// The value of `rows` at `tau` inside and beyond the table, as an expression whose
/// corners are events.
fn table_value(rows: &[[f64; 2]], tau: Expr, smoothness: Smoothness, hold: bool) -> Expr {
    let n = rows.len();
    if n == 1 {
        return Expr::from(rows[0][1]);
    }
    let (first, last) = (rows[0], rows[n - 1]);
    let inside = match smoothness {
        Smoothness::LinearSegments => interpolate(rows, tau, true),
        Smoothness::ConstantSegments => {
            // y_i on [t_i, t_(i+1)); past the last row, through the last two.
            let mut curve = interpolate(&rows[n - 2..], tau, true);
            for i in (0..n - 1).rev() {
                if rows[i + 1][0] > rows[i][0] {
                    curve = if_else(lt(tau, rows[i + 1][0]), rows[i][1], curve);
                }
            }
            if hold {
                curve
            } else {
                if_else(lt(tau, first[0]), interpolate(&rows[..2], tau, true), curve)
            }
        }
    };
    if hold {
        if_else(
            lt(tau, first[0]),
            first[1],
            if_else(ge(tau, last[0]), last[1], inside),
        )
    } else {
        inside
    }
}

component! {
    /// A signal interpolated in one column of a table (MSL
    /// `Blocks.Sources.CombiTimeTable`): rows `[time, value, value, ...]` given as
    /// `table` or read from `file` (MSL's text format with the matrix `table_name`, or
    /// CSV), the times non-decreasing, a jump where two rows share their time (before
    /// it the first one's value, after it the last one's). `offset` before `start_time`;
    /// the table's times are in units of `time_scale` seconds from `shift_time`. Every
    /// row's time is a time event. One column per instance (MSL's `y[i]` of `columns`).
    #[type_name = "Blocks.CombiTimeTable"]
    pub struct CombiTimeTable {
        /// Rows `[time, values...]`, default empty (then `file` is read).
        structural table: Vec<Vec<f64>> = Vec::new();
        /// A file to read the table from instead, default none.
        structural file: Option<PathBuf> = None;
        /// The matrix of the file in MSL's text format, default "NoName" (unused for CSV).
        structural table_name: String = "NoName".to_string();
        /// The column to output (1-based; column 1 is the time), default 2.
        structural column: usize = 2;
        /// Interpolation between rows, default linear.
        structural smoothness: Smoothness = Smoothness::LinearSegments;
        /// Continuation outside the rows, default through the last two rows.
        structural extrapolation: Extrapolation = Extrapolation::LastTwoPoints;
        /// Seconds per unit of the table's time, default 1.
        parameter time_scale(min = 0.0): f64 = 1.0;
        /// Offset of the output, default 0.
        parameter offset: f64 = 0.0;
        /// Output `offset` before this time [s], default 0.
        parameter start_time: f64 = 0.0;
        /// Time the table's times count from [s], default `start_time` (MSL).
        structural shift_time: Option<f64> = None;
        /// Output.
        connector y: RealOutput;
        /// Periods completed (with periodic extrapolation).
        variable periods(start = 0.0): Real;
        equation {
            let rows = match (&file, table.is_empty()) {
                (Some(path), _) => read_table(path, &table_name),
                (None, false) => Ok(table.clone()),
                (None, true) => Err("neither a table nor a file is given".to_string()),
            };
            let rows = rows.and_then(|r| column_rows(&r, column));
            assert(rows.is_ok(), rows.as_ref().err().cloned().unwrap_or_default());
            let rows = rows.unwrap_or_else(|_| vec![[0.0, 0.0]]);
            let shift: Expr = shift_time.map_or(Expr::from(start_time), Expr::from);
            let tau = (time - shift) / time_scale;
            let periodic = extrapolation == Extrapolation::Periodic && rows.len() > 1;
            let (t0, t1) = (rows[0][0], rows[rows.len() - 1][0]);
            let period = (t1 - t0).max(f64::MIN_POSITIVE);
            let hold = extrapolation == Extrapolation::HoldLastPoint;
            if periodic {
                assert(t1 > t0, "a periodic table needs a time span");
                when ge(tau, t0 + (periods + 1.0) * period) {
                    periods = pre(periods) + 1.0;
                }
                let value = table_value(&rows, tau - periods * period, smoothness, true);
                y = offset + if_else(lt(time, start_time), 0.0, value);
            } else {
                periods = Expr::from(0.0);
                let value = table_value(&rows, tau, smoothness, hold);
                y = offset + if_else(lt(time, start_time), 0.0, value);
            }
        }
    }
}
