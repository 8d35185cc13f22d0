//! Piecewise-linear interpolation in tables of `[x, y]` rows, as equations.

use crate::prelude::*;

/// `y(x)` interpolated linearly in `table` (rows `[x, y]`, `x` increasing): linear
/// between neighbouring rows, a jump where two rows share their `x`, extrapolated
/// through the first or last two rows (MSL `Math.Vectors.interpolate`). With `events`
/// each row's `x` inside the table is a relation on `x` that generates an event;
/// without, the corners are integrated through (as a Modelica function call is).
pub(crate) fn interpolate(table: &[[f64; 2]], x: Expr, events: bool) -> Expr {
    let n = table.len();
    match n {
        0 => return Expr::from(0.0),
        1 => return Expr::from(table[0][1]),
        _ => {}
    }
    let line = |i: usize| {
        let ([x0, y0], [x1, y1]) = (table[i - 1], table[i]);
        let dx = x1 - x0;
        if dx <= 100.0 * f64::EPSILON * x1.abs() {
            Expr::from(y1)
        } else {
            (x - x0) * ((y1 - y0) / dx) + y0
        }
    };
    // From the last interval (which extrapolates) back to the first.
    let mut curve = line(n - 1);
    for i in (1..n - 1).rev() {
        let before = if events {
            lt(x, table[i][0])
        } else {
            no_event(lt(x, table[i][0]))
        };
        curve = if_else(before, line(i), curve);
    }
    curve
}

/// `y(x0)` of [`interpolate`] at a number.
pub(crate) fn interpolate_at(table: &[[f64; 2]], x0: f64) -> f64 {
    let n = table.len();
    match n {
        0 => return 0.0,
        1 => return table[0][1],
        _ => {}
    }
    let i = (1..n - 1).find(|&i| x0 < table[i][0]).unwrap_or(n - 1);
    let ([xa, ya], [xb, yb]) = (table[i - 1], table[i]);
    if xb - xa <= 100.0 * f64::EPSILON * xb.abs() {
        yb
    } else {
        ya + (x0 - xa) * (yb - ya) / (xb - xa)
    }
}

/// Whether `table` is usable by [`interpolate`]: at least one row, finite, `x`
/// increasing.
pub(crate) fn valid(table: &[[f64; 2]]) -> bool {
    !table.is_empty()
        && table.iter().flatten().all(|v| v.is_finite())
        && table.windows(2).all(|w| w[1][0] >= w[0][0])
}
