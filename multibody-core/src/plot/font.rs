//! Embedded fonts for plotters' `ab_glyph` text renderer.
//!
//! plotters is built without its `ttf` feature, so it never looks at system
//! fonts: every font family a drawing asks for must be registered from bytes
//! first, or text drawing fails with `FontUnavailable`. The DejaVu fonts come
//! from the `dejavu` crate, so text renders on machines with no fonts installed.

use std::sync::Once;

use plotters::style::{FontStyle, register_font};

static REGISTER: Once = Once::new();

/// Registers the embedded DejaVu fonts with plotters.
///
/// After this call the generic families plotters uses — `"sans-serif"`
/// (used by all of plotters' default label, caption and legend styles),
/// `"serif"` and `"monospace"` — plus the names `"DejaVu Sans"`,
/// `"DejaVu Serif"` and `"DejaVu Sans Mono"` are available in every
/// [`FontStyle`] (`Italic` uses the oblique face for the sans fonts).
///
/// Idempotent and thread-safe (guarded by a [`std::sync::Once`]); cheap to call
/// before every drawing. [`super::plot_panels`] calls it itself.
pub fn register_fonts() {
    REGISTER.call_once(|| {
        type Faces = [(FontStyle, &'static [u8]); 4];
        let sans: Faces = [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Oblique, dejavu::sans::oblique()),
            (FontStyle::Italic, dejavu::sans::oblique()),
        ];
        let serif: Faces = [
            (FontStyle::Normal, dejavu::serif::regular()),
            (FontStyle::Bold, dejavu::serif::bold()),
            (FontStyle::Oblique, dejavu::serif::italic()),
            (FontStyle::Italic, dejavu::serif::italic()),
        ];
        let mono: Faces = [
            (FontStyle::Normal, dejavu::sans_mono::regular()),
            (FontStyle::Bold, dejavu::sans_mono::bold()),
            (FontStyle::Oblique, dejavu::sans_mono::oblique()),
            (FontStyle::Italic, dejavu::sans_mono::oblique()),
        ];
        let families: [(&[&str], &Faces); 3] = [
            (&["sans-serif", "DejaVu Sans"], &sans),
            (&["serif", "DejaVu Serif"], &serif),
            (&["monospace", "DejaVu Sans Mono"], &mono),
        ];
        for (names, faces) in families {
            for name in names {
                for &(style, bytes) in faces.iter() {
                    if register_font(name, style, bytes).is_err() {
                        log::error!("plot: could not register font {name} ({})", style.as_str());
                    }
                }
            }
        }
    });
}

/// Horizontal layout of DejaVu Sans, read from the font's own tables.
///
/// plotters' `ab_glyph` renderer draws every glyph at its advance position but
/// ignores the glyph's left side bearing, so narrow glyphs (`1`, `.`, `i`)
/// end up squeezed against their left neighbour ("9. 81"). The plot module
/// therefore places each character itself, using these metrics, and lets
/// plotters draw single characters only.
pub(crate) struct SansMetrics {
    data: &'static [u8],
    /// Offset of the format-4 `cmap` subtable.
    cmap4: usize,
    /// Offset of the `hmtx` table.
    hmtx: usize,
    n_hmetrics: usize,
    /// Font units per pixel of plotters' font size: ab_glyph scales fonts so
    /// that `ascender - descender` spans the requested size.
    height_units: f64,
    /// Height of capital letters in font units.
    cap_units: f64,
}

fn be_u16(d: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes([*d.get(at)?, *d.get(at + 1)?]))
}

fn be_i16(d: &[u8], at: usize) -> Option<i16> {
    be_u16(d, at).map(|v| v as i16)
}

fn be_u32(d: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes([
        *d.get(at)?,
        *d.get(at + 1)?,
        *d.get(at + 2)?,
        *d.get(at + 3)?,
    ]))
}

fn find_table(d: &[u8], tag: &[u8; 4]) -> Option<usize> {
    let n = usize::from(be_u16(d, 4)?);
    (0..n).find_map(|i| {
        let rec = 12 + 16 * i;
        (d.get(rec..rec + 4)? == tag).then(|| be_u32(d, rec + 8).map(|o| o as usize))?
    })
}

impl SansMetrics {
    fn parse(data: &'static [u8]) -> Option<Self> {
        let hhea = find_table(data, b"hhea")?;
        let hmtx = find_table(data, b"hmtx")?;
        let cmap = find_table(data, b"cmap")?;
        let mut ascender = f64::from(be_i16(data, hhea + 4)?);
        let mut descender = f64::from(be_i16(data, hhea + 6)?);
        let n_hmetrics = usize::from(be_u16(data, hhea + 34)?);
        let mut cap_units = None;
        if let Some(os2) = find_table(data, b"OS/2") {
            let version = be_u16(data, os2)?;
            // USE_TYPO_METRICS: ab_glyph (ttf-parser) then uses the typo values.
            if be_u16(data, os2 + 62)? & (1 << 7) != 0 {
                ascender = f64::from(be_i16(data, os2 + 68)?);
                descender = f64::from(be_i16(data, os2 + 70)?);
            }
            if version >= 2 {
                cap_units = be_i16(data, os2 + 88).map(f64::from);
            }
        }
        let n_sub = usize::from(be_u16(data, cmap + 2)?);
        let cmap4 = (0..n_sub).find_map(|i| {
            let rec = cmap + 4 + 8 * i;
            let (platform, encoding) = (be_u16(data, rec)?, be_u16(data, rec + 2)?);
            let sub = cmap + be_u32(data, rec + 4)? as usize;
            let unicode = platform == 0 || (platform == 3 && encoding == 1);
            (unicode && be_u16(data, sub)? == 4).then_some(sub)
        })?;
        let height_units = ascender - descender;
        (height_units > 0.0).then_some(Self {
            data,
            cmap4,
            hmtx,
            n_hmetrics,
            height_units,
            cap_units: cap_units.unwrap_or(0.73 * height_units / 1.17),
        })
    }

    fn glyph_id(&self, c: char) -> usize {
        let (d, sub) = (self.data, self.cmap4);
        let Ok(c) = u16::try_from(u32::from(c)) else {
            return 0;
        };
        let lookup = || -> Option<usize> {
            let seg_x2 = usize::from(be_u16(d, sub + 6)?);
            let ends = sub + 14;
            let starts = ends + seg_x2 + 2;
            let deltas = starts + seg_x2;
            let range_offsets = deltas + seg_x2;
            for seg in (0..seg_x2).step_by(2) {
                if be_u16(d, ends + seg)? < c {
                    continue;
                }
                let start = be_u16(d, starts + seg)?;
                if start > c {
                    return Some(0);
                }
                let delta = be_u16(d, deltas + seg)?;
                let range_offset = usize::from(be_u16(d, range_offsets + seg)?);
                if range_offset == 0 {
                    return Some(usize::from(c.wrapping_add(delta)));
                }
                let at = range_offsets + seg + range_offset + 2 * usize::from(c - start);
                let g = be_u16(d, at)?;
                return Some(if g == 0 {
                    0
                } else {
                    usize::from(g.wrapping_add(delta))
                });
            }
            Some(0)
        };
        lookup().unwrap_or(0)
    }

    /// Advance width and left side bearing of `c`, in font units.
    fn h_metrics(&self, c: char) -> (f64, f64) {
        let (d, g, n) = (self.data, self.glyph_id(c), self.n_hmetrics.max(1));
        let advance = be_u16(d, self.hmtx + 4 * g.min(n - 1)).unwrap_or(0);
        let lsb = if g < n {
            be_i16(d, self.hmtx + 4 * g + 2)
        } else {
            be_i16(d, self.hmtx + 4 * n + 2 * (g - n))
        };
        (f64::from(advance), f64::from(lsb.unwrap_or(0)))
    }

    /// Where plotters must be asked to draw each character of `text` (as a
    /// one-character string) so that the glyphs land at their proper
    /// positions: pixel offsets along the baseline from the text's start,
    /// and the total advance width, for plotters font size `size`.
    pub(crate) fn layout(&self, text: &str, size: f64) -> (Vec<(char, i32)>, i32) {
        let scale = size / self.height_units;
        let mut pen: f64 = 0.0;
        let mut out = Vec::with_capacity(text.len());
        for c in text.chars() {
            let (advance, lsb) = self.h_metrics(c);
            if !c.is_whitespace() {
                out.push((c, (pen.round() + (lsb * scale).floor()) as i32));
            }
            pen += advance * scale;
        }
        (out, pen.round() as i32)
    }

    /// Width of `text` in pixels at plotters font size `size`.
    pub(crate) fn width(&self, text: &str, size: f64) -> i32 {
        self.layout(text, size).1
    }

    /// Height of capital letters in pixels at plotters font size `size`.
    pub(crate) fn cap_height(&self, size: f64) -> f64 {
        self.cap_units * size / self.height_units
    }
}

/// Metrics of DejaVu Sans (regular), the face registered for `"sans-serif"`.
pub(crate) fn sans_metrics() -> Option<&'static SansMetrics> {
    static METRICS: std::sync::OnceLock<Option<SansMetrics>> = std::sync::OnceLock::new();
    METRICS
        .get_or_init(|| SansMetrics::parse(dejavu::sans::regular()))
        .as_ref()
}
