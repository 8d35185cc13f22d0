//! Planar kinematic loops, found from the mechanism's geometry.
//!
//! A closed loop whose revolute joints all have parallel axes (and whose prismatic
//! joints, if any, move across that axis) moves in a plane: of the six loop-closure
//! constraints only three are independent, and the constraint force along the axis and
//! the torques across it cannot be determined. Modelica tools then report a
//! structurally singular system; here the loop is found from the model tree (frames as
//! nodes; connections, rigid parts and joints as edges) and named, and on request one
//! revolute joint of each planar loop becomes a *planar cut* (see
//! [`Revolute::planar_cut`](crate::joints::Revolute)).

use multibody_core::hash::HashMap;
use multibody_core::model::{System, join_path};

use crate::joints::Revolute;
use crate::numeric::{cross, dot, normalize};

/// How a component relates its two frames, for loop finding.
#[derive(Clone, Debug, PartialEq)]
enum Link {
    /// A connection or a rigid part without rotation.
    Rigid,
    /// A revolute joint about its axis (resolved in its frames).
    Revolute([f64; 3]),
    /// A prismatic joint along its axis.
    Prismatic([f64; 3]),
    /// Any other rotation (a fixed rotation, a spherical joint).
    Rotating,
    /// A loop through this link needs no help (a planar-loop constraint, a planar cut).
    Resolved,
}

struct Edge {
    a: usize,
    b: usize,
    link: Link,
    /// The component's path (empty for connections).
    owner: String,
}

#[derive(Default)]
struct Graph {
    nodes: Vec<String>,
    index: HashMap<String, usize>,
    edges: Vec<Edge>,
}

impl Graph {
    fn node(&mut self, path: &str) -> usize {
        if let Some(&k) = self.index.get(path) {
            return k;
        }
        self.nodes.push(path.to_string());
        self.index.insert(path.to_string(), self.nodes.len() - 1);
        self.nodes.len() - 1
    }

    fn edge(&mut self, a: &str, b: &str, link: Link, owner: &str) {
        let (a, b) = (self.node(a), self.node(b));
        self.edges.push(Edge {
            a,
            b,
            link,
            owner: owner.to_string(),
        });
    }
}

const GROUND: &str = "<ground>";

/// The type name of a revolute joint.
const REVOLUTE: &str = "MultiBody.Joints.Revolute";

fn vector(s: &System, name: &str, default: [f64; 3]) -> [f64; 3] {
    match s.structural_value(name) {
        Some(v) if v.len() == 3 => [v[0], v[1], v[2]],
        _ => default,
    }
}

fn flag(s: &System, name: &str) -> bool {
    s.structural_value(name)
        .is_some_and(|v| v.first() == Some(&1.0))
}

fn is_frame(s: &System) -> bool {
    s.is_connector() && s.type_name.ends_with("Frame")
}

fn collect(s: &System, frames: &mut Vec<String>, g: &mut Graph) {
    for sub in &s.subsystems {
        if is_frame(sub) {
            frames.push(sub.path.clone());
        }
    }
    let frame = |local: &str| join_path(&s.path, local);
    let leaf = match s.type_name.as_str() {
        REVOLUTE => Some(if flag(s, "iscut") && flag(s, "planar_cut") {
            Link::Resolved
        } else {
            Link::Revolute(vector(s, "n", [0.0, 0.0, 1.0]))
        }),
        "MultiBody.Joints.Prismatic" => Some(Link::Prismatic(vector(s, "n", [1.0, 0.0, 0.0]))),
        "MultiBody.Joints.RevolutePlanarLoopConstraint" => Some(Link::Resolved),
        "MultiBody.Parts.FixedTranslation" => Some(Link::Rigid),
        "MultiBody.Parts.FixedRotation" | "MultiBody.Joints.Spherical" => Some(Link::Rotating),
        "MultiBody.World" | "MultiBody.Parts.Fixed" => {
            g.edge(GROUND, &frame("frame_b"), Link::Rigid, &s.path);
            None
        }
        _ => None,
    };
    if let Some(link) = leaf {
        g.edge(&frame("frame_a"), &frame("frame_b"), link, &s.path);
        return;
    }
    for c in &s.connections {
        g.edge(&frame(&c.a), &frame(&c.b), Link::Rigid, "");
    }
    for sub in &s.subsystems {
        if !sub.is_connector() {
            collect(sub, frames, g);
        }
    }
}

/// The revolute joints in `s` and below, counted up to `enough`.
fn count_revolute_joints(s: &System, enough: usize) -> usize {
    if s.type_name == REVOLUTE {
        return 1;
    }
    let mut n = 0;
    for sub in &s.subsystems {
        if n >= enough {
            break;
        }
        if !sub.is_connector() {
            n += count_revolute_joints(sub, enough - n);
        }
    }
    n
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// The edges of the tree path from `from` to `to` (`adjacent[n]`: tree edges at n).
fn tree_path(g: &Graph, adjacent: &[Vec<usize>], from: usize, to: usize) -> Vec<usize> {
    let mut via: Vec<Option<usize>> = vec![None; g.nodes.len()];
    let mut seen = vec![false; g.nodes.len()];
    let mut queue = std::collections::VecDeque::from([from]);
    seen[from] = true;
    while let Some(n) = queue.pop_front() {
        if n == to {
            break;
        }
        for &k in &adjacent[n] {
            let e = &g.edges[k];
            let m = if e.a == n { e.b } else { e.a };
            if !seen[m] {
                seen[m] = true;
                via[m] = Some(k);
                queue.push_back(m);
            }
        }
    }
    let mut path = Vec::new();
    let mut n = to;
    while let Some(k) = via[n] {
        path.push(k);
        let e = &g.edges[k];
        n = if e.a == n { e.b } else { e.a };
    }
    path.reverse();
    path
}

/// Whether a loop's links move in a plane: at least two revolute joints, all axes
/// parallel, prismatic axes across them, nothing else that rotates.
fn is_planar(links: &[&Link]) -> bool {
    let axes: Vec<[f64; 3]> = links
        .iter()
        .filter_map(|l| match l {
            Link::Revolute(n) => normalize(*n),
            _ => None,
        })
        .collect();
    if axes.len() < 2
        || links
            .iter()
            .any(|l| matches!(l, Link::Rotating | Link::Resolved))
    {
        return false;
    }
    let n0 = axes[0];
    let parallel = axes.iter().all(|&n| {
        let c = cross(n0, n);
        dot(c, c) < 1e-18
    });
    let across = links.iter().all(|l| match l {
        Link::Prismatic(n) => normalize(*n).is_some_and(|u| dot(u, n0).abs() < 1e-9),
        _ => true,
    });
    parallel && across
}

/// The planar loops of a model: for each, the paths of its revolute and prismatic
/// joints in loop order.
pub fn planar_loops(model: &(impl AsRef<System> + ?Sized)) -> Vec<Vec<String>> {
    let model = model.as_ref();
    // A planar loop has two revolute joints at least: a model with fewer (any model of
    // 1-D components) needs no graph of its connections.
    if count_revolute_joints(model, 2) < 2 {
        return Vec::new();
    }
    let mut g = Graph::default();
    let mut frames = Vec::new();
    collect(model, &mut frames, &mut g);
    let n = g.nodes.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut loops = Vec::new();
    for k in 0..g.edges.len() {
        let (a, b) = (g.edges[k].a, g.edges[k].b);
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        if ra != rb {
            parent[ra] = rb;
            adjacent[a].push(k);
            adjacent[b].push(k);
            continue;
        }
        let mut cycle = tree_path(&g, &adjacent, b, a);
        cycle.push(k);
        let links: Vec<&Link> = cycle.iter().map(|&e| &g.edges[e].link).collect();
        if is_planar(&links) {
            let mut joints: Vec<usize> = cycle
                .into_iter()
                .filter(|&e| matches!(g.edges[e].link, Link::Revolute(_) | Link::Prismatic(_)))
                .collect();
            // Loop order from the first declared joint, towards its first declared
            // neighbour.
            if let Some(first) = (0..joints.len()).min_by_key(|&i| joints[i]) {
                joints.rotate_left(first);
                if joints.len() > 2 && joints[joints.len() - 1] < joints[1] {
                    joints[1..].reverse();
                }
            }
            loops.push(joints.iter().map(|&e| g.edges[e].owner.clone()).collect());
        }
    }
    loops
}

fn connected(model: &System, connector: &str) -> bool {
    fn walk(s: &System, target: &str) -> bool {
        s.connections
            .iter()
            .any(|c| join_path(&s.path, &c.a) == target || join_path(&s.path, &c.b) == target)
            || s.subsystems.iter().any(|sub| walk(sub, target))
    }
    walk(model, connector)
}

/// A copy of `model` in which one revolute joint of each planar loop is a planar cut
/// (`iscut` and `planar_cut`): preferably the last joint of the loop whose axis and
/// support flanges are free. Every variable of the model stays.
pub fn remove_planar_redundancy(model: &System, loops: &[Vec<String>]) -> System {
    let mut out = model.clone();
    for joints in loops {
        let revolutes: Vec<&String> = joints
            .iter()
            .filter(|j| model.subsystem(j).is_some_and(|s| s.type_name == REVOLUTE))
            .collect();
        let Some(chosen) = revolutes
            .iter()
            .rev()
            .find(|j| {
                !connected(model, &format!("{j}.axis"))
                    && !connected(model, &format!("{j}.support"))
            })
            .or(revolutes.last())
        else {
            continue;
        };
        let Some(old) = model.subsystem(chosen) else {
            continue;
        };
        let scalar = |name: &str, default: f64| {
            old.structural_value(name)
                .and_then(|v| v.first().copied())
                .unwrap_or(default)
        };
        let default = Revolute::default();
        let cut = Revolute {
            n: vector(old, "n", default.n),
            phi_start: scalar("phi_start", default.phi_start),
            w_start: scalar("w_start", default.w_start),
            state_priority: scalar("state_priority", default.state_priority),
            iscut: true,
            planar_cut: true,
            axisflange: flag(old, "axisflange"),
            radius: scalar("radius", default.radius),
            length: scalar("length", default.length),
            ..default
        };
        let (parent_path, local) = match chosen.rsplit_once('.') {
            Some((p, l)) => (Some(p), l),
            None => (None, chosen.as_str()),
        };
        let parent = match parent_path {
            Some(p) => out.subsystem_mut(p),
            None => Some(&mut out),
        };
        if let Some(parent) = parent {
            parent.replace(local, &cut);
        }
    }
    out
}
