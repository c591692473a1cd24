//! `atlas.svg`: each variant's mean RMS error against its mean frame time, both axes
//! logarithmic, one marker shape per page model, every marker labelled, and the Pareto
//! front (the good variants nothing beats in both) drawn as a staircase. Variants that
//! could not run, or whose error is not finite, are listed under the plot instead.

use core::fmt::Write as _;

use super::Atlas;
use crate::timeline::log_axis;

const WIDTH: f64 = 960.0;
const HEIGHT: f64 = 640.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = WIDTH - 180.0;
const TOP: f64 = 50.0;
const BOTTOM: f64 = HEIGHT - 90.0;

/// The marker of a page model at `(x, y)`: a circle (dog), a triangle (cone), a square
/// (mass-spring), a diamond (xpbd).
fn marker(model: &str, x: f64, y: f64, pareto: bool) -> String {
    let fill = if pareto { "#b8431f" } else { "#1f5fa8" };
    let r = 6.0;
    match model {
        "cone" => format!(
            "<polygon points=\"{x:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{fill}\"/>",
            y - r,
            x - r,
            y + r,
            x + r,
            y + r
        ),
        "mass-spring" => format!(
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"{fill}\"/>",
            x - r,
            y - r,
            2.0 * r,
            2.0 * r
        ),
        "xpbd" => format!(
            "<polygon points=\"{x:.1},{:.1} {:.1},{y:.1} {x:.1},{:.1} {:.1},{y:.1}\" fill=\"{fill}\"/>",
            y - r,
            x + r,
            y + r,
            x - r
        ),
        _ => format!("<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"{r}\" fill=\"{fill}\"/>"),
    }
}

/// An axis-aligned box on the plot (pixels).
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    /// The square of half-side `r` around `(x, y)`.
    fn around(x: f64, y: f64, r: f64) -> Self {
        Self {
            x0: x - r,
            y0: y - r,
            x1: x + r,
            y1: y + r,
        }
    }

    fn overlaps(&self, o: &Self) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
}

/// The width of a 10 px label (pixels): about 0.56 em a character.
fn label_width(label: &str) -> f64 {
    5.6 * label.chars().count() as f64
}

/// Where the label of width `width` of the marker at `(x, y)` goes: the first of a few
/// places around the marker (right above, right below, left above, left below, then further
/// up and down) whose box meets no other label and no marker, else the first place. Returns
/// the text's anchor point and `text-anchor`, and adds its box to `placed`.
fn place_label(
    x: f64,
    y: f64,
    width: f64,
    markers: &[Rect],
    placed: &mut Vec<Rect>,
) -> (f64, f64, &'static str) {
    const LABEL_HEIGHT: f64 = 10.0;
    let candidates = [
        (8.0, -6.0),
        (8.0, 14.0),
        (-8.0, -6.0),
        (-8.0, 14.0),
        (8.0, -18.0),
        (8.0, 26.0),
        (-8.0, -18.0),
        (-8.0, 26.0),
    ];
    let boxed = |(dx, dy): (f64, f64)| {
        let (x0, x1) = if dx > 0.0 {
            (x + dx, x + dx + width)
        } else {
            (x + dx - width, x + dx)
        };
        Rect {
            x0,
            y0: y + dy - LABEL_HEIGHT,
            x1,
            y1: y + dy + 2.0,
        }
    };
    let free = |b: &Rect| !placed.iter().chain(markers).any(|o| b.overlaps(o));
    let (dx, dy) = candidates
        .iter()
        .copied()
        .find(|&c| free(&boxed(c)))
        .unwrap_or(candidates[0]);
    placed.push(boxed((dx, dy)));
    (x + dx, y + dy, if dx > 0.0 { "start" } else { "end" })
}

/// Escapes `s` for SVG text.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The atlas plot (module docs).
#[must_use]
pub fn svg(atlas: &Atlas) -> String {
    let points: Vec<(usize, f64, f64)> = atlas
        .variants
        .iter()
        .enumerate()
        .filter_map(|(i, r)| {
            let (c, e) = (r.costs?, r.errors?);
            (c.frame_ms_mean > 0.0 && e.rms_mean > 0.0 && e.rms_mean.is_finite()).then_some((
                i,
                c.frame_ms_mean,
                100.0 * e.rms_mean,
            ))
        })
        .collect();
    let xs: Vec<f64> = points.iter().map(|p| p.1).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.2).collect();
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"sans-serif\" font-size=\"12\">\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\
         <text x=\"{LEFT}\" y=\"28\" font-size=\"16\">Accuracy atlas of {}: mean RMS error (% of page width) against mean frame time (ms)</text>",
        escape(&atlas.scene)
    );
    let (Some(x_axis), Some(y_axis)) = (log_axis((RIGHT, LEFT), &xs), log_axis((TOP, BOTTOM), &ys))
    else {
        s.push_str("<text x=\"100\" y=\"300\">no variant with a finite, positive error and time</text></svg>");
        return s;
    };
    let _ = write!(
        s,
        "<rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>",
        RIGHT - LEFT,
        BOTTOM - TOP
    );
    for (v, label) in x_axis.ticks() {
        if let Some(x) = x_axis.y(v) {
            let _ = write!(
                s,
                "<line x1=\"{x:.1}\" y1=\"{TOP}\" x2=\"{x:.1}\" y2=\"{BOTTOM}\" stroke=\"#ddd\"/>\
                 <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{label}</text>",
                BOTTOM + 18.0
            );
        }
    }
    for (v, label) in y_axis.ticks() {
        if let Some(y) = y_axis.y(v) {
            let _ = write!(
                s,
                "<line x1=\"{LEFT}\" y1=\"{y:.1}\" x2=\"{RIGHT}\" y2=\"{y:.1}\" stroke=\"#ddd\"/>\
                 <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{label}</text>",
                LEFT - 6.0,
                y + 4.0
            );
        }
    }
    let _ = write!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">mean frame time (ms, log)</text>\
         <text x=\"18\" y=\"{:.1}\" transform=\"rotate(-90 18 {:.1})\" text-anchor=\"middle\">mean RMS error (% of page width, log)</text>",
        0.5 * (LEFT + RIGHT),
        BOTTOM + 40.0,
        0.5 * (TOP + BOTTOM),
        0.5 * (TOP + BOTTOM)
    );
    // The Pareto front, as a staircase from the cheapest to the most accurate.
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| atlas.variants[p.0].pareto)
        .filter_map(|p| Some((x_axis.y(p.1)?, y_axis.y(p.2)?)))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    if front.len() > 1 {
        let mut path = format!("M{:.1},{:.1}", front[0].0, front[0].1);
        for w in front.windows(2) {
            let _ = write!(path, " H{:.1} V{:.1}", w[1].0, w[1].1);
        }
        let _ = write!(
            s,
            "<path d=\"{path}\" fill=\"none\" stroke=\"#b8431f\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>"
        );
    }
    let drawn: Vec<(usize, f64, f64)> = points
        .iter()
        .filter_map(|&(i, t, e)| Some((i, x_axis.y(t)?, y_axis.y(e)?)))
        .collect();
    let markers: Vec<Rect> = drawn
        .iter()
        .map(|&(_, x, y)| Rect::around(x, y, 6.0))
        .collect();
    let mut labels: Vec<Rect> = Vec::new();
    for &(i, x, y) in &drawn {
        let row = &atlas.variants[i];
        s.push_str(&marker(&row.model, x, y, row.pareto));
        let (lx, ly, anchor) = place_label(x, y, label_width(&row.label), &markers, &mut labels);
        let _ = write!(
            s,
            "<text x=\"{lx:.1}\" y=\"{ly:.1}\" font-size=\"10\" text-anchor=\"{anchor}\">{}</text>",
            escape(&row.label)
        );
    }
    // The legend.
    for (k, model) in ["dog", "cone", "mass-spring", "xpbd"].iter().enumerate() {
        let y = TOP + 20.0 + 22.0 * k as f64;
        s.push_str(&marker(model, RIGHT + 24.0, y, false));
        let _ = write!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\">{model}</text>",
            RIGHT + 38.0,
            y + 4.0
        );
    }
    let y = TOP + 20.0 + 22.0 * 4.0;
    s.push_str(&marker("dog", RIGHT + 24.0, y, true));
    let _ = write!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\">Pareto front</text>",
        RIGHT + 38.0,
        y + 4.0
    );
    let missing: Vec<&str> = atlas
        .variants
        .iter()
        .enumerate()
        .filter(|(i, _)| !points.iter().any(|p| p.0 == *i))
        .map(|(_, r)| r.label.as_str())
        .collect();
    if !missing.is_empty() {
        let _ = write!(
            s,
            "<text x=\"{LEFT}\" y=\"{:.1}\">not drawn (refused, or no finite error): {}</text>",
            HEIGHT - 20.0,
            escape(&missing.join("; "))
        );
    }
    s.push_str("</svg>");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Markers in a cluster get labels that overlap neither each other nor a marker.
    #[test]
    fn labels_of_a_cluster_do_not_overlap() {
        let points = [
            (300.0, 200.0),
            (304.0, 202.0),
            (296.0, 206.0),
            (302.0, 194.0),
        ];
        let markers: Vec<Rect> = points
            .iter()
            .map(|&(x, y)| Rect::around(x, y, 6.0))
            .collect();
        let mut placed = Vec::new();
        for &(x, y) in &points {
            place_label(
                x,
                y,
                label_width("dog newton 2, hessian"),
                &markers,
                &mut placed,
            );
        }
        for (i, a) in placed.iter().enumerate() {
            for b in &placed[i + 1..] {
                assert!(!a.overlaps(b), "{a:?} {b:?}");
            }
            assert!(!markers.iter().any(|m| a.overlaps(m)), "{a:?}");
        }
    }
}
