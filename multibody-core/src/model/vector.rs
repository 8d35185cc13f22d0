//! How vectors and matrices of expressions take part in models: declared as variables
//! (`Vec3`, `Mat3`) and parameters (`[f64; 3]`), and equated element by element.

use super::{Equate, Parameter, ParameterType, System, Variable, VariableType};
use crate::expr::{Expr, Mat3, Vec3};

impl VariableType for Vec3 {
    fn declare(s: &mut System, template: Variable) -> Self {
        let mut out = [Expr::constant(0.0); 3];
        for (i, o) in out.iter_mut().enumerate() {
            *o = s.variable_at(&element_name(&template.name, i), template.clone());
        }
        Vec3(out)
    }
    fn at(path: &str) -> Self {
        Vec3(std::array::from_fn(|i| Expr::var(&element_name(path, i))))
    }
}

impl VariableType for Mat3 {
    fn declare(s: &mut System, template: Variable) -> Self {
        let mut m = [[Expr::constant(0.0); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let local = format!("{}[{},{}]", template.name, i + 1, j + 1);
                m[i][j] = s.variable_at(&local, template.clone());
            }
        }
        Mat3(m)
    }
    fn at(path: &str) -> Self {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| Expr::var(&format!("{path}[{},{}]", i + 1, j + 1)))
        }))
    }
}

impl<R: Into<Vec3>> Equate<R> for Vec3 {
    fn pairs(self, rhs: R) -> Vec<(Expr, Expr)> {
        let r = rhs.into();
        (0..3).map(|i| (self.0[i], r.0[i])).collect()
    }
}

impl Equate<Vec3> for [f64; 3] {
    fn pairs(self, rhs: Vec3) -> Vec<(Expr, Expr)> {
        Vec3::from(self).pairs(rhs)
    }
}

impl Equate<Mat3> for Mat3 {
    fn pairs(self, rhs: Mat3) -> Vec<(Expr, Expr)> {
        self.elements().into_iter().zip(rhs.elements()).collect()
    }
}

/// A tunable 3-vector parameter: its value is an array, its symbolic form a [`Vec3`] of
/// parameters named `name[1]`...
impl ParameterType for [f64; 3] {
    type Symbolic = Vec3;
    fn declare(&self, s: &mut System, template: Parameter) -> Vec3 {
        let mut out = [Expr::constant(0.0); 3];
        for (i, o) in out.iter_mut().enumerate() {
            let mut p = template.clone();
            p.value = Some(Expr::constant(self[i]));
            *o = s.parameter_at(&element_name(&template.name, i), p);
        }
        Vec3(out)
    }
    fn at(path: &str) -> Vec3 {
        Vec3(std::array::from_fn(|i| Expr::param(&element_name(path, i))))
    }
}

/// The name of element `i` (from 0) of a vector: `name[i + 1]`, as Modelica numbers it.
fn element_name(name: &str, i: usize) -> String {
    format!("{name}[{}]", i + 1)
}
