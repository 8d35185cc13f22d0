//! 3-D rendering of mechanisms: the GIF decodes with the requested frames and size,
//! frames follow the motion (they differ while the mechanism moves and stop differing
//! when it rests), and a frame seen along the z axis shows the parts where the solution
//! puts them (pixel colours at projected points, computed here with the pinhole formula).

#[path = "../examples/fourbar.rs"]
#[allow(dead_code)]
mod fourbar_example;

#[path = "../examples/pendulum.rs"]
#[allow(dead_code)]
mod pendulum_example;

#[path = "../examples/flexible_beam.rs"]
#[allow(dead_code)]
mod flexible_beam_example;

use std::path::PathBuf;

use multibody::forces::Spring;
use multibody::joints::Prismatic;
use multibody::parts::Body;
use multibody::prelude::*;
use multibody::render::{RenderError, render_frame, render_image};
use multibody::world::World;

fn out(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

fn fourbar() -> (System, Solution) {
    let model = fourbar_example::fourbar();
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default().with_output_interval(0.0, 2.0, 0.01))
        .unwrap();
    (model.into_system(), sol)
}

/// Plain options for tests: no grid, axes or label unless a test wants them.
fn bare(width: u32, height: u32, camera: [f64; 3], look_at: [f64; 3]) -> RenderOptions {
    RenderOptions {
        width,
        height,
        camera,
        look_at,
        grid: false,
        world_axes: 0.0,
        time_label: false,
        ..RenderOptions::default()
    }
}

/// The frames of a GIF as RGBA: the logical screen size, and each frame's delay in
/// hundredths of a second and pixels.
fn decode(path: &PathBuf) -> (u16, u16, Vec<(u16, Vec<u8>)>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let (w, h) = (decoder.width(), decoder.height());
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(
            (frame.left, frame.top, frame.width, frame.height),
            (0, 0, w, h)
        );
        frames.push((frame.delay, frame.buffer.to_vec()));
    }
    (w, h, frames)
}

fn differing_pixels(a: &[u8], b: &[u8]) -> usize {
    a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count()
}

#[test]
fn fourbar_gif_has_the_requested_frames_and_follows_the_motion() {
    let (model, sol) = fourbar();
    let path = out("render_fourbar.gif");
    let options = RenderOptions {
        times: Some((0..8).map(|k| 0.25 * k as f64).collect()),
        frame_delay_ms: 100,
        ..bare(120, 100, [4.0, -1.0, 4.0], [0.0, -1.0, 0.0])
    };
    render(&model, &sol, &path, &options).unwrap();
    let (w, h, frames) = decode(&path);
    assert_eq!((w, h), (120, 100));
    assert_eq!(frames.len(), 8);
    for (delay, pixels) in &frames {
        assert_eq!(*delay, 10);
        assert_eq!(pixels.len(), 120 * 100 * 4);
    }
    // The linkage falls and swings through these two seconds: every frame differs
    // from the one before in many pixels.
    for k in 1..frames.len() {
        let n = differing_pixels(&frames[k - 1].1, &frames[k].1);
        assert!(n > 30, "frames {} and {k} differ in {n} pixels", k - 1);
    }
}

#[test]
fn a_damped_pendulum_at_rest_gives_identical_frames() {
    let model = pendulum_example::pendulum();
    let ssys = structural_simplify(&model).unwrap();
    // Over-damped: J = 0.251 kg.m2, m g L = 4.9 N.m, critical d = 2.2 N.m.s/rad. The
    // slow mode decays as exp(-1.95 t): 1e-7 rad after 9 s.
    let sol = DaeProblem::new(&ssys, &[("damper.d", 3.0)], (0.0, 12.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let phi = sol.final_value("rev.phi").unwrap();
    assert!(
        (phi + std::f64::consts::FRAC_PI_2).abs() < 1e-4,
        "phi = {phi}"
    );
    let path = out("render_pendulum.gif");
    let times: Vec<f64> = (0..=24).map(|k| 0.5 * k as f64).collect();
    let options = RenderOptions {
        times: Some(times.clone()),
        grid: true,
        world_axes: 0.5,
        ..bare(120, 120, [0.8, 0.3, 1.8], [0.0, -0.25, 0.0])
    };
    render(&model, &sol, &path, &options).unwrap();
    let (_, _, frames) = decode(&path);
    assert_eq!(frames.len(), times.len());
    // Moving at first...
    for k in 1..=3 {
        assert!(differing_pixels(&frames[k - 1].1, &frames[k].1) > 20);
    }
    // ... at rest from 9 s on: pixel for pixel the same.
    for k in 19..frames.len() {
        assert_eq!(
            differing_pixels(&frames[k - 1].1, &frames[k].1),
            0,
            "t = {}",
            times[k]
        );
    }
}

/// Column and row of a world point seen by a camera at `(0, 0, d)` looking at the
/// origin with y up: `f = (h/2) / tan(fov/2)`, the image centre at `(w/2, h/2)`.
fn project(p: [f64; 3], d: f64, fov_deg: f64, (w, h): (u32, u32)) -> (u32, u32) {
    let f = 0.5 * h as f64 / (0.5 * fov_deg.to_radians()).tan();
    let z = d - p[2];
    let col = 0.5 * w as f64 + f * p[0] / z;
    let row = 0.5 * h as f64 - f * p[1] / z;
    (col.floor() as u32, row.floor() as u32)
}

fn position(sol: &Solution, frame: &str, t: f64) -> [f64; 3] {
    std::array::from_fn(|i| sol.at(format!("{frame}.r_0[{}]", i + 1), t).unwrap())
}

/// Distance from `p` to the segment from `a` to `b` (in the x-y plane).
fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let s = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    ((p[0] - a[0] - s * dx).powi(2) + (p[1] - a[1] - s * dy).powi(2)).sqrt()
}

/// The colour of a shaded `BodyShape` (MSL's body colour {0, 128, 255} times a shade).
fn is_link(c: [u8; 3]) -> bool {
    c[0] == 0 && c[2] > 80 && (c[1] as f64 - c[2] as f64 * 128.0 / 255.0).abs() <= 2.0
}

#[test]
fn a_frame_along_the_z_axis_shows_the_links_where_the_solution_puts_them() {
    let (model, sol) = fourbar();
    let (d, fov, size) = (6.0, 50.0, (400, 400));
    let t = 1.0;
    let options = RenderOptions {
        fov,
        times: Some(vec![t]),
        ..bare(size.0, size.1, [0.0, 0.0, d], [0.0; 3])
    };
    let path = out("render_fourbar_z.gif");
    render(&model, &sol, &path, &options).unwrap();
    let (_, _, frames) = decode(&path);
    assert_eq!(frames.len(), 1);
    let pixels = &frames[0].1;
    let pixel = |(x, y): (u32, u32)| {
        let i = 4 * (y as usize * size.0 as usize + x as usize);
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let links = ["b1", "b2", "b3", "b4"].map(|b| {
        (
            position(&sol, &format!("{b}.frame_a"), t),
            position(&sol, &format!("{b}.frame_b"), t),
        )
    });
    for (b, (a, e)) in links.iter().enumerate() {
        // A 3 cm thick link is 4 pixels wide here: its midpoint is link-coloured.
        let mid = std::array::from_fn(|i| 0.5 * (a[i] + e[i]));
        let c = pixel(project(mid, d, fov, size));
        assert!(is_link(c), "midpoint of b{} at {mid:?}: {c:?}", b + 1);
        // Joints (red cylinders along z, 5 cm radius) at the links' ends.
        let c = pixel(project(*e, d, fov, size));
        assert!(
            c[0] > 100 && c[1] == 0 && c[2] == 0,
            "joint at {e:?}: {c:?}"
        );
    }
    // The middle of the rhombus, and where b2's midpoint was at t = 0, are far from
    // every link now: background.
    let centre: [f64; 3] =
        std::array::from_fn(|i| links.iter().map(|(a, _)| a[i]).sum::<f64>() / 4.0);
    let (a0, e0) = (
        position(&sol, "b2.frame_a", 0.0),
        position(&sol, "b2.frame_b", 0.0),
    );
    let then: [f64; 3] = std::array::from_fn(|i| 0.5 * (a0[i] + e0[i]));
    for p in [centre, then] {
        let gap = links
            .iter()
            .map(|(a, e)| distance_to_segment(p, *a, *e))
            .fold(f64::INFINITY, f64::min);
        assert!(gap > 0.2, "{p:?} is {gap} m from a link");
        assert_eq!(pixel(project(p, d, fov, size)), [255, 255, 255], "at {p:?}");
    }
}

#[test]
fn a_spring_is_drawn_as_a_helix_between_its_frames() {
    let model = system! {
        name: "spring_mass";
        world = World::default();
        slider = Prismatic { n: [0.0, 1.0, 0.0], s_start: -0.6, width: 0.0 };
        body = Body { m: 1.0, radius: 0.08 };
        spring = Spring { c: 30.0, s_unstretched: 0.4, radius: 0.06 };
        connect(world.frame_b, slider.frame_a);
        connect(slider.frame_b, body.frame_a);
        connect(world.frame_b, spring.frame_a);
        connect(spring.frame_b, body.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let (d, fov, size) = (3.0, 40.0, (160, 160));
    let options = RenderOptions {
        fov,
        ..bare(size.0, size.1, [0.0, 0.0, d], [0.0; 3])
    };
    let t = 0.5;
    let image = render_image(&model, &sol, t, &options).unwrap();
    let y = sol.at("body.frame_a.r_0[2]", t).unwrap();
    assert!(y < -0.3, "the body hangs below the origin: y = {y}");
    // The body's sphere at its frame, blue.
    let (x, r) = project([0.0, y, 0.0], d, fov, size);
    let c = image.pixel(x, r).unwrap();
    assert!(c[0] == 0 && c[2] > 80, "{c:?}");
    // Spring-coloured pixels ({0, 0, 255} shaded) only between the origin and the
    // body, within the coil radius of the y axis.
    let (x0, top) = project([0.06, 0.0, 0.0], d, fov, size);
    let (_, bottom) = project([0.0, y, 0.0], d, fov, size);
    let spring: Vec<(u32, u32)> = (0..size.1)
        .flat_map(|r| (0..size.0).map(move |x| (x, r)))
        .filter(|&(x, r)| {
            let c = image.pixel(x, r).unwrap();
            c[0] == 0 && c[1] == 0 && c[2] > 60
        })
        .collect();
    assert!(spring.len() > 50, "{} spring pixels", spring.len());
    let half = x0 - size.0 / 2 + 2;
    for (x, r) in spring {
        assert!(
            x.abs_diff(size.0 / 2) <= half && r + 2 >= top && r <= bottom + 2,
            "({x}, {r})"
        );
    }
}

#[test]
fn a_frame_is_written_as_png_with_the_time() {
    let (model, sol) = fourbar();
    let path = out("render_fourbar.png");
    let options = RenderOptions {
        width: 160,
        height: 120,
        ..RenderOptions::default()
    };
    render_frame(&model, &sol, 0.5, &path, &options).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes[..8], *b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big-endian.
    assert_eq!(bytes[16..24], [0, 0, 0, 160, 0, 0, 0, 120]);
    // The time label darkens pixels in the top left corner only.
    let with = render_image(&model, &sol, 0.5, &options).unwrap();
    let without = render_image(
        &model,
        &sol,
        0.5,
        &RenderOptions {
            time_label: false,
            ..options
        },
    )
    .unwrap();
    let mut changed = Vec::new();
    for y in 0..120 {
        for x in 0..160 {
            if with.pixel(x, y) != without.pixel(x, y) {
                changed.push((x, y));
            }
        }
    }
    assert!(changed.len() > 30, "{} label pixels", changed.len());
    assert!(
        changed.iter().all(|&(x, y)| x < 110 && y < 25),
        "{changed:?}"
    );
}

#[test]
fn bad_requests_are_errors() {
    let (model, sol) = fourbar();
    let path = out("render_bad.gif");
    let with = |f: fn(&mut RenderOptions)| {
        let mut o = RenderOptions {
            times: Some(vec![0.0, 1.0]),
            ..RenderOptions::default()
        };
        f(&mut o);
        render(&model, &sol, &path, &o).unwrap_err()
    };
    assert!(matches!(
        with(|o| o.times = Some(vec![])),
        RenderError::NoFrames
    ));
    assert!(matches!(
        with(|o| o.width = 0),
        RenderError::ImageSize { width: 0, .. }
    ));
    assert!(matches!(
        with(|o| o.times = Some(vec![0.0, 3.0])),
        RenderError::TimeOutOfRange { t: 3.0, .. }
    ));
    assert!(matches!(
        with(|o| o.times = Some(vec![f64::NAN])),
        RenderError::TimeOutOfRange { .. }
    ));
    assert!(matches!(
        with(|o| o.look_at = o.camera),
        RenderError::Camera(_)
    ));
    assert!(matches!(with(|o| o.up = [0.0; 3]), RenderError::Camera(_)));
    // A solution of another model: the pendulum's body is not in the four-bar's.
    let err = render(
        &pendulum_example::pendulum(),
        &sol,
        &path,
        &RenderOptions::default(),
    )
    .unwrap_err();
    match &err {
        RenderError::MissingVariable { component, .. } => assert_eq!(component, "rev"),
        e => panic!("{e}"),
    }
    assert!(err.to_string().contains("rev.frame_a"), "{err}");
    let e: multibody::Error = err.into();
    assert!(matches!(e, multibody::Error::Solution(_)));
    // An unwritable path.
    let err = render(
        &model,
        &sol,
        "/nonexistent-dir/x.gif",
        &RenderOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(err, RenderError::Write { .. }), "{err}");
}

#[test]
fn a_flexible_beam_is_drawn_bent_along_its_deflection_curve() {
    use multibody::parts::{CrossSection, FlexibleBeam, section_properties};
    // A critically damped 5 cm square cantilever along x, settled under a load -P y at
    // its end that bends it 0.4 m down.
    let beam = FlexibleBeam {
        cross_section: CrossSection::Rectangle {
            width: 0.05,
            height: 0.05,
        },
        n_bending_xz: 0,
        damping: 1.0,
        ..FlexibleBeam::default()
    };
    let (l, ei) = (beam.l, beam.E * section_properties(beam.cross_section).2);
    let p = 0.4 * 3.0 * ei / l.powi(3);
    let model = flexible_beam_example::cantilever(beam, [0.0, -p, 0.0]);
    let ssys = structural_simplify(&model).unwrap();
    let t = 0.5;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // The closed-form deflection curve w(x) = -P x^2 (3 l - x) / (6 E I).
    let w = |x: f64| -p * x * x * (3.0 * l - x) / (6.0 * ei);
    let tip = sol.at("beam.u_b[2]", t).unwrap();
    assert!((tip - w(l)).abs() < 0.01 * w(l).abs(), "{tip} vs {}", w(l));
    let (d, fov, size) = (2.5, 50.0, (400, 400));
    let centre = [0.8, -0.2, 0.0];
    let options = RenderOptions {
        fov,
        times: Some(vec![t]),
        ..bare(size.0, size.1, [centre[0], centre[1], d], centre)
    };
    let path = out("render_bent_beam.gif");
    render(&model, &sol, &path, &options).unwrap();
    let (_, _, frames) = decode(&path);
    let pixels = &frames[0].1;
    let pixel = |q: [f64; 3]| {
        let (x, y) = project(std::array::from_fn(|i| q[i] - centre[i]), d, fov, size);
        let i = 4 * (y as usize * size.0 as usize + x as usize);
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    // On the curve: the beam's colour; on the chord from the root to the end (7.5 cm
    // above the curve at the middle): background.
    for x in [0.25 * l, 0.5 * l, 0.75 * l] {
        let c = pixel([x, w(x), 0.0]);
        assert!(is_link(c), "on the curve at x = {x}: {c:?}");
    }
    let c = pixel([0.5 * l, 0.5 * w(l), 0.0]);
    assert_eq!(c, [255, 255, 255], "on the chord");
}
