//! The procedural page texture and the plain colours of the other surfaces (linear RGB
//! albedos in $[0, 1]$).
//!
//! A page is white paper with a text block inside margins: grey bars for lines of text,
//! broken into words, grouped into paragraphs (indented first line, short last line). The
//! front (recto) opens with a heading; the back (verso) with a figure and its caption, so
//! the two sides are told apart at a glance. Coordinates are each side's own texture
//! coordinates $(u, v) \in [0, 1]^2$ as [`folio_geometry::mesh::page_mesh`] lays them out:
//! $u$ runs left to right as the side is read (the binding is at $u = 0$ on the front and
//! at $u = 1$ on the back), $v$ runs along the binding from the head ($z = 0$).

use folio_geometry::mesh::Surface;

/// Paper.
pub const PAPER: [f32; 3] = [0.93, 0.91, 0.86];
/// Printing ink.
pub const INK: [f32; 3] = [0.22, 0.22, 0.25];
/// The figure on the back.
const FIGURE: [f32; 3] = [0.42, 0.54, 0.66];
/// The stacked page edges of a block (fore-edge, ends) and the rim of the active page.
pub const PAGE_EDGES: [f32; 3] = [0.84, 0.82, 0.76];
/// Cover cloth.
pub const COVER: [f32; 3] = [0.40, 0.10, 0.08];
/// The table the book lies on.
pub const TABLE: [f32; 3] = [0.46, 0.38, 0.30];

/// Lines of text in the text block.
const LINES: u32 = 34;
/// Lines per paragraph.
const PARAGRAPH: u32 = 7;

/// A side of a page.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The recto (binding on the left as read).
    Front,
    /// The verso (binding on the right as read).
    Back,
}

/// A deterministic hash of two integers to $[0, 1)$ (an integer mixer: multiply by odd
/// constants, xor-shift).
#[inline]
fn hash(a: u32, b: u32) -> f32 {
    let mut x = a.wrapping_mul(0x9E37_79B1) ^ b.wrapping_mul(0x85EB_CA77).rotate_left(13);
    x ^= x >> 16;
    x = x.wrapping_mul(0x7FEB_352D);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846C_A68B);
    x ^= x >> 16;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

/// Whether the position `x` $\in [0, 1]$ along line `line` (`length` long, as a fraction
/// of the text width, starting at `indent`) falls on a word: words of 3-11 % of the width
/// separated by 1.6 % gaps.
fn on_word(line: u32, x: f32, indent: f32, length: f32) -> bool {
    if x < indent || x > length {
        return false;
    }
    let mut start = indent;
    for word in 0..64 {
        let end = start + 0.03 + 0.08 * hash(line, word);
        if x < end {
            return true;
        }
        start = end + 0.016;
        if x < start {
            return false;
        }
    }
    false
}

/// Albedo of `side` at its texture coordinates `uv` (module docs).
#[must_use]
pub fn page_albedo(side: Side, uv: [f32; 2]) -> [f32; 3] {
    let [u, v] = uv;
    // Margins: inner 0.11, outer 0.14, head 0.08, foot 0.10 of the page.
    let (left, right) = match side {
        Side::Front => (0.11, 0.86),
        Side::Back => (0.14, 0.89),
    };
    let (top, bottom) = (0.08, 0.90);
    let x = (u - left) / (right - left);
    let pitch = (bottom - top) / LINES as f32;
    let row = (v - top) / pitch;
    // Page number, at the outer corner of the foot margin.
    let number_x = match side {
        Side::Front => (0.93..=0.99).contains(&x),
        Side::Back => (0.01..=0.07).contains(&x),
    };
    if number_x && (LINES as f32 + 1.2..=LINES as f32 + 1.7).contains(&row) {
        return INK;
    }
    if !(0.0..=1.0).contains(&x) || !(0.0..LINES as f32).contains(&row) {
        return PAPER;
    }
    let line = row as u32;
    let within = row - line as f32;
    let bar = (0.36..=0.70).contains(&within);
    let first_text = match side {
        Side::Front => {
            // Heading: a wide bar over line 0, then an empty line.
            if line == 0 {
                return if (0.05..=0.95).contains(&within) && x <= 0.55 {
                    INK
                } else {
                    PAPER
                };
            }
            2
        }
        Side::Back => {
            // Figure over lines 0-10, caption on line 11, then an empty line.
            if line <= 10 {
                let in_figure = (0.2..=10.8).contains(&row) && (0.02..=0.98).contains(&x);
                return if in_figure {
                    // A simple horizon: darker below a wavy line.
                    let horizon = 6.0 + 1.5 * (x * 9.0).sin() * (1.0 - x);
                    let shade = if row > horizon { 0.75 } else { 1.0 };
                    FIGURE.map(|c| c * shade)
                } else {
                    PAPER
                };
            }
            if line == 11 {
                return if bar && (0.2..=0.8).contains(&x) {
                    INK
                } else {
                    PAPER
                };
            }
            13
        }
    };
    if line < first_text || !bar {
        return PAPER;
    }
    let k = line - first_text;
    let (indent, length) = match k % PARAGRAPH {
        0 => (0.05, 1.0),
        p if p == PARAGRAPH - 1 => (0.0, 0.25 + 0.5 * hash(line, 999)),
        _ => (0.0, 1.0),
    };
    if on_word(
        line + 100 * u32::from(side == Side::Back),
        x,
        indent,
        length,
    ) {
        INK
    } else {
        PAPER
    }
}

/// Albedo of the non-page `surface` at texture coordinates `uv` and world X `x`: a block's
/// top is the outermost page of the block, the back of a page on the left block ($x < 0$,
/// its $u$ mirrored to the back's $1 - u$) and the front on the right block; page edges,
/// block bottoms and the cover are plain colours. Page surfaces get the front or back
/// texture ([`page_albedo`]).
#[must_use]
pub fn surface_albedo(surface: Surface, uv: [f32; 2], x: f32) -> [f32; 3] {
    match surface {
        Surface::BlockTop if x < 0.0 => page_albedo(Side::Back, [1.0 - uv[0], uv[1]]),
        Surface::BlockTop | Surface::PageFront => page_albedo(Side::Front, uv),
        Surface::PageBack => page_albedo(Side::Back, uv),
        Surface::PageEdge | Surface::BlockEdge | Surface::BlockBottom => PAGE_EDGES,
        Surface::Cover => COVER,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean albedo over a grid of samples of the region `[u0, u1] x [v0, v1]`.
    fn mean(side: Side, u: [f32; 2], v: [f32; 2]) -> f32 {
        let n = 200;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let uv = [
                    u[0] + (u[1] - u[0]) * (i as f32 + 0.5) / n as f32,
                    v[0] + (v[1] - v[0]) * (j as f32 + 0.5) / n as f32,
                ];
                sum += page_albedo(side, uv).iter().sum::<f32>() / 3.0;
            }
        }
        sum / (n * n) as f32
    }

    #[test]
    fn margins_are_paper_text_is_darker_and_sides_differ() {
        for side in [Side::Front, Side::Back] {
            let margin = mean(side, [0.0, 0.05], [0.0, 1.0]);
            assert!((margin - 0.9).abs() < 0.01, "{side:?} margin {margin}");
            let text = mean(side, [0.2, 0.8], [0.6, 0.85]);
            assert!(text < margin - 0.15, "{side:?} text {text}");
        }
        // The figure makes the back's upper half much darker than the front's.
        let front = mean(Side::Front, [0.2, 0.8], [0.1, 0.35]);
        let back = mean(Side::Back, [0.2, 0.8], [0.1, 0.35]);
        assert!(back < front - 0.1, "front {front} back {back}");
    }

    #[test]
    fn albedos_stay_in_unit_range_even_outside_the_page() {
        for &u in &[-1.0, 0.0, 0.3, 1.0, 2.0, f32::NAN] {
            for &v in &[-1.0, 0.0, 0.5, 1.0, 2.0, f32::NAN] {
                for side in [Side::Front, Side::Back] {
                    let a = page_albedo(side, [u, v]);
                    assert!(a.iter().all(|c| (0.0..=1.0).contains(c)));
                }
            }
        }
    }
}
