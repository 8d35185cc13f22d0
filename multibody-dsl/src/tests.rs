//! Unit tests of parsing, checking and expansion.

use quote::quote;

use crate::ast::{ComponentDef, ConnectorDef, Item, SystemDef, SystemItem};

fn parse_component(t: proc_macro2::TokenStream) -> syn::Result<ComponentDef> {
    let d = syn::parse2::<ComponentDef>(t)?;
    crate::check::check_component(&d)?;
    Ok(d)
}

fn error_of(t: proc_macro2::TokenStream) -> String {
    match parse_component(t) {
        Ok(d) => match crate::expand::component(&d) {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}

#[test]
fn inertia_declaration_parses_every_kind_of_item() {
    let d = parse_component(quote! {
        /// An inertia.
        #[type_name = "Rotational.Inertia"]
        pub struct Inertia {
            /// Moment of inertia [kg.m2].
            parameter J: f64 = 1.0;
            structural use_support: bool = false;
            connector flange_a: Flange;
            connector flange_b: Flange;
            /// Absolute rotation angle [rad].
            variable phi(start = 0.0, state_priority = 10.0): Real;
            variable w: Real;
            component sub: Other = Other { k: 2.0 };
            extends Base { a, b };
            equation {
                phi = flange_a.phi;
                der(phi) = w;
                connect(flange_a, sub.flange);
                if use_support { w = 0.0; } else { w = 1.0; }
            }
            initial_equation {
                phi = 0.0;
            }
        }
    })
    .unwrap();
    assert_eq!(d.name, "Inertia");
    assert_eq!(d.type_name.unwrap().value(), "Rotational.Inertia");
    let kinds: Vec<&str> = d
        .items
        .iter()
        .map(|i| match i {
            Item::Parameter { .. } => "parameter",
            Item::Structural { .. } => "structural",
            Item::Connector { .. } => "connector",
            Item::Variable { .. } => "variable",
            Item::Component { .. } => "component",
            Item::Extends { .. } => "extends",
            Item::Equations { initial: false, .. } => "equation",
            Item::Equations { initial: true, .. } => "initial_equation",
        })
        .collect();
    assert_eq!(
        kinds,
        [
            "parameter",
            "structural",
            "connector",
            "connector",
            "variable",
            "variable",
            "component",
            "extends",
            "equation",
            "initial_equation"
        ]
    );
}

#[test]
fn expansion_declares_builder_calls() {
    let d = parse_component(quote! {
        pub struct Damper {
            /// Damping constant [N.m.s/rad].
            parameter d: f64 = 0.0;
            connector flange_a: Flange;
            variable w_rel: Real;
            equation {
                w_rel = der(flange_a.phi);
            }
        }
    })
    .unwrap();
    let out = crate::expand::component(&d).unwrap().to_string();
    for needle in [
        "pub struct Damper",
        "pub struct DamperHandle",
        "impl :: core :: default :: Default for Damper",
        "ParameterType :: declare",
        "add_connector (\"flange_a\"",
        "Variable :: new (\"w_rel\")",
        "__s . equate (w_rel , der (flange_a . phi))",
        "Default: `0.0`.",
    ] {
        assert!(out.contains(needle), "missing {needle} in {out}");
    }
}

#[test]
fn malformed_equations_are_errors_at_their_tokens() {
    let e = error_of(quote! {
        struct X { variable a: Real; equation { a == 1.0; } }
    });
    assert!(e.contains("single `=`"), "{e}");
    let e = error_of(quote! {
        struct X { variable a: Real; equation { a + 1.0; } }
    });
    assert!(e.contains("expected an equation"), "{e}");
    let e = error_of(quote! {
        struct X { variable a: Real; equation { connect(a); } }
    });
    assert!(e.contains("connect takes two connectors"), "{e}");
}

#[test]
fn bad_declarations_are_errors() {
    let e = error_of(quote! { struct X { variable a: Real; variable a: Real; } });
    assert!(e.contains("`a` is declared twice"), "{e}");
    let e = error_of(quote! { struct X { variable time: Real; } });
    assert!(e.contains("reserved"), "{e}");
    let e = error_of(quote! { struct X { variable a(strat = 1.0): Real; } });
    assert!(e.contains("unknown variable attribute `strat`"), "{e}");
    let e = error_of(quote! { struct X { parameter k: f64; } });
    assert!(e.contains("needs a default value"), "{e}");
    let e = error_of(quote! { struct X { varible a: Real; } });
    assert!(e.contains("unknown declaration `varible`"), "{e}");
}

#[test]
fn connectors_parse_and_expand() {
    let d = syn::parse2::<ConnectorDef>(quote! {
        /// A flange.
        pub struct Flange {
            /// Angle [rad].
            potential phi: Real;
            /// Torque [N.m].
            flow tau: Real;
        }
    })
    .unwrap();
    assert_eq!(d.vars.len(), 2);
    let out = crate::expand::connector(&d).unwrap().to_string();
    assert!(out.contains("pub struct FlangeHandle"), "{out}");
    assert!(out.contains("VarKind :: Flow"), "{out}");
    let s = syn::parse2::<ConnectorDef>(quote! { pub struct RealInput = input Real; }).unwrap();
    let out = crate::expand::connector(&s).unwrap().to_string();
    assert!(
        out.contains("type Handle = :: multibody :: __private :: Signal"),
        "{out}"
    );
    assert!(out.contains("signal:Real"), "{out}");
    let bad = crate::connector(quote! { pub struct P { across v: Real; } }).to_string();
    assert!(
        bad.contains("unknown connector variable kind `across`"),
        "{bad}"
    );
}

#[test]
fn system_items_and_struct_defaults() {
    let d = syn::parse2::<SystemDef>(quote! {
        name: "fourbar";
        world = World::default();
        j1 = Revolute { n: [1.0, 0.0, 0.0] };
        connect(world.frame_b, j1.frame_a);
        equation j1.phi = 0.0;
    })
    .unwrap();
    assert_eq!(d.name.as_ref().unwrap().value(), "fourbar");
    assert!(matches!(d.items[2], SystemItem::Connect { .. }));
    let out = crate::expand::system(&d).unwrap().to_string();
    assert!(
        out.contains(":: core :: default :: Default :: default ()"),
        "{out}"
    );
    assert!(out.contains("connect_handles"), "{out}");
    let bad = crate::system(quote! { connect(a.b); }).to_string();
    assert!(bad.contains("connect takes two connectors"), "{bad}");
    let bad = crate::system(quote! { a = A::default(); a = A::default(); }).to_string();
    assert!(bad.contains("declared twice"), "{bad}");
}

#[test]
fn unit_brackets_are_escaped_but_links_are_kept() {
    use crate::expand::escape_units;
    assert_eq!(escape_units("Inertia [kg.m2]."), "Inertia \\[kg.m2\\].");
    assert_eq!(escape_units("See [`Flange`]."), "See [`Flange`].");
    assert_eq!(
        escape_units("A [link](x) and [ref][r]"),
        "A [link](x) and [ref][r]"
    );
    assert_eq!(escape_units("no brackets"), "no brackets");
}

#[test]
fn graph_statements_become_branch_and_root_declarations() {
    let d = parse_component(quote! {
        pub struct Joint {
            connector frame_a: Frame;
            connector frame_b: Frame;
            variable phi: Real;
            equation {
                branch(frame_a.R, frame_b.R);
                if rooted(frame_a.R) {
                    frame_b.R = f(frame_a.R, phi);
                } else {
                    frame_a.R = g(frame_b.R, phi);
                }
            }
        }
    })
    .unwrap();
    let out = crate::expand::component(&d).unwrap().to_string();
    assert!(out.contains("__s . capture"), "{out}");
    assert!(
        out.contains("__s . branch (& frame_a . R , & frame_b . R , __a_rooted , __b_rooted)"),
        "{out}"
    );
    // `rooted` of the second orientation swaps the two sets.
    let d = parse_component(quote! {
        pub struct J2 {
            equation {
                branch(a.R, b.R);
                if rooted(b.R) { x = 1.0; } else { x = 2.0; }
            }
        }
    })
    .unwrap();
    let out = crate::expand::component(&d).unwrap().to_string();
    let first = out.find("x , 2.0").unwrap();
    let second = out.find("x , 1.0").unwrap();
    assert!(first < second, "{out}");
    // A branch with no conditional is registered with empty sets; roots immediately.
    let d = parse_component(quote! {
        pub struct Rigid {
            equation {
                root(frame_b.R);
                branch(a.R, b.R);
                potential_root(a.R, 2);
            }
        }
    })
    .unwrap();
    let out = crate::expand::component(&d).unwrap().to_string();
    assert!(out.contains("__s . root (& frame_b . R)"), "{out}");
    assert!(
        out.contains("__s . branch (& a . R , & b . R , :: std :: vec :: Vec :: new ()"),
        "{out}"
    );
    assert!(out.contains("__s . potential_root (& a . R , 2 ,"), "{out}");
    // rooted without a branch is an error.
    let d = parse_component(quote! {
        pub struct Bad { equation { if rooted(a.R) { x = 1.0; } } }
    })
    .unwrap();
    let e = crate::expand::component(&d).err().unwrap().to_string();
    assert!(e.contains("needs a preceding `branch(..)`"), "{e}");
}

#[test]
fn a_branch_inside_a_conditional_block_is_declared_only_there() {
    let d = parse_component(quote! {
        pub struct Cut {
            structural iscut: bool = false;
            connector frame_a: Frame;
            connector frame_b: Frame;
            equation {
                if iscut {
                    x = 1.0;
                } else {
                    branch(frame_a.R, frame_b.R);
                    frame_b.R = frame_a.R;
                }
            }
        }
    })
    .unwrap();
    let out = crate::expand::component(&d).unwrap().to_string();
    // The registration sits inside the `else` block: no brace closes it before.
    let branch_at = out.find("__s . branch").expect("the branch is declared");
    let else_at = out[..branch_at]
        .rfind("else {")
        .expect("inside the else block");
    assert!(!out[else_at + 6..branch_at].contains('}'), "{out}");
    assert_eq!(out.matches("__s . branch").count(), 1, "{out}");
}

#[test]
fn a_signal_connector_takes_a_start_and_nothing_else() {
    let d = parse_component(quote! {
        struct Lag {
            parameter y_start: f64 = 0.5;
            connector y(start = y_start): RealOutput;
        }
    })
    .unwrap();
    let Item::Connector { modifiers, .. } = &d.items[1] else {
        panic!("a connector");
    };
    assert_eq!(modifiers.len(), 1);
    assert_eq!(modifiers[0].key, "start");
    let code = crate::expand::component(&d).unwrap().to_string();
    assert!(code.contains("set_start (\"y\" , y_start)"), "{code}");
    let e = error_of(quote! { struct X { connector y(fixed = true): RealOutput; } });
    assert!(e.contains("only `start`") && e.contains("`fixed`"), "{e}");
}

#[test]
fn units_are_read_from_doc_comments() {
    use crate::expand::doc_unit;
    assert_eq!(doc_unit("Rotation angle \\[rad\\]").as_deref(), Some("rad"));
    assert_eq!(
        doc_unit("Angular acceleration `der(w)` \\[rad/s2\\].").as_deref(),
        Some("rad/s2")
    );
    assert_eq!(
        doc_unit("Torque \\[N.m\\] on `frame_b`").as_deref(),
        Some("N.m")
    );
    // Brackets in code spans are indices, not units.
    assert_eq!(doc_unit("Position `r_0[1]` of the frame"), None);
    assert_eq!(doc_unit("A sentence [with words] in brackets"), None);
    assert_eq!(doc_unit("No unit"), None);
}

#[test]
fn a_vector_start_is_set_element_by_element() {
    let d = parse_component(quote! {
        struct Spin {
            structural w0: [f64; 3] = [1.0, 2.0, 3.0];
            variable w(start = w0, fixed = true): Vec3;
            variable s(start = 0.5): Real;
        }
    })
    .unwrap();
    let code = crate::expand::component(&d).unwrap().to_string();
    // The vector's start goes through `VectorStart` after the declaration, per element;
    // its other attributes and a scalar's start stay on the builder.
    assert!(code.contains("VectorStart :: elements (w0)"), "{code}");
    assert!(code.contains(". fixed (true)"), "{code}");
    assert!(code.contains(". start (0.5)"), "{code}");
    assert!(!code.contains(". start (w0)"), "{code}");
}
