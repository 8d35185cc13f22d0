//! Overdetermined connectors and the virtual connection graph (Modelica's
//! `Connections.root`, `potentialRoot`, `branch` and `rooted`).
//!
//! An orientation in a frame connector has more variables (a 3x3 matrix and an angular
//! velocity) than degrees of freedom (3). Such a group is *overdetermined*: connections
//! do not equate it blindly. Instead every group is a node of the virtual connection
//! graph; components declare roots (the world), potential roots (a free body) and
//! branches (a joint or rigid part relating two frames), each with the equations to use
//! depending on which side is rooted. Flattening picks a root per connected part,
//! builds a spanning tree (branches always in it), equates the groups along tree
//! connections, emits the group's residue (3 equations for an orientation) for
//! connections that close a loop, and keeps for each branch the equations of the side
//! that is nearer the root.

use crate::expr::Expr;

use super::system::{Equation, System};
use super::typed::VariableType;
use super::variable::{VarKind, Variable};

/// A variable type whose connector instances are overdetermined.
pub trait OverdeterminedType: VariableType {
    /// The scalar variables, in a fixed order.
    fn scalars(&self) -> Vec<Expr>;
    /// The residue that is zero when two instances (given by their scalars) agree:
    /// as many equations as the type has degrees of freedom.
    fn residue(a: &[Expr], b: &[Expr]) -> Vec<Expr>;
    /// The full path of an instance (the graph node's name).
    fn node_path(&self) -> String;
}

/// A node of the virtual connection graph, by its path.
pub trait GraphNode {
    /// The full path of the overdetermined group (`j1.frame_a.R`).
    fn node_path(&self) -> String;
}

impl<T: OverdeterminedType> GraphNode for T {
    fn node_path(&self) -> String {
        OverdeterminedType::node_path(self)
    }
}

/// An overdetermined group declared in a connector.
#[derive(Clone, Debug)]
pub struct OverdeterminedGroup {
    /// Full path (the graph node's name).
    pub path: String,
    /// Its scalar variables.
    pub vars: Vec<Expr>,
    /// The residue of two instances (see [`OverdeterminedType::residue`]).
    pub residue: fn(&[Expr], &[Expr]) -> Vec<Expr>,
}

/// A declaration about the virtual connection graph.
#[derive(Clone, Debug)]
pub enum GraphDecl {
    /// The node is a definite root (the world's frame).
    Root {
        /// Node path.
        node: String,
    },
    /// The node may be a root (a free body); the equations depend on whether it is.
    PotentialRoot {
        /// Node path.
        node: String,
        /// Higher priority is chosen first among potential roots.
        priority: i32,
        /// Equations when it is the root (orientation states of a free body).
        if_root: Vec<Equation>,
        /// Equations when it is not.
        otherwise: Vec<Equation>,
    },
    /// The two nodes are related by the component (a joint, a rigid part).
    Branch {
        /// First node.
        a: String,
        /// Second node.
        b: String,
        /// Equations when `a` is nearer the root (it determines `b`).
        a_rooted: Vec<Equation>,
        /// Equations when `b` is nearer the root.
        b_rooted: Vec<Equation>,
    },
}

impl System {
    /// Declares that the time derivative of the variable `var` is the expression `der`
    /// (no derivative unknown is created; differentiation uses the expression).
    pub fn derivative_rule(&mut self, var: Expr, der: Expr) {
        let der = self.own(der);
        self.derivative_rules.push((var, der));
    }

    /// Declares an overdetermined connector variable (an orientation in a frame).
    pub fn declare_overdetermined<T: OverdeterminedType>(&mut self, template: Variable) -> T {
        let v: T = T::declare(self, template.kind(VarKind::Overdetermined));
        self.overdetermined.push(OverdeterminedGroup {
            path: OverdeterminedType::node_path(&v),
            vars: v.scalars(),
            residue: T::residue,
        });
        v
    }

    /// Runs `f` and returns the equations it added, without keeping them in this
    /// system (for the alternative equation sets of roots and branches).
    pub fn capture(&mut self, f: impl FnOnce(&mut System)) -> Vec<Equation> {
        let n = self.equations.len();
        f(self);
        self.equations.split_off(n)
    }

    /// Declares `node` a definite root of the virtual connection graph.
    pub fn root(&mut self, node: &impl GraphNode) {
        self.graph.push(GraphDecl::Root {
            node: node.node_path(),
        });
    }

    /// Declares `node` a potential root with the equations for both cases.
    pub fn potential_root(
        &mut self,
        node: &impl GraphNode,
        priority: i32,
        if_root: Vec<Equation>,
        otherwise: Vec<Equation>,
    ) {
        self.graph.push(GraphDecl::PotentialRoot {
            node: node.node_path(),
            priority,
            if_root,
            otherwise,
        });
    }

    /// Declares a branch between two nodes with the equations for both directions.
    pub fn branch(
        &mut self,
        a: &impl GraphNode,
        b: &impl GraphNode,
        a_rooted: Vec<Equation>,
        b_rooted: Vec<Equation>,
    ) {
        self.graph.push(GraphDecl::Branch {
            a: a.node_path(),
            b: b.node_path(),
            a_rooted,
            b_rooted,
        });
    }
}
