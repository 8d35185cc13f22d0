//! Controller design on linear models: pole placement for one input (Ackermann's
//! formula) and the linear-quadratic regulator (the continuous algebraic Riccati
//! equation, by Newton-Kleinman iteration from a stabilizing gain).

use nalgebra::{Complex, DMatrix, DVector};

/// Why a design failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DesignError {
    /// The matrices' sizes do not fit together.
    #[error("the matrices do not fit: {0}")]
    Shape(String),
    /// The system cannot be controlled from its input: no gain places the poles.
    #[error("the system is not controllable from its input")]
    Uncontrollable,
    /// The Riccati iteration did not converge (or started from no stabilizing gain).
    #[error("the Riccati equation's iteration did not converge: {0}")]
    NoConvergence(String),
}

/// The gain row `k` of `u = -k x` that gives `dx = (A - b k) x` the `poles` (complex
/// ones in conjugate pairs), for a single input `b` (Ackermann's formula).
pub fn place_poles(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    poles: &[Complex<f64>],
) -> Result<DVector<f64>, DesignError> {
    let n = a.nrows();
    if a.ncols() != n || b.len() != n || poles.len() != n {
        return Err(DesignError::Shape(format!(
            "A is {}x{}, b has {}, {} poles",
            a.nrows(),
            a.ncols(),
            b.len(),
            poles.len()
        )));
    }
    // The desired characteristic polynomial's coefficients (real for conjugate pairs).
    let mut coeffs: Vec<Complex<f64>> = vec![Complex::new(1.0, 0.0)];
    for &p in poles {
        let mut next = vec![Complex::new(0.0, 0.0); coeffs.len() + 1];
        for (i, &c) in coeffs.iter().enumerate() {
            next[i] += c;
            next[i + 1] -= c * p;
        }
        coeffs = next;
    }
    // phi(A) = A^n + c1 A^(n-1) + ... + cn I.
    let mut phi = DMatrix::<f64>::zeros(n, n);
    let mut power = DMatrix::<f64>::identity(n, n);
    for k in (0..=n).rev() {
        phi += &power * coeffs[k].re;
        power = &power * a;
    }
    // Controllability matrix [b, A b, ..., A^(n-1) b].
    let mut ctrb = DMatrix::<f64>::zeros(n, n);
    let mut col = b.clone();
    for j in 0..n {
        ctrb.set_column(j, &col);
        col = a * col;
    }
    let inv = ctrb.try_inverse().ok_or(DesignError::Uncontrollable)?;
    let last = inv.row(n - 1).into_owned();
    Ok((last * phi).transpose())
}

/// Solves the Lyapunov equation `M^T X + X M + S = 0` (`S` symmetric) by its Kronecker
/// form (for the small systems of controller design).
fn lyapunov(m: &DMatrix<f64>, s: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = m.nrows();
    let mut big = DMatrix::<f64>::zeros(n * n, n * n);
    // vec(M^T X + X M) = (I kron M^T + M^T kron I) vec(X), column-major vec.
    for i in 0..n {
        for j in 0..n {
            let row = i + j * n;
            for k in 0..n {
                // (M^T X)_(i,j) = sum_k M(k,i) X(k,j)
                big[(row, k + j * n)] += m[(k, i)];
                // (X M)_(i,j) = sum_k X(i,k) M(k,j)
                big[(row, i + k * n)] += m[(k, j)];
            }
        }
    }
    let rhs = DVector::from_iterator(n * n, s.iter().map(|v| -v));
    let x = big.lu().solve(&rhs)?;
    let x = DMatrix::from_column_slice(n, n, x.as_slice());
    Some((&x + x.transpose()) * 0.5)
}

/// The linear-quadratic regulator: the gain `K` of `u = -K x` that minimizes
/// `integral(x^T Q x + u^T R u)` for `dx = A x + B u`, with the solution `P` of the
/// continuous algebraic Riccati equation `A^T P + P A - P B R^-1 B^T P + Q = 0`.
/// `K0` is a stabilizing gain to start from (`None`: zero, for a stable `A`).
pub fn lqr(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    k0: Option<&DMatrix<f64>>,
) -> Result<(DMatrix<f64>, DMatrix<f64>), DesignError> {
    let (n, m) = (a.nrows(), b.ncols());
    if a.ncols() != n || b.nrows() != n || q.shape() != (n, n) || r.shape() != (m, m) {
        return Err(DesignError::Shape(format!(
            "A {:?}, B {:?}, Q {:?}, R {:?}",
            a.shape(),
            b.shape(),
            q.shape(),
            r.shape()
        )));
    }
    let r_inv = r
        .clone()
        .try_inverse()
        .ok_or_else(|| DesignError::Shape("R is singular".into()))?;
    let mut k = k0.cloned().unwrap_or_else(|| DMatrix::zeros(m, n));
    if k.shape() != (m, n) {
        return Err(DesignError::Shape(format!("K0 {:?}", k.shape())));
    }
    let mut previous: Option<DMatrix<f64>> = None;
    for _ in 0..100 {
        let closed = a - b * &k;
        if closed.complex_eigenvalues().iter().any(|l| l.re >= 0.0) {
            return Err(DesignError::NoConvergence(
                "the gain does not stabilize the system (give a stabilizing K0)".into(),
            ));
        }
        let s = q + k.transpose() * r * &k;
        let p = lyapunov(&closed, &s)
            .ok_or_else(|| DesignError::NoConvergence("a Lyapunov equation is singular".into()))?;
        k = &r_inv * b.transpose() * &p;
        if let Some(prev) = &previous
            && (&p - prev).norm() <= 1e-13 * p.norm().max(1.0)
        {
            return Ok((k, p));
        }
        previous = Some(p);
    }
    Err(DesignError::NoConvergence("100 iterations".into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_integrator_lqr_has_the_closed_form_gain() {
        // x'' = u with Q = I, R = 1: K = [1, sqrt(3)] (closed form of the CARE).
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
        let k0 = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let (k, p) = lqr(
            &a,
            &b,
            &DMatrix::identity(2, 2),
            &DMatrix::identity(1, 1),
            Some(&k0),
        )
        .unwrap();
        assert!((k[(0, 0)] - 1.0).abs() < 1e-12 && (k[(0, 1)] - 3f64.sqrt()).abs() < 1e-12);
        let residual = a.transpose() * &p + &p * &a - &p * &b * b.transpose() * &p
            + DMatrix::<f64>::identity(2, 2);
        assert!(residual.norm() < 1e-12);
    }

    #[test]
    fn ackermann_places_the_poles() {
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 27.0, -0.5]);
        let b = DVector::from_row_slice(&[0.0, 2.0]);
        let poles = [Complex::new(-4.0, 3.0), Complex::new(-4.0, -3.0)];
        let k = place_poles(&a, &b, &poles).unwrap();
        let closed = &a - &b * k.transpose();
        let mut ev: Vec<Complex<f64>> = closed.complex_eigenvalues().iter().copied().collect();
        ev.sort_by(|x, y| x.im.total_cmp(&y.im));
        assert!((ev[0] - poles[1]).norm() < 1e-12 && (ev[1] - poles[0]).norm() < 1e-12);
        let uncontrollable = place_poles(&a, &DVector::from_row_slice(&[0.0, 0.0]), &poles);
        assert_eq!(uncontrollable, Err(DesignError::Uncontrollable));
    }
}
