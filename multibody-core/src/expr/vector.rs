//! Symbolic 3-vectors and 3x3 matrices of expressions, with the algebra equations need.

use std::ops::{Add, Index, Mul, Neg, Sub};

use super::Expr;

/// A 3-vector of expressions (`r_0`, `f`, `w`). Declared as a variable it is three
/// scalars named `name[1]`, `name[2]`, `name[3]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Vec3(pub [Expr; 3]);

/// A 3x3 matrix of expressions, row-major: `m.0[i][j]` is row i, column j.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Mat3(pub [[Expr; 3]; 3]);

fn c(x: f64) -> Expr {
    Expr::constant(x)
}

impl Vec3 {
    /// A vector of constants.
    pub fn constant(v: [f64; 3]) -> Vec3 {
        Vec3([c(v[0]), c(v[1]), c(v[2])])
    }

    /// The zero vector.
    pub fn zero() -> Vec3 {
        Vec3::constant([0.0; 3])
    }

    /// A vector of expressions.
    pub fn new(x: impl Into<Expr>, y: impl Into<Expr>, z: impl Into<Expr>) -> Vec3 {
        Vec3([x.into(), y.into(), z.into()])
    }

    /// Scalar product.
    pub fn dot(self, b: Vec3) -> Expr {
        self.0[0] * b.0[0] + self.0[1] * b.0[1] + self.0[2] * b.0[2]
    }

    /// Cross product.
    pub fn cross(self, b: Vec3) -> Vec3 {
        let (a, b) = (self.0, b.0);
        Vec3([
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ])
    }

    /// `self * k` for a scalar expression.
    pub fn scale(self, k: impl Into<Expr>) -> Vec3 {
        let k = k.into();
        Vec3([self.0[0] * k, self.0[1] * k, self.0[2] * k])
    }

    /// Euclidean length.
    pub fn norm(self) -> Expr {
        self.dot(self).sqrt()
    }

    /// The skew-symmetric matrix with `skew(a) * v = a x v`.
    pub fn skew(self) -> Mat3 {
        let z = c(0.0);
        let [x, y, w] = self.0;
        Mat3([[z, -w, y], [w, z, -x], [-y, x, z]])
    }

    /// The outer product `self * b'`.
    pub fn outer(self, b: Vec3) -> Mat3 {
        let mut m = [[c(0.0); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = self.0[i] * b.0[j];
            }
        }
        Mat3(m)
    }

    /// The time derivative, element by element.
    pub fn der(self) -> Vec3 {
        Vec3(self.0.map(Expr::der))
    }

    /// The elements.
    pub fn to_array(self) -> [Expr; 3] {
        self.0
    }

    /// The values, when every element is a constant.
    pub fn as_f64(self) -> Option<[f64; 3]> {
        Some([
            self.0[0].as_f64()?,
            self.0[1].as_f64()?,
            self.0[2].as_f64()?,
        ])
    }
}

impl Index<usize> for Vec3 {
    type Output = Expr;
    fn index(&self, i: usize) -> &Expr {
        &self.0[i]
    }
}

impl From<[f64; 3]> for Vec3 {
    fn from(v: [f64; 3]) -> Vec3 {
        Vec3::constant(v)
    }
}

impl From<[Expr; 3]> for Vec3 {
    fn from(v: [Expr; 3]) -> Vec3 {
        Vec3(v)
    }
}

impl<T: Into<Vec3>> Add<T> for Vec3 {
    type Output = Vec3;
    fn add(self, b: T) -> Vec3 {
        let b = b.into();
        Vec3([self.0[0] + b.0[0], self.0[1] + b.0[1], self.0[2] + b.0[2]])
    }
}

impl<T: Into<Vec3>> Sub<T> for Vec3 {
    type Output = Vec3;
    fn sub(self, b: T) -> Vec3 {
        let b = b.into();
        Vec3([self.0[0] - b.0[0], self.0[1] - b.0[1], self.0[2] - b.0[2]])
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    fn neg(self) -> Vec3 {
        Vec3(self.0.map(|x| -x))
    }
}

impl Mul<Expr> for Vec3 {
    type Output = Vec3;
    fn mul(self, k: Expr) -> Vec3 {
        self.scale(k)
    }
}

impl Mul<f64> for Vec3 {
    type Output = Vec3;
    fn mul(self, k: f64) -> Vec3 {
        self.scale(k)
    }
}

impl Mul<Vec3> for Expr {
    type Output = Vec3;
    fn mul(self, v: Vec3) -> Vec3 {
        v.scale(self)
    }
}

impl Mul<Vec3> for f64 {
    type Output = Vec3;
    fn mul(self, v: Vec3) -> Vec3 {
        v.scale(self)
    }
}

impl Mat3 {
    /// A matrix of constants (rows).
    pub fn constant(m: [[f64; 3]; 3]) -> Mat3 {
        Mat3(m.map(|r| r.map(c)))
    }

    /// The identity.
    pub fn identity() -> Mat3 {
        Mat3::constant([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    }

    /// The zero matrix.
    pub fn zero() -> Mat3 {
        Mat3::constant([[0.0; 3]; 3])
    }

    /// A diagonal matrix.
    pub fn diagonal(d: [Expr; 3]) -> Mat3 {
        let z = c(0.0);
        Mat3([[d[0], z, z], [z, d[1], z], [z, z, d[2]]])
    }

    /// The transpose.
    pub fn transpose(self) -> Mat3 {
        let m = self.0;
        Mat3([
            [m[0][0], m[1][0], m[2][0]],
            [m[0][1], m[1][1], m[2][1]],
            [m[0][2], m[1][2], m[2][2]],
        ])
    }

    /// Row `i`.
    pub fn row(self, i: usize) -> Vec3 {
        Vec3(self.0[i])
    }

    /// Column `j`.
    pub fn col(self, j: usize) -> Vec3 {
        Vec3([self.0[0][j], self.0[1][j], self.0[2][j]])
    }

    /// Matrix times vector.
    pub fn mul_vec(self, v: Vec3) -> Vec3 {
        Vec3([self.row(0).dot(v), self.row(1).dot(v), self.row(2).dot(v)])
    }

    /// Matrix product.
    pub fn mul_mat(self, b: Mat3) -> Mat3 {
        let mut m = [[c(0.0); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = self.row(i).dot(b.col(j));
            }
        }
        Mat3(m)
    }

    /// Element-wise scaling.
    pub fn scale(self, k: impl Into<Expr>) -> Mat3 {
        let k = k.into();
        Mat3(self.0.map(|r| r.map(|x| x * k)))
    }

    /// The nine elements, row-major.
    pub fn elements(self) -> [Expr; 9] {
        let m = self.0;
        [
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        ]
    }

    /// The values, when every element is a constant.
    pub fn as_f64(self) -> Option<[[f64; 3]; 3]> {
        let mut out = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                out[i][j] = self.0[i][j].as_f64()?;
            }
        }
        Some(out)
    }
}

impl Add for Mat3 {
    type Output = Mat3;
    fn add(self, b: Mat3) -> Mat3 {
        let mut m = self.0;
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = m[i][j] + b.0[i][j];
            }
        }
        Mat3(m)
    }
}

impl Sub for Mat3 {
    type Output = Mat3;
    fn sub(self, b: Mat3) -> Mat3 {
        let mut m = self.0;
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = m[i][j] - b.0[i][j];
            }
        }
        Mat3(m)
    }
}

impl Neg for Mat3 {
    type Output = Mat3;
    fn neg(self) -> Mat3 {
        Mat3(self.0.map(|r| r.map(|x| -x)))
    }
}

impl Mul<Vec3> for Mat3 {
    type Output = Vec3;
    fn mul(self, v: Vec3) -> Vec3 {
        self.mul_vec(v)
    }
}

impl Mul<Mat3> for Mat3 {
    type Output = Mat3;
    fn mul(self, b: Mat3) -> Mat3 {
        self.mul_mat(b)
    }
}

impl From<[[f64; 3]; 3]> for Mat3 {
    fn from(m: [[f64; 3]; 3]) -> Mat3 {
        Mat3::constant(m)
    }
}
