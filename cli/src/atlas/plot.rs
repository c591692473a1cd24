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
    for &(i, t, e) in &points {
        let row = &atlas.variants[i];
        let (Some(x), Some(y)) = (x_axis.y(t), y_axis.y(e)) else {
            continue;
        };
        s.push_str(&marker(&row.model, x, y, row.pareto));
        let _ = write!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"10\">{}</text>",
            x + 8.0,
            y - 6.0,
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
