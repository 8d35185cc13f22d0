//! Tests of the figure layout, drawing and errors.

use super::draw::*;
use super::*;

fn demo_panels() -> Vec<Panel> {
    let t: Vec<f64> = (0..=200).map(|i| f64::from(i) * 0.05).collect();
    let sin = t.iter().map(|t| t.sin()).collect();
    let cos = t.iter().map(|t| t.cos()).collect();
    vec![
        Panel {
            title: None,
            x_label: String::new(),
            y_label: "x [m]".into(),
            series: vec![
                Series {
                    label: "sin(t)".into(),
                    t: t.clone(),
                    y: sin,
                },
                Series {
                    label: "cos(t)".into(),
                    t: t.clone(),
                    y: cos,
                },
            ],
        },
        Panel {
            title: Some("Constant".into()),
            x_label: "time [s]".into(),
            y_label: "F [N]".into(),
            series: vec![Series {
                label: "F = 9.81".into(),
                t: t.clone(),
                y: vec![9.81; t.len()],
            }],
        },
    ]
}

fn pixel(buf: &[u8], w: u32, x: u32, y: u32) -> [u8; 3] {
    let i = 3 * (y as usize * w as usize + x as usize);
    [buf[i], buf[i + 1], buf[i + 2]]
}

fn unique_temp_png(tag: &str) -> std::path::PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    std::env::temp_dir().join(format!(
        "multibody-plot-{tag}-{}-{nanos}.png",
        std::process::id()
    ))
}

#[test]
fn buffer_has_curves_and_legend_text() {
    let panels = demo_panels();
    let options = PlotOptions::default();
    let (w, h) = figure_size(panels.len(), &options);
    assert_eq!((w, h), (1200, 500));
    let buf = render_to_buffer(&panels, &options).unwrap();
    assert_eq!(buf.len(), (w * h * 3) as usize);
    assert!(buf.iter().any(|&b| b != 255), "figure is all white");

    // Legend of the first panel: inside its plotting area (right of the y tick labels,
    // above the x tick labels, x < 600), the only dark pixels there.
    let mut dark = 0;
    for y in 15..420 {
        for x in 110..595 {
            let [r, g, b] = pixel(&buf, w, x, y);
            if r < 100 && g < 100 && b < 100 {
                dark += 1;
            }
        }
    }
    assert!(dark > 50, "no legend text found ({dark} dark pixels)");

    let near = |p: [u8; 3], c: RGBColor| {
        (i32::from(p[0]) - i32::from(c.0)).abs() < 12
            && (i32::from(p[1]) - i32::from(c.1)).abs() < 12
            && (i32::from(p[2]) - i32::from(c.2)).abs() < 12
    };
    let count = |c: RGBColor, xs: std::ops::Range<u32>| {
        let mut n = 0;
        for y in 0..h {
            for x in xs.clone() {
                if near(pixel(&buf, w, x, y), c) {
                    n += 1;
                }
            }
        }
        n
    };
    assert!(
        count(PALETTE[0], 0..600) > 300,
        "first curve colour missing"
    );
    assert!(
        count(PALETTE[1], 0..600) > 300,
        "second curve colour missing"
    );
    assert!(count(PALETTE[0], 600..1200) > 300, "constant curve missing");
    assert_eq!(
        count(PALETTE[1], 600..1200),
        0,
        "second panel uses one colour only"
    );
}

/// Width, height, bit depth and colour type from a PNG's IHDR chunk (the first
/// chunk, right after the 8-byte signature; PNG specification, section 11.2.2).
fn png_header(bytes: &[u8]) -> (u32, u32, u8, u8) {
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR", "the first chunk is not IHDR");
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20), bytes[24], bytes[25])
}

#[test]
fn writes_png_file() {
    let path = unique_temp_png("demo");
    let options = PlotOptions {
        width: 900,
        height: 300,
        ..PlotOptions::default()
    };
    plot_panels(&demo_panels(), &path, &options).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    // The asked size (two panels side by side: one row), 8-bit RGB (colour type 2).
    assert_eq!(png_header(&bytes), (900, 300, 8, 2));
    assert!(bytes.len() > 1000);
    if std::env::var_os("MULTIBODY_KEEP_PLOT").is_none() {
        let _ = std::fs::remove_file(&path);
    }
}

#[test]
fn layout_rows_and_columns() {
    let o = PlotOptions::default();
    assert_eq!(grid(1, &o), (1, 1));
    assert_eq!(grid(2, &o), (2, 1));
    assert_eq!(grid(3, &o), (2, 2));
    assert_eq!(figure_size(3, &o), (1200, 1000));
    let o1 = PlotOptions {
        columns: 1,
        ..o.clone()
    };
    assert_eq!(grid(3, &o1), (1, 3));
    let o0 = PlotOptions { columns: 0, ..o };
    assert_eq!(grid(5, &o0), (2, 3));
}

#[test]
fn three_panels_with_nan_render() {
    let mut panels = demo_panels();
    let t: Vec<f64> = (0..50).map(f64::from).collect();
    let mut y: Vec<f64> = t.iter().map(|t| t * t).collect();
    y[10] = f64::NAN;
    y[12] = f64::NAN; // isolated point 11 becomes a dot
    panels.push(Panel {
        series: vec![Series {
            label: String::new(),
            t,
            y,
        }],
        ..Panel::default()
    });
    let options = PlotOptions {
        columns: 2,
        ..PlotOptions::default()
    };
    let buf = render_to_buffer(&panels, &options).unwrap();
    assert_eq!(buf.len(), 1200 * 1000 * 3);
    // The third panel (bottom left, x < 600, y >= 500) draws y = t^2 in the first
    // palette colour, and nothing else in that colour (no legend: empty label).
    let (w, h) = (1200u32, 1000u32);
    let near = |p: [u8; 3], c: RGBColor| {
        (i32::from(p[0]) - i32::from(c.0)).abs() < 12
            && (i32::from(p[1]) - i32::from(c.1)).abs() < 12
            && (i32::from(p[2]) - i32::from(c.2)).abs() < 12
    };
    let columns: Vec<Vec<u32>> = (0..600)
        .map(|x| {
            (500..h)
                .filter(|&y| near(pixel(&buf, w, x, y), PALETTE[0]))
                .collect()
        })
        .collect();
    let drawn: Vec<usize> = (0..600).filter(|&x| !columns[x].is_empty()).collect();
    let (xa, xb) = (drawn[0], *drawn.last().unwrap());
    let rows = drawn.iter().flat_map(|&x| columns[x].iter().copied());
    let (r_top, r_bottom) = rows.fold((u32::MAX, 0), |(a, b), r| (a.min(r), b.max(r)));
    // The curve spans most of the panel both ways.
    assert!(
        xb - xa > 400 && r_bottom - r_top > 300,
        "{xa}..{xb}, {r_top}..{r_bottom}"
    );
    // Pixel column -> t and t -> row, linear between the curve's ends (t = 0 at the
    // bottom left, t = 49 at the top right, up to the line's half width).
    let t_of = |x: usize| 49.0 * (x - xa) as f64 / (xb - xa) as f64;
    let x_of = |t: f64| xa as f64 + t / 49.0 * (xb - xa) as f64;
    let row_of = |t: f64| f64::from(r_bottom) - (t / 49.0).powi(2) * f64::from(r_bottom - r_top);
    // Within 3 pixels of a run's end (t = 0, 9, 13, 49) the line's caps and the
    // mapping's pixel rounding leave it open whether a column is drawn: skipped.
    let near = |x: usize, t: f64| (x as f64 - x_of(t)).abs() <= 3.0;
    for x in xa..=xb {
        let t = t_of(x);
        if [0.0, 9.0, 11.0, 13.0, 49.0].iter().any(|&end| near(x, end)) {
            continue;
        }
        if t > 9.0 && t < 13.0 {
            // NaN at t = 10 and 12 break the line: nothing between 9 and 13 but the
            // isolated point at t = 11.
            assert!(columns[x].is_empty(), "column {x} (t = {t:.2}) is drawn");
        } else {
            // The parabola passes through this column within 3 pixels (the line is
            // 2 pixels wide; its steepest part climbs 2 rows per column).
            let expected = row_of(t);
            let miss = columns[x]
                .iter()
                .map(|&r| (f64::from(r) - expected).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(
                miss <= 3.0,
                "column {x} (t = {t:.2}): curve {miss} px from y = t^2"
            );
        }
    }
    // The isolated point at t = 11 is a dot at y = 121.
    assert!(
        (xa..=xb)
            .filter(|&x| near(x, 11.0))
            .flat_map(|x| columns[x].iter())
            .any(|&r| (f64::from(r) - row_of(11.0)).abs() <= 3.0),
        "no dot at t = 11"
    );
    let path = unique_temp_png("three");
    plot_panels(&panels, &path, &options).unwrap();
    assert_eq!(
        png_header(&std::fs::read(&path).unwrap()),
        (1200, 1000, 8, 2)
    );
    if std::env::var_os("MULTIBODY_KEEP_PLOT").is_none() {
        let _ = std::fs::remove_file(&path);
    }
}

#[test]
fn errors() {
    let o = PlotOptions::default();
    assert!(matches!(
        render_to_buffer(&[], &o),
        Err(PlotError::Empty(_))
    ));
    assert!(matches!(
        render_to_buffer(&[Panel::default()], &o),
        Err(PlotError::Empty(_))
    ));

    let no_points = Panel {
        series: vec![Series {
            label: "a".into(),
            t: vec![],
            y: vec![],
        }],
        ..Panel::default()
    };
    assert!(matches!(
        render_to_buffer(&[no_points], &o),
        Err(PlotError::Empty(_))
    ));

    let mismatch = Panel {
        series: vec![Series {
            label: "bad".into(),
            t: vec![0.0, 1.0, 2.0],
            y: vec![1.0, 2.0],
        }],
        ..Panel::default()
    };
    match render_to_buffer(std::slice::from_ref(&mismatch), &o) {
        Err(PlotError::LengthMismatch { label, t, y }) => {
            assert_eq!((label.as_str(), t, y), ("bad", 3, 2))
        }
        other => panic!("expected LengthMismatch, got {other:?}"),
    }
    let path = unique_temp_png("mismatch");
    assert!(matches!(
        plot_panels(&[mismatch], &path, &o),
        Err(PlotError::LengthMismatch { .. })
    ));
    assert!(!path.exists());

    let all_nan = Panel {
        series: vec![Series {
            label: "nan".into(),
            t: vec![0.0, 1.0],
            y: vec![f64::NAN; 2],
        }],
        ..Panel::default()
    };
    assert!(matches!(
        render_to_buffer(&[all_nan], &o),
        Err(PlotError::Empty(_))
    ));

    let missing_dir = std::env::temp_dir()
        .join("multibody-no-such-dir-8d3f")
        .join("x.png");
    assert!(matches!(
        plot_panels(&demo_panels(), &missing_dir, &o),
        Err(PlotError::Io(_))
    ));
    let wrong_ext = std::env::temp_dir().join("x.jpg");
    assert!(matches!(
        plot_panels(&demo_panels(), &wrong_ext, &o),
        Err(PlotError::Io(_))
    ));
    let zero = PlotOptions {
        width: 0,
        ..PlotOptions::default()
    };
    assert!(matches!(
        render_to_buffer(&demo_panels(), &zero),
        Err(PlotError::Backend(_))
    ));
}

#[test]
fn tick_format() {
    assert_eq!(format_tick(0.5, 2.2), "0.5");
    assert_eq!(format_tick(-1.0, 2.2), "-1");
    assert_eq!(format_tick(0.30000000000000004, 2.2), "0.3");
    assert_eq!(format_tick(1e-17, 2.2), "0");
    assert_eq!(format_tick(2.5e7, 1e7), "2.5e7");
    assert_eq!(format_tick(1.5e-5, 1e-5), "1.5e-5");
    assert_eq!(format_tick(9.81, 1.962), "9.81");
}

#[test]
fn constant_and_zero_ranges() {
    assert_eq!(padded_range((0.0, 0.0), 0.05), (-1.0, 1.0));
    let (a, b) = padded_range((10.0, 10.0), 0.05);
    assert!((a - 9.0).abs() < 1e-12 && (b - 11.0).abs() < 1e-12);
    let (a, b) = padded_range((0.0, 10.0), 0.05);
    assert!((a + 0.5).abs() < 1e-12 && (b - 10.5).abs() < 1e-12);
}

#[test]
fn glyph_metrics_place_narrow_glyphs() {
    let m = font::sans_metrics().expect("DejaVu Sans metrics");
    let (glyphs, width) = m.layout("10.5", 15.0);
    let offsets: Vec<i32> = glyphs.iter().map(|g| g.1).collect();
    assert_eq!(glyphs.iter().map(|g| g.0).collect::<String>(), "10.5");
    // '1' has a wide left bearing; every glyph starts right of the previous one.
    assert!(offsets[0] >= 1, "{offsets:?}");
    assert!(offsets.windows(2).all(|w| w[1] > w[0]), "{offsets:?}");
    assert!((25..40).contains(&width), "width {width}");
    assert_eq!(m.layout("a b", 15.0).0.len(), 2);
    let cap = m.cap_height(15.0);
    assert!((8.0..11.0).contains(&cap), "cap height {cap}");
}

#[test]
fn single_panel_uses_full_width() {
    let mut panels = demo_panels();
    panels.truncate(1);
    let options = PlotOptions {
        width: 640,
        height: 360,
        ..PlotOptions::default()
    };
    assert_eq!(figure_size(1, &options), (640, 360));
    let buf = render_to_buffer(&panels, &options).unwrap();
    assert_eq!(buf.len(), 640 * 360 * 3);
}

#[test]
fn register_fonts_is_idempotent_across_threads() {
    // Text needs the registered fonts (plotters has no system fonts here): threads
    // that register them concurrently, and then again, all draw the same figure,
    // with its legend text, as a single thread does.
    let options = PlotOptions {
        width: 400,
        height: 200,
        ..PlotOptions::default()
    };
    let draw = move || {
        register_fonts();
        register_fonts();
        render_to_buffer(&demo_panels()[..1], &options).expect("fonts available")
    };
    let handles: Vec<_> = (0..4).map(|_| std::thread::spawn(draw.clone())).collect();
    let buffers: Vec<Vec<u8>> = handles.into_iter().map(|h| h.join().unwrap()).collect();
    let reference = draw();
    for b in &buffers {
        assert!(b == &reference, "a thread drew a different figure");
    }
    // Text is the only black in the figure (axes and ticks are drawn at 80 %
    // black, (51, 51, 51); grid lines and the legend frame lighter): the legend
    // labels, tick labels and the axis description give about 240 pixels below 20.
    let black = reference
        .chunks(3)
        .filter(|p| p[0] < 20 && p[1] < 20 && p[2] < 20)
        .count();
    assert!(black > 100, "only {black} black pixels: text missing");
}

/// A panel of one curve over `t` in 0..10 with values `y(t)`, labelled `y`.
fn panel_of(y: impl Fn(f64) -> f64) -> Panel {
    let t: Vec<f64> = (0..=400).map(|i| f64::from(i) * 0.025).collect();
    Panel {
        series: vec![Series {
            label: "a long legend label".into(),
            y: t.iter().map(|&t| y(t)).collect(),
            t,
        }],
        ..Panel::default()
    }
}

/// The legend placement of `panel` in a 600 x 400 plotting area: the corner and the
/// frame (with its final y range).
fn placement(panel: &Panel) -> (Corner, Frame, Legend<'_>) {
    let metrics = font::sans_metrics().unwrap();
    let legend = Legend::new(panel, 2, metrics, Scale(1));
    let y = padded_range(finite_bounds(panel.series[0].y.iter()).unwrap(), 0.05);
    let mut frame = Frame {
        width: 600,
        height: 400,
        x: padded_range((0.0, 10.0), 0.01),
        y,
    };
    let top = finite_bounds(panel.series[0].y.iter()).unwrap().1;
    let corner = place_legend(panel, &legend, &mut frame, top, Scale(1));
    (corner, frame, legend)
}

#[test]
fn the_legend_takes_a_corner_that_no_curve_crosses() {
    // A rising line leaves the top left and bottom right free: top right is taken by
    // the line, so the legend goes to the top left.
    let rising = panel_of(|t| t);
    let (corner, frame, legend) = placement(&rising);
    assert_eq!(corner, Corner::TopLeft);
    let bx = frame.legend_box(corner, &legend, 10);
    assert_eq!(frame.covered(&rising, bx), 0);
    // A falling line: top right is free.
    let falling = panel_of(|t| -t);
    assert_eq!(placement(&falling).0, Corner::TopRight);
}

#[test]
fn a_legend_that_every_corner_would_cover_raises_the_range_above_the_curves() {
    // Oscillating through the whole range: every corner is crossed.
    let wave = panel_of(|t| (3.0 * t).sin());
    let before = padded_range((-1.0, 1.0), 0.05);
    let (corner, frame, legend) = placement(&wave);
    assert_eq!(corner, Corner::TopRight);
    assert!(frame.y.1 > before.1, "{:?}", frame.y);
    // The curves' top now lies below the legend's box.
    let bx = frame.legend_box(corner, &legend, 10);
    let (_, top_px) = frame.pixel((0.0, 1.0));
    assert!(
        top_px > bx[3],
        "curve top at {top_px}, legend bottom at {}",
        bx[3]
    );
    assert_eq!(frame.covered(&wave, bx), 0);
}
