//! The virtual connection graph: which equations relate overdetermined groups.
//!
//! Run before flattening proper, on the system tree. Nodes are the overdetermined
//! groups (orientations of frames); edges are the components' branches and the
//! connections between frames. Each connected part gets one root (a definite root, or
//! the potential root of highest priority); a spanning tree takes every branch and then
//! connections in declaration order; connections left out close loops and contribute
//! the group's residue instead of full equality; branch equations follow the direction
//! away from the root.

use std::collections::VecDeque;

use crate::expr::Expr;
use crate::hash::HashMap;

use super::error::ModelError;
use super::overdetermined::{GraphDecl, OverdeterminedGroup};
use super::system::{Equation, System, join_path};

/// An equation produced by the graph, with where it comes from.
#[derive(Clone, Debug)]
pub(crate) struct GraphEquation {
    /// The equation.
    pub equation: Equation,
    /// Its origin in words (`connection: a = b`, `j1: frame_b.R from frame_a.R`).
    pub text: String,
    /// The component (or connection) it belongs to, for display.
    pub path: String,
}

/// The equations the graph decides, and a summary.
#[derive(Clone, Debug, Default)]
pub(crate) struct GraphResult {
    pub equations: Vec<GraphEquation>,
    /// Connections that close loops (cut), as `a - b`.
    pub cuts: Vec<(String, String)>,
    /// The chosen roots.
    pub roots: Vec<String>,
}

struct Edge {
    a: usize,
    b: usize,
    kind: EdgeKind,
}

enum EdgeKind {
    /// A branch of a component (index into the branch list).
    Branch(usize),
    /// A connection between two connectors (for messages).
    Connection(String),
}

struct BranchInfo {
    owner: String,
    a_rooted: Vec<Equation>,
    b_rooted: Vec<Equation>,
}

struct PotentialRoot {
    node: usize,
    owner: String,
    priority: i32,
    if_root: Vec<Equation>,
    otherwise: Vec<Equation>,
    order: usize,
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Resolves the virtual connection graph of a model.
pub(crate) fn resolve(model: &System) -> Result<GraphResult, ModelError> {
    // Collect groups, connector groups, connections and declarations.
    let mut groups: Vec<OverdeterminedGroup> = Vec::new();
    let mut node_of: HashMap<String, usize> = HashMap::default();
    let mut connector_groups: HashMap<String, Vec<usize>> = HashMap::default();
    let mut decls: Vec<(String, GraphDecl)> = Vec::new();
    // Connections by their system, their full paths written out only when the model
    // has overdetermined groups at all.
    let mut connection_of: Vec<(&str, &super::system::Connection)> = Vec::new();
    let mut stack = vec![model];
    while let Some(s) = stack.pop() {
        for g in &s.overdetermined {
            let id = groups.len();
            node_of.insert(g.path.clone(), id);
            groups.push(g.clone());
            if s.connector_class.is_some() {
                connector_groups.entry(s.path.clone()).or_default().push(id);
            }
        }
        for d in &s.graph {
            decls.push((s.path.clone(), d.clone()));
        }
        for c in &s.connections {
            connection_of.push((&s.path, c));
        }
        for sub in s.subsystems.iter().rev() {
            stack.push(sub);
        }
    }
    if groups.is_empty() {
        return Ok(GraphResult::default());
    }
    let connections: Vec<(String, String)> = connection_of
        .iter()
        .map(|(path, c)| (join_path(path, &c.a), join_path(path, &c.b)))
        .collect();
    let n = groups.len();
    let node = |path: &str| -> Result<usize, ModelError> {
        node_of.get(path).copied().ok_or_else(|| ModelError::Graph {
            message: format!(
                "`{path}` is not an overdetermined connector variable (a frame's orientation)"
            ),
        })
    };
    let mut edges: Vec<Edge> = Vec::new();
    let mut branches: Vec<BranchInfo> = Vec::new();
    let mut roots: Vec<(usize, String)> = Vec::new();
    let mut potential: Vec<PotentialRoot> = Vec::new();
    for (owner, d) in decls {
        match d {
            GraphDecl::Root { node: p } => roots.push((node(&p)?, owner)),
            GraphDecl::PotentialRoot {
                node: p,
                priority,
                if_root,
                otherwise,
            } => {
                let order = potential.len();
                potential.push(PotentialRoot {
                    node: node(&p)?,
                    owner,
                    priority,
                    if_root,
                    otherwise,
                    order,
                });
            }
            GraphDecl::Branch {
                a,
                b,
                a_rooted,
                b_rooted,
            } => {
                let (a, b) = (node(&a)?, node(&b)?);
                edges.push(Edge {
                    a,
                    b,
                    kind: EdgeKind::Branch(branches.len()),
                });
                branches.push(BranchInfo {
                    owner,
                    a_rooted,
                    b_rooted,
                });
            }
        }
    }
    let n_branch_edges = edges.len();
    for (ca, cb) in connections {
        let (Some(ga), Some(gb)) = (connector_groups.get(&ca), connector_groups.get(&cb)) else {
            continue;
        };
        for (&a, &b) in ga.iter().zip(gb) {
            edges.push(Edge {
                a,
                b,
                kind: EdgeKind::Connection(format!("connect({ca}, {cb})")),
            });
        }
    }

    // Spanning forest: branches first (a loop of branches alone is an error), then
    // connections in order.
    let mut parent: Vec<usize> = (0..n).collect();
    let mut in_tree = vec![false; edges.len()];
    for (k, e) in edges.iter().enumerate() {
        let (ra, rb) = (find(&mut parent, e.a), find(&mut parent, e.b));
        if ra != rb {
            parent[ra] = rb;
            in_tree[k] = true;
        } else if k < n_branch_edges {
            return Err(ModelError::Graph {
                message: format!(
                    "the components relating `{}` and `{}` form a closed chain of rigid \
                     branches without a connection that could be cut",
                    groups[e.a].path, groups[e.b].path
                ),
            });
        }
    }
    // Connected parts (over all edges: a cut connection still joins its ends).
    let mut comp_parent: Vec<usize> = (0..n).collect();
    for e in &edges {
        let (ra, rb) = (find(&mut comp_parent, e.a), find(&mut comp_parent, e.b));
        if ra != rb {
            comp_parent[ra] = rb;
        }
    }
    let mut comp_root: HashMap<usize, usize> = HashMap::default();
    let mut result = GraphResult::default();
    for (r, owner) in &roots {
        let c = find(&mut comp_parent, *r);
        if let Some(&other) = comp_root.get(&c) {
            return Err(ModelError::Graph {
                message: format!(
                    "two roots fight over one mechanism: `{}` and `{}` (of `{owner}`) are \
                     both fixed in the world and connected to each other; one part cannot \
                     be fixed twice",
                    groups[other].path, groups[*r].path
                ),
            });
        }
        comp_root.insert(c, *r);
    }
    let mut chosen_potential = vec![false; potential.len()];
    let mut order: Vec<usize> = (0..potential.len()).collect();
    order.sort_by(|&x, &y| {
        potential[y]
            .priority
            .cmp(&potential[x].priority)
            .then(potential[x].order.cmp(&potential[y].order))
    });
    for k in order {
        let c = find(&mut comp_parent, potential[k].node);
        if let std::collections::hash_map::Entry::Vacant(v) = comp_root.entry(c) {
            v.insert(potential[k].node);
            chosen_potential[k] = true;
        }
    }
    // Every part needs a root.
    let mut members: HashMap<usize, Vec<usize>> = HashMap::default();
    for v in 0..n {
        let c = find(&mut comp_parent, v);
        members.entry(c).or_default().push(v);
    }
    let mut unrooted: Vec<String> = Vec::new();
    for (c, ms) in &members {
        if !comp_root.contains_key(c) {
            unrooted.extend(ms.iter().map(|&v| groups[v].path.clone()));
        }
    }
    if !unrooted.is_empty() {
        unrooted.sort();
        return Err(ModelError::Graph {
            message: format!(
                "the orientation of {} is not determined: this part of the mechanism is \
                 connected neither to the world nor to a free body (a joint left floating?)",
                crate::names::list(&unrooted, 8)
            ),
        });
    }
    // Orient the tree from the roots.
    let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (k, e) in edges.iter().enumerate() {
        if in_tree[k] {
            adjacency[e.a].push(k);
            adjacency[e.b].push(k);
        }
    }
    let mut seen = vec![false; n];
    let mut root_list: Vec<usize> = comp_root.values().copied().collect();
    root_list.sort_unstable();
    for &r in &root_list {
        result.roots.push(groups[r].path.clone());
        seen[r] = true;
        let mut queue = VecDeque::from([r]);
        while let Some(v) = queue.pop_front() {
            for &k in &adjacency[v] {
                let e = &edges[k];
                let (from, to) = if e.a == v { (e.a, e.b) } else { (e.b, e.a) };
                if seen[to] {
                    continue;
                }
                seen[to] = true;
                queue.push_back(to);
                match &e.kind {
                    EdgeKind::Branch(bi) => {
                        let b = &branches[*bi];
                        let (eqs, dir) = if from == e.a {
                            (&b.a_rooted, "a")
                        } else {
                            (&b.b_rooted, "b")
                        };
                        let text = format!(
                            "{} (orientation propagated from its {} side)",
                            if b.owner.is_empty() {
                                "model"
                            } else {
                                &b.owner
                            },
                            if dir == "a" { "first" } else { "second" }
                        );
                        for eq in eqs {
                            result.equations.push(GraphEquation {
                                equation: *eq,
                                text: text.clone(),
                                path: b.owner.clone(),
                            });
                        }
                    }
                    EdgeKind::Connection(text) => {
                        let (ga, gb) = (&groups[from], &groups[to]);
                        for (x, y) in ga.vars.iter().zip(&gb.vars) {
                            result.equations.push(GraphEquation {
                                equation: Equation { lhs: *y, rhs: *x },
                                text: format!("{text}: {} = {}", gb.path, ga.path),
                                path: String::new(),
                            });
                        }
                    }
                }
            }
        }
    }
    // Connections left out of the tree close loops: the residue.
    for (k, e) in edges.iter().enumerate() {
        if in_tree[k] {
            continue;
        }
        let EdgeKind::Connection(text) = &e.kind else {
            continue;
        };
        let (ga, gb) = (&groups[e.a], &groups[e.b]);
        result.cuts.push((ga.path.clone(), gb.path.clone()));
        for r in (ga.residue)(&ga.vars, &gb.vars) {
            result.equations.push(GraphEquation {
                equation: Equation {
                    lhs: Expr::constant(0.0),
                    rhs: r,
                },
                text: format!(
                    "{text}: loop closure residue of {} and {}",
                    ga.path, gb.path
                ),
                path: String::new(),
            });
        }
    }
    // Potential roots.
    for (k, p) in potential.iter().enumerate() {
        let (eqs, what) = if chosen_potential[k] {
            (&p.if_root, "as root")
        } else {
            (&p.otherwise, "not a root")
        };
        for eq in eqs {
            result.equations.push(GraphEquation {
                equation: *eq,
                text: format!(
                    "{} ({what})",
                    if p.owner.is_empty() {
                        "model"
                    } else {
                        &p.owner
                    }
                ),
                path: p.owner.clone(),
            });
        }
    }
    Ok(result)
}
