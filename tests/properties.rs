//! Random models, some with degenerate parameters: random 1-D networks of inertias,
//! springs and dampers, and random 3-D trees (some closed into a loop) of bodies and
//! joints with random axes. For every one: no panic; either an error whose message names
//! the model or one of its components, or outputs that are all finite; and a
//! conservative model (no dampers, physical parameters) keeps its energy.
//!
//! The cases run in CI are fixed (`PROPTEST_CASES`, default 48 per property). A long
//! campaign: `PROPTEST_CASES=20000 cargo test --release --test properties`; a failure
//! is shrunk to a small model and written to `tests/properties.proptest-regressions`,
//! which then reruns it first.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, relative_drift};
use multibody::joints::{Prismatic, Revolute, Spherical};
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::rotational::{Damper, Fixed, Inertia, Spring};
use multibody::world::World;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Cases per property unless `PROPTEST_CASES` says otherwise.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(48);
    ProptestConfig {
        cases,
        // Shrinking a failure compiles many models: bounded, so a failure reports soon.
        max_shrink_iters: 200,
        ..ProptestConfig::default()
    }
}

/// A parameter value: usually physical, sometimes degenerate (0, negative, huge, tiny,
/// NaN or infinite).
fn value(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        40 => lo..hi,
        1 => Just(0.0),
        1 => -hi..-lo,
        1 => Just(1e12),
        1 => Just(1e-12),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
    ]
}

fn physical(v: f64) -> bool {
    v.is_finite() && (1e-3..=1e3).contains(&v)
}

/// Checks what a model gave: an error naming the model or one of `parts`, or finite
/// values of `read`. Returns the solution when it exists.
fn outcome(
    model: &(impl AsRef<System> + ?Sized),
    parts: &[String],
    read: &[String],
    options: &SolverOptions,
) -> Result<Option<Solution>, TestCaseError> {
    let model = model.as_ref();
    let result = structural_simplify(model)
        .and_then(|ssys| DaeProblem::new(&ssys, &[], (0.0, 2.0))?.solve(options));
    let named =
        |text: &str| text.contains(&model.name) || parts.iter().any(|p| text.contains(p.as_str()));
    match result {
        Err(e) => {
            let text = e.to_string();
            prop_assert!(named(&text), "an error that names nothing: {text}");
            Ok(None)
        }
        Ok(sol) => {
            let refs: Vec<&str> = read.iter().map(String::as_str).collect();
            match sol.get_many(&refs) {
                Ok(series) => {
                    for (name, s) in read.iter().zip(&series) {
                        prop_assert!(
                            s.iter().all(|v| v.is_finite()),
                            "`{name}` has a value that is not finite without an error"
                        );
                    }
                    Ok(Some(sol))
                }
                Err(e) => {
                    // A value that is not finite is reported by name.
                    let text = e.to_string();
                    prop_assert!(read.iter().any(|n| text.contains(n.as_str())), "{text}");
                    Ok(None)
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// 1-D networks.

/// An element between two nodes (node 0 is the fixed housing when `grounded`).
#[derive(Clone, Debug)]
struct Element {
    a: usize,
    b: usize,
    spring: bool,
    k: f64,
}

#[derive(Clone, Debug)]
struct Network {
    grounded: bool,
    inertias: Vec<(f64, f64)>,
    elements: Vec<Element>,
}

fn network() -> impl Strategy<Value = Network> {
    (1usize..6, any::<bool>()).prop_flat_map(|(n, grounded)| {
        let nodes = n + usize::from(grounded);
        (
            Just(grounded),
            prop::collection::vec((value(0.1, 10.0), -1.0..1.0f64), n),
            prop::collection::vec(
                (
                    0..nodes,
                    0..nodes,
                    prop::bool::weighted(0.7),
                    value(0.1, 100.0),
                )
                    .prop_map(|(a, b, spring, k)| Element { a, b, spring, k }),
                0..(2 * nodes),
            ),
        )
            .prop_map(|(grounded, inertias, elements)| Network {
                grounded,
                inertias,
                elements,
            })
    })
}

/// The flange path of node `i`.
fn node(net: &Network, i: usize) -> String {
    match (net.grounded, i) {
        (true, 0) => "fixed.flange".into(),
        (true, i) => format!("i{}.flange_a", i - 1),
        (false, i) => format!("i{i}.flange_a"),
    }
}

fn build_network(net: &Network) -> System {
    let mut m = System::new("network");
    if net.grounded {
        m.add("fixed", &Fixed::default());
    }
    for (k, &(j, phi)) in net.inertias.iter().enumerate() {
        m.add(
            &format!("i{k}"),
            &Inertia {
                J: j,
                phi_start: phi,
                ..Default::default()
            },
        );
    }
    for (k, e) in net.elements.iter().enumerate() {
        let name = format!("e{k}");
        if e.spring {
            m.add(
                &name,
                &Spring {
                    c: e.k,
                    ..Default::default()
                },
            );
        } else {
            m.add(&name, &Damper { d: e.k });
        }
        m.connect(&node(net, e.a), &format!("{name}.flange_a"));
        m.connect(&format!("{name}.flange_b"), &node(net, e.b));
    }
    m
}

/// Kinetic energy of the inertias and potential energy of the springs.
fn network_energy(net: &Network, sol: &Solution) -> Vec<f64> {
    let mut total = vec![0.0; sol.t().len()];
    for (k, &(j, _)) in net.inertias.iter().enumerate() {
        let w = sol.get(format!("i{k}.w")).expect("w");
        for (e, w) in total.iter_mut().zip(w) {
            *e += 0.5 * j * w * w;
        }
    }
    for (k, el) in net.elements.iter().enumerate() {
        let phi = sol.get(format!("e{k}.phi_rel")).expect("phi_rel");
        for (e, p) in total.iter_mut().zip(phi) {
            *e += 0.5 * el.k * p * p;
        }
    }
    total
}

fn check_network(net: &Network) -> Result<(), TestCaseError> {
    let model = build_network(net);
    let mut parts: Vec<String> = (0..net.inertias.len()).map(|k| format!("i{k}")).collect();
    parts.extend((0..net.elements.len()).map(|k| format!("e{k}")));
    let read: Vec<String> = (0..net.inertias.len())
        .flat_map(|k| [format!("i{k}.phi"), format!("i{k}.w")])
        .collect();
    let options = SolverOptions {
        rtol: 1e-9,
        atol: 1e-11,
        ..Default::default()
    };
    let Some(sol) = outcome(&model, &parts, &read, &options)? else {
        return Ok(());
    };
    let conservative = net.inertias.iter().all(|&(j, _)| physical(j))
        && net.elements.iter().all(|e| e.spring && physical(e.k));
    if conservative {
        let energy = network_energy(net, &sol);
        let scale = energy[0].abs().max(1e-6);
        let drift = relative_drift(&energy, scale);
        prop_assert!(drift < 1e-4, "energy drift {drift:e} of {net:?}");
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// 3-D trees and loops.

#[derive(Clone, Debug)]
enum JointKind {
    Revolute([f64; 3]),
    Prismatic([f64; 3]),
    Spherical,
}

#[derive(Clone, Debug)]
struct Link {
    /// The body (or the world, 0) whose `frame_a` this link hangs from.
    parent: usize,
    offset: [f64; 3],
    joint: JointKind,
    m: f64,
    r_cm: [f64; 3],
    inertia: [f64; 3],
}

#[derive(Clone, Debug)]
struct Tree {
    links: Vec<Link>,
    /// Close a loop: a spherical joint from the last body to the world at this offset.
    closing: Option<[f64; 3]>,
}

fn axis() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        8 => prop::array::uniform3(-1.0..1.0f64),
        1 => Just([0.0, 0.0, 0.0]),
        1 => Just([0.0, 0.0, 1.0]),
    ]
}

fn joint() -> impl Strategy<Value = JointKind> {
    prop_oneof![
        5 => axis().prop_map(JointKind::Revolute),
        2 => axis().prop_map(JointKind::Prismatic),
        1 => Just(JointKind::Spherical),
    ]
}

fn tree() -> impl Strategy<Value = Tree> {
    (1usize..4)
        .prop_flat_map(|n| {
            let links = (0..n)
                .map(|k| {
                    (
                        0..=k,
                        prop::array::uniform3(-0.5..0.5f64),
                        joint(),
                        value(0.1, 5.0),
                        prop::array::uniform3(-0.3..0.3f64),
                        prop::array::uniform3(value(0.001, 0.1)),
                    )
                        .prop_map(
                            |(parent, offset, joint, m, r_cm, inertia)| Link {
                                parent,
                                offset,
                                joint,
                                m,
                                r_cm,
                                inertia,
                            },
                        )
                })
                .collect::<Vec<_>>();
            (
                links,
                prop::option::weighted(0.2, prop::array::uniform3(-1.0..1.0f64)),
            )
        })
        .prop_map(|(links, closing)| Tree { links, closing })
}

const G: f64 = 9.81;

fn build_tree(tree: &Tree) -> System {
    let mut m = System::new("tree");
    m.add(
        "world",
        &World {
            g: G,
            ..Default::default()
        },
    );
    let frame = |p: usize| {
        if p == 0 {
            "world.frame_b".to_string()
        } else {
            format!("b{p}.frame_a")
        }
    };
    for (k, l) in tree.links.iter().enumerate() {
        let k = k + 1;
        m.add(
            &format!("o{k}"),
            &FixedTranslation {
                r: l.offset,
                ..Default::default()
            },
        );
        let j = format!("j{k}");
        match l.joint {
            JointKind::Revolute(n) => {
                m.add(
                    &j,
                    &Revolute {
                        n,
                        ..Default::default()
                    },
                );
            }
            JointKind::Prismatic(n) => {
                m.add(
                    &j,
                    &Prismatic {
                        n,
                        ..Default::default()
                    },
                );
            }
            JointKind::Spherical => {
                m.add(&j, &Spherical::default());
            }
        }
        m.add(
            &format!("b{k}"),
            &Body {
                m: l.m,
                r_CM: l.r_cm,
                I_11: l.inertia[0],
                I_22: l.inertia[1],
                I_33: l.inertia[2],
                ..Default::default()
            },
        );
        m.connect(&frame(l.parent), &format!("o{k}.frame_a"));
        m.connect(&format!("o{k}.frame_b"), &format!("{j}.frame_a"));
        m.connect(&format!("{j}.frame_b"), &format!("b{k}.frame_a"));
    }
    if let Some(r) = tree.closing {
        m.add(
            "closing_rod",
            &FixedTranslation {
                r,
                ..Default::default()
            },
        );
        m.add("closing", &Spherical::default());
        m.connect("world.frame_b", "closing_rod.frame_a");
        m.connect("closing_rod.frame_b", "closing.frame_a");
        m.connect("closing.frame_b", &format!("b{}.frame_a", tree.links.len()));
    }
    m
}

fn check_tree(tree: &Tree) -> Result<(), TestCaseError> {
    let model = build_tree(tree);
    let n = tree.links.len();
    let mut parts: Vec<String> = (1..=n)
        .flat_map(|k| [format!("b{k}"), format!("j{k}"), format!("o{k}")])
        .collect();
    parts.extend(["closing".to_string(), "world".to_string()]);
    let read: Vec<String> = (1..=n)
        .flat_map(|k| (1..=3).map(move |i| format!("b{k}.r_0[{i}]")))
        .collect();
    let options = SolverOptions {
        rtol: 1e-8,
        atol: 1e-10,
        ..Default::default()
    };
    let Some(sol) = outcome(&model, &parts, &read, &options)? else {
        return Ok(());
    };
    let conservative = tree
        .links
        .iter()
        .all(|l| physical(l.m) && l.inertia.iter().all(|&i| physical(i)));
    if conservative {
        let mut total = vec![0.0; sol.t().len()];
        let mut scale: f64 = 1e-6;
        for (k, l) in tree.links.iter().enumerate() {
            let p = MassProps {
                m: l.m,
                r_cm: l.r_cm,
                inertia: [
                    [l.inertia[0], 0.0, 0.0],
                    [0.0, l.inertia[1], 0.0],
                    [0.0, 0.0, l.inertia[2]],
                ],
            };
            let e = body_energy(&sol, &format!("b{}", k + 1), p, G, [0.0, -1.0, 0.0]);
            // The size of the energies exchanged: m g times a length of the tree.
            scale = scale.max(l.m * G * 1.0);
            for (t, e) in total.iter_mut().zip(e) {
                *t += e;
            }
        }
        let drift = relative_drift(&total, scale);
        prop_assert!(drift < 1e-4, "energy drift {drift:e} of {tree:?}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_1d_networks_never_panic_nor_report_what_they_did_not_compute(net in network()) {
        check_network(&net)?;
    }

    #[test]
    fn random_3d_trees_and_loops_never_panic_nor_report_what_they_did_not_compute(tree in tree()) {
        check_tree(&tree)?;
    }
}
