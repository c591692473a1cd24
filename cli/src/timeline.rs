//! The run's timeline (`timeline.svg`): step time and page stretch over the frames, as a
//! self-contained SVG of two stacked panels sharing the frame axis.
//!
//! - Top: wall time of each frame's steps in milliseconds (its compute time; a frame is
//!   1/60 s of model time and may take several steps) on a logarithmic axis (times span
//!   decades: a book at rest steps its blocks only, a held page adds the page's unknowns
//!   and collision rounds), decade ticks.
//! - Bottom: the largest relative edge stretch $\max \lvert \ell/\ell_0 - 1\rvert$ of the
//!   active page in percent on a linear axis from 0 (seed `000_…` Sec. 5 reports 11 % on
//!   average over a page turn); frames without an active page leave a gap.
//!
//! Values that cannot be drawn (NaN, infinite, `None`, and step times $\le 0$ on the log
//! axis) are skipped and break the line. Without frames each panel carries a "no frames"
//! note.

use core::fmt::Write as _;

/// Image width (SVG user units = pixels).
const WIDTH: f64 = 900.0;
/// Image height.
const HEIGHT: f64 = 540.0;
/// Left edge of the plot area (room for tick labels).
const LEFT: f64 = 72.0;
/// Right edge of the plot area.
const RIGHT: f64 = WIDTH - 24.0;
/// Top and bottom of the two plot areas.
const PANELS: [(f64, f64); 2] = [(46.0, 230.0), (302.0, 486.0)];
/// Line colours of the two panels.
const COLOURS: [&str; 2] = ["#1f5fa8", "#b8431f"];

/// A "nice" step (1, 2 or 5 times a power of ten) near `span / target`, for about
/// `target` ticks over `span`; 1 for an empty or non-finite span.
fn nice_step(span: f64, target: f64) -> f64 {
    let raw = span / target;
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let magnitude = 10f64.powf(raw.log10().floor());
    let fraction = raw / magnitude;
    let nice = if fraction < 1.5 {
        1.0
    } else if fraction < 3.5 {
        2.0
    } else if fraction < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * magnitude
}

/// A tick label: up to 3 decimals, trailing zeros removed.
pub(crate) fn label(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// One panel's vertical axis: maps a value to its y coordinate, lists its ticks. A
/// horizontal axis is the same with `panel` = (right, left): `y` then gives the x.
pub(crate) struct Axis {
    /// The panel's top and bottom (y).
    panel: (f64, f64),
    /// Value range shown (in axis units: log10 of the value on a log axis).
    range: (f64, f64),
    log: bool,
}

impl Axis {
    /// The y of `value`, or `None` if it cannot be drawn on this axis.
    pub(crate) fn y(&self, value: f64) -> Option<f64> {
        let v = if self.log {
            if value.is_nan() || value <= 0.0 {
                return None;
            }
            value.log10()
        } else {
            value
        };
        if !v.is_finite() {
            return None;
        }
        let (lo, hi) = self.range;
        let t = ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
        Some(self.panel.1 - t * (self.panel.1 - self.panel.0))
    }

    /// Tick values (in data units) with their labels.
    pub(crate) fn ticks(&self) -> Vec<(f64, String)> {
        let (lo, hi) = self.range;
        if self.log {
            let (a, b) = (lo.round() as i32, hi.round() as i32);
            (a..=b)
                .map(|k| {
                    let v = 10f64.powi(k);
                    (v, label(v))
                })
                .collect()
        } else {
            let step = nice_step(hi - lo, 4.0);
            let count = ((hi - lo) / step).floor() as usize;
            (0..=count.min(50))
                .map(|k| {
                    let v = lo + step * k as f64;
                    (v, label(v))
                })
                .collect()
        }
    }
}

/// The log axis over the positive finite `values`: whole decades around them (at least one).
pub(crate) fn log_axis(panel: (f64, f64), values: &[f64]) -> Option<Axis> {
    let logs = values
        .iter()
        .filter(|&&v| v > 0.0 && v.is_finite())
        .map(|v| v.log10());
    let (lo, hi) = logs.fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    if lo > hi {
        return None;
    }
    let (lo, mut hi) = (lo.floor(), hi.ceil());
    if hi <= lo {
        hi = lo + 1.0;
    }
    Some(Axis {
        panel,
        range: (lo, hi),
        log: true,
    })
}

/// The linear axis from 0 to a nice ceiling over the finite `values`.
fn linear_axis(panel: (f64, f64), values: &[f64]) -> Option<Axis> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        return None;
    }
    let max = finite.iter().copied().fold(0.0, f64::max);
    let step = nice_step(max, 4.0);
    let top = ((max / step).ceil() * step).max(step);
    Some(Axis {
        panel,
        range: (0.0, top),
        log: false,
    })
}

/// The x of frame `i` of `n`.
fn frame_x(i: usize, n: usize) -> f64 {
    let span = n.saturating_sub(1).max(1) as f64;
    LEFT + (RIGHT - LEFT) * i as f64 / span
}

/// Appends one panel: frame, title, axes, ticks and the data line (broken at values the
/// axis cannot draw).
fn panel(svg: &mut String, index: usize, title: &str, values: &[f64], log: bool, frames: usize) {
    let (top, bottom) = PANELS[index];
    let _ = writeln!(
        svg,
        r##"<text x="{LEFT}" y="{}" font-size="15" font-weight="bold">{title}</text>"##,
        top - 12.0
    );
    let _ = writeln!(
        svg,
        r##"<rect x="{LEFT}" y="{top}" width="{}" height="{}" fill="#fbfbf8" stroke="#888"/>"##,
        RIGHT - LEFT,
        bottom - top
    );
    let middle = 0.5 * (top + bottom);
    let centre = 0.5 * (LEFT + RIGHT);
    if frames == 0 {
        let _ = writeln!(
            svg,
            r##"<text x="{centre}" y="{middle}" text-anchor="middle" fill="#666">no frames</text>"##
        );
        return;
    }
    let axis = if log {
        log_axis((top, bottom), values)
    } else {
        linear_axis((top, bottom), values)
    };
    let Some(axis) = axis else {
        let _ = writeln!(
            svg,
            r##"<text x="{centre}" y="{middle}" text-anchor="middle" fill="#666">no values</text>"##
        );
        return;
    };
    for (v, text) in axis.ticks() {
        if let Some(y) = axis.y(v) {
            let _ = writeln!(
                svg,
                r##"<line x1="{LEFT}" y1="{y:.1}" x2="{RIGHT}" y2="{y:.1}" stroke="#ddd"/>"##
            );
            let _ = writeln!(
                svg,
                r##"<text x="{}" y="{:.1}" text-anchor="end" font-size="11">{text}</text>"##,
                LEFT - 6.0,
                y + 4.0
            );
        }
    }
    // Frame ticks.
    let step = nice_step(frames.saturating_sub(1) as f64, 8.0).max(1.0) as usize;
    for i in (0..frames).step_by(step) {
        let x = frame_x(i, frames);
        let _ = writeln!(
            svg,
            r##"<line x1="{x:.1}" y1="{bottom}" x2="{x:.1}" y2="{}" stroke="#888"/>"##,
            bottom + 4.0
        );
        let _ = writeln!(
            svg,
            r##"<text x="{x:.1}" y="{}" text-anchor="middle" font-size="11">{i}</text>"##,
            bottom + 16.0
        );
    }
    // The data, one polyline per run of drawable values.
    let mut run: Vec<String> = Vec::new();
    let flush = |svg: &mut String, run: &mut Vec<String>| {
        if run.len() == 1 {
            // A lone value: a dot.
            if let Some((x, y)) = run[0].split_once(',') {
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x}" cy="{y}" r="1.5" fill="{}"/>"##,
                    COLOURS[index]
                );
            }
        } else if run.len() > 1 {
            let _ = writeln!(
                svg,
                r##"<polyline fill="none" stroke="{}" stroke-width="1.2" points="{}"/>"##,
                COLOURS[index],
                run.join(" ")
            );
        }
        run.clear();
    };
    for (i, &v) in values.iter().enumerate() {
        match axis.y(v) {
            Some(y) => run.push(format!("{:.1},{y:.1}", frame_x(i, frames))),
            None => flush(svg, &mut run),
        }
    }
    flush(svg, &mut run);
}

/// The timeline of a run (module docs): `step_ms[i]` is frame `i`'s compute time in
/// milliseconds, `stretch[i]` its largest edge stretch as a fraction (0.11 = 11 %), `None`
/// without an active page. The frame count is the longer of the two slices.
#[must_use]
pub fn timeline_svg(step_ms: &[f64], stretch: &[Option<f64>]) -> String {
    let frames = step_ms.len().max(stretch.len());
    let percent: Vec<f64> = stretch
        .iter()
        .map(|s| s.map_or(f64::NAN, |v| 100.0 * v))
        .collect();
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif">"##
    );
    let _ = writeln!(
        svg,
        r##"<rect x="0" y="0" width="{WIDTH}" height="{HEIGHT}" fill="white"/>"##
    );
    panel(
        &mut svg,
        0,
        "Step time per frame (ms, log scale)",
        step_ms,
        true,
        frames,
    );
    panel(
        &mut svg,
        1,
        "Max edge stretch of the active page (%)",
        &percent,
        false,
        frames,
    );
    let _ = writeln!(
        svg,
        r##"<text x="{}" y="{}" text-anchor="middle" font-size="12">frame</text>"##,
        0.5 * (LEFT + RIGHT),
        HEIGHT - 14.0
    );
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tiny well-formedness check: every tag is closed in order (self-closing tags
    /// count as closed); returns the number of elements.
    fn balanced(svg: &str) -> usize {
        let mut stack: Vec<String> = Vec::new();
        let mut elements = 0;
        let mut rest = svg;
        while let Some(open) = rest.find('<') {
            let close = rest[open..].find('>').expect("unterminated tag") + open;
            let tag = &rest[open + 1..close];
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(
                    stack.pop().as_deref(),
                    Some(name.trim()),
                    "mismatched </{name}>"
                );
            } else {
                let name: String = tag.chars().take_while(|c| c.is_alphanumeric()).collect();
                assert!(!name.is_empty(), "bad tag <{tag}>");
                elements += 1;
                if !tag.ends_with('/') {
                    stack.push(name);
                }
            }
            rest = &rest[close + 1..];
        }
        assert!(stack.is_empty(), "unclosed {stack:?}");
        elements
    }

    fn check(svg: &str) -> usize {
        assert!(svg.starts_with("<svg"));
        assert!(svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("Step time per frame"));
        assert!(svg.contains("Max edge stretch"));
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
        balanced(svg)
    }

    #[test]
    fn timeline_is_well_formed_with_lines_and_ticks() {
        let step: Vec<f64> = (0..300)
            .map(|i| 0.05 + (i as f64 * 0.1).sin().abs() * 3.0)
            .collect();
        let stretch: Vec<Option<f64>> = (0..300)
            .map(|i| {
                (40..200)
                    .contains(&i)
                    .then_some(0.002 * (i - 40) as f64 / 16.0)
            })
            .collect();
        let svg = timeline_svg(&step, &stretch);
        check(&svg);
        assert_eq!(svg.matches("<polyline").count(), 2);
        // Decade ticks 0.01 .. 10 ms, percent ticks, frame ticks.
        for tick in [">0.01<", ">0.1<", ">1<", ">10<", ">0<", ">100<", ">250<"] {
            assert!(svg.contains(tick), "missing tick {tick}");
        }
    }

    #[test]
    fn empty_input_says_no_frames() {
        let svg = timeline_svg(&[], &[]);
        check(&svg);
        assert_eq!(svg.matches("no frames").count(), 2);
        assert!(!svg.contains("<polyline"));
    }

    /// NaN, infinite, non-positive (log axis) and `None` values are skipped and break
    /// the line; a panel without any drawable value says so.
    #[test]
    fn bad_values_are_skipped() {
        let step = [1.0, f64::NAN, 2.0, 3.0, -1.0, 0.0, f64::INFINITY, 4.0, 5.0];
        let stretch = [None, Some(f64::NAN), None, Some(f64::INFINITY)];
        let svg = timeline_svg(&step, &stretch);
        check(&svg);
        // Runs: [1] (a dot), [2, 3], [4, 5].
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert_eq!(svg.matches("<circle").count(), 1);
        assert!(svg.contains("no values"));
    }
}
