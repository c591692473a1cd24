//! The one validation of a DOG book's settings, shared by scene files ([`crate::book`]) and
//! the C API (`folio_book_create`): the book's own [`BookSettings::validate`] and the limits
//! below, each refusal named by its scene key (`book.page_width`, `solver.time_step`,
//! `weights.pull`) with a message whose numbers are short ([`crate::number::show`]).

use folio_book::{BookError, BookSettings, LayoutError};

use crate::number::show;

/// The most pages a book may have: more only make every frame slower.
pub const MAX_PAGES: u32 = 100_000;

/// No weight (`[weights]`) may exceed this; each has its own, narrower range
/// ([`folio_book::WEIGHT_RANGES`]), which [`weight`] checks.
pub const MAX_WEIGHT: f64 = 1e9;

/// The shortest time step (seconds). A scene runs at most $10^6$ frames, so a shorter step
/// cannot cover a second of motion; far below it the step's $1/h^2$ terms overflow (at
/// $h = 10^{-300}$ every step reports non-finite input).
pub const MIN_TIME_STEP: f64 = 1e-6;

/// The longest time step (seconds): six frames at 60 per second.
pub const MAX_TIME_STEP: f64 = 0.1;

/// A grid cell of the page must be at least this many times the book's constraint
/// tolerance (`constraint_tolerance`, $10^{-4}$ page units by default): in a smaller page
/// every constraint holds to within the tolerance whatever the page does, and a gesture
/// no longer moves it measurably (a page $10^{-9}$ wide cannot be touched).
pub const MIN_CELL_TOLERANCES: f64 = 100.0;

/// The thinnest paper relative to the page width: $10^{-6} W$, about eight `f32` roundings
/// of a coordinate on the page ($\varepsilon_{32} W \approx 1.2 \cdot 10^{-7} W$); thinner
/// paper (a subnormal thickness) is below what the page's coordinates resolve.
pub const MIN_THICKNESS_RATIO: f64 = 1e-6;

/// A setting refused: its scene key and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    /// The scene key (`book.page_width`, `solver.time_step`, `weights.glue`, ...).
    pub key: String,
    /// What is wrong, starting with the key.
    pub message: String,
}

impl Refusal {
    fn new(key: &str, message: String) -> Self {
        Self {
            key: key.to_string(),
            message,
        }
    }
}

/// Checks a time step `h` (seconds): $h \in [$[`MIN_TIME_STEP`]$,$ [`MAX_TIME_STEP`]$]$.
///
/// # Errors
/// The message, naming `solver.time_step` and the value.
pub fn time_step(h: f64) -> Result<(), String> {
    if h.is_finite() && (MIN_TIME_STEP..=MAX_TIME_STEP).contains(&h) {
        Ok(())
    } else {
        Err(format!(
            "solver.time_step must be in [{}, {}] seconds, not {}",
            show(MIN_TIME_STEP),
            show(MAX_TIME_STEP),
            show(h)
        ))
    }
}

/// Checks a weight (`weights.*`): finite and in its range of [`folio_book::WEIGHT_RANGES`]
/// (the range the DOG book holds its page within 10 % stretch), or in $[0,$
/// [`MAX_WEIGHT`]$]$ for a key without one.
///
/// # Errors
/// The message, naming the weight, its range and its value.
pub fn weight(key: &str, w: f64) -> Result<(), String> {
    let (lo, hi, requirement) = folio_book::WEIGHT_RANGES
        .iter()
        .find(|range| range.0 == key)
        .map_or((0.0, MAX_WEIGHT, "in [0, 1e9]"), |r| (r.1, r.2, r.3));
    if w.is_finite() && (lo..=hi).contains(&w) {
        Ok(())
    } else {
        Err(format!(
            "{key} must be {requirement} (the range the DOG book holds its page within 10 % \
             stretch; see folio_book::WEIGHT_RANGES), not {}",
            show(w)
        ))
    }
}

/// Checks the settings of a DOG book: at most [`MAX_PAGES`] pages, the time step and the
/// weights in range, everything [`BookSettings::validate`] checks, a page large enough to
/// be touched ([`MIN_CELL_TOLERANCES`]) and paper thick enough to resolve
/// ([`MIN_THICKNESS_RATIO`]).
///
/// # Errors
/// The first refused setting.
pub fn book(settings: &BookSettings<f64>) -> Result<(), Refusal> {
    let p = &settings.params;
    if p.total_pages > MAX_PAGES {
        let message = format!(
            "book.total_pages must be between 1 and {MAX_PAGES}, not {}",
            p.total_pages
        );
        return Err(Refusal::new("book.total_pages", message));
    }
    time_step(settings.solver.time_step).map_err(|m| Refusal::new("solver.time_step", m))?;
    for (key, w) in settings.weights.named() {
        weight(key, w).map_err(|m| Refusal::new(key, m))?;
    }
    settings.validate().map_err(|e| refusal(settings, &e))?;
    let cell = p.page_width / settings.quads_across as f64;
    let smallest = MIN_CELL_TOLERANCES * settings.constraint_tolerance;
    if cell < smallest {
        let message = format!(
            "book.page_width {} is too small to touch: its grid cells ({}) must be at least \
             {} x the constraint tolerance ({}), the page at least {} wide",
            show(p.page_width),
            show(cell),
            show(MIN_CELL_TOLERANCES),
            show(settings.constraint_tolerance),
            show(smallest * settings.quads_across as f64)
        );
        return Err(Refusal::new("book.page_width", message));
    }
    let thinnest = MIN_THICKNESS_RATIO * p.page_width;
    if p.page_thickness < thinnest {
        let message = format!(
            "book.page_thickness {} is too thin: at least {} (1e-6 of the page width)",
            show(p.page_thickness),
            show(thinnest)
        );
        return Err(Refusal::new("book.page_thickness", message));
    }
    Ok(())
}

/// A refusal of [`BookSettings::validate`] at its scene key.
fn refusal(settings: &BookSettings<f64>, e: &BookError) -> Refusal {
    let p = &settings.params;
    let (key, message) = match *e {
        BookError::Layout(LayoutError::NoPages) => (
            "book.total_pages",
            format!(
                "a book needs at least one page: book.total_pages must be between 1 and {MAX_PAGES}"
            ),
        ),
        BookError::Layout(LayoutError::LeftPagesExceedTotal { left, total }) => (
            "book.left_pages",
            format!("book.left_pages ({left}) must be at most total_pages ({total})"),
        ),
        BookError::Layout(LayoutError::NonPositive { field }) => {
            (field, format!("book.{field} must be finite and > 0"))
        }
        BookError::Layout(LayoutError::TooFewMidlineNodes { .. }) => (
            "midline_nodes",
            "book.midline_nodes must be at least 3".into(),
        ),
        BookError::Layout(LayoutError::TooLarge { field }) => {
            let value = match field {
                "page_width" => p.page_width,
                "page_height" => p.page_height(),
                "page_thickness" => p.page_thickness * f64::from(p.total_pages),
                "cover_thickness" => p.cover_thickness,
                _ => p.cover_overhang,
            };
            let what = if field == "page_thickness" {
                "the book's thickness (pages x page_thickness)".to_string()
            } else {
                format!("book.{field}")
            };
            let message = format!(
                "{what} is too large: {} exceeds {} page units",
                show(value),
                show(folio_book::layout::MAX_EXTENT)
            );
            // The height is aspect_ratio x page_width: report it at the width.
            let key = if field == "page_height" {
                "page_width"
            } else {
                field
            };
            (key, message)
        }
        BookError::InvalidSetting { field, requirement } => {
            (field, format!("{field} must be {requirement}"))
        }
        _ => ("", e.to_string()),
    };
    let key = if key.is_empty() || key.contains('.') {
        key.to_string()
    } else if key == "time_step" {
        "solver.time_step".to_string()
    } else {
        format!("book.{key}")
    };
    Refusal { key, message }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_pass_and_each_limit_is_named() {
        let ok = BookSettings::<f64>::default();
        assert_eq!(book(&ok), Ok(()));
        let key = |f: fn(&mut BookSettings<f64>)| {
            let mut s = ok;
            f(&mut s);
            book(&s).expect_err("refused").key
        };
        assert_eq!(key(|s| s.solver.time_step = 1e-300), "solver.time_step");
        assert_eq!(key(|s| s.solver.time_step = 4e-320), "solver.time_step");
        assert_eq!(key(|s| s.solver.time_step = 1e308), "solver.time_step");
        assert_eq!(
            key(|s| s.params.page_thickness = 4e-320),
            "book.page_thickness"
        );
        assert_eq!(key(|s| s.params.page_width = 1e-9), "book.page_width");
        assert_eq!(key(|s| s.params.page_width = 1e300), "book.page_width");
        assert_eq!(key(|s| s.params.total_pages = 100_001), "book.total_pages");
        assert_eq!(key(|s| s.weights.pull = 2e9), "weights.pull");
        let m = book(&BookSettings {
            params: folio_book::BookParams {
                page_width: 1e300,
                ..ok.params
            },
            ..ok
        })
        .expect_err("refused")
        .message;
        assert!(m.contains("1e300") && m.len() < 120, "{m}");
    }
}
