//! A refused setting, in one shape for every settings type of Folio: the field's path from
//! the settings type it belongs to (`weights.bend_page`, `solver.time_step`), the rule in
//! words with its range (`in [30, 200]`), and the value refused.
//!
//! Each settings type (the solver's, the book's, the page models', the sheet's) states each
//! of its ranges once, in its own `validate`; a type that holds another (the book holds the
//! solver's settings under `solver`) puts the inner error [`SettingError::within`] its field.
//! Readers of the error (scene files, the C API) translate the path to their own names.

use core::fmt;

/// The shortest time step (seconds) any Folio model takes. Far below it a step's $1/h^2$
/// terms overflow (at $h = 10^{-300}$ every step of the DOG book reports non-finite input),
/// and a run of a million steps would not cover a second.
pub const MIN_TIME_STEP: f64 = 1e-6;

/// The most segments a path has (`solver.time_step` has two, `tearing.fibers.seed` three).
/// Three keep a [`SettingError`] small enough to return by value (clippy's
/// `result_large_err` bound of 128 bytes, inside the models' own errors).
const MAX_SEGMENTS: usize = 3;

/// The path of a field from the root of a settings type: segments joined by `.` (a segment
/// may itself hold dots, as `"weights.glue"` does).
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct SettingPath {
    segments: [&'static str; MAX_SEGMENTS],
    len: u8,
}

impl SettingPath {
    /// The path of a field of the type that validates it.
    #[must_use]
    pub const fn new(field: &'static str) -> Self {
        Self {
            segments: [field, "", ""],
            len: 1,
        }
    }

    /// The same field seen from the type that holds this one under `section`. A path that is
    /// already three segments deep keeps its deepest segments (no settings type nests so
    /// deep).
    #[must_use]
    pub fn within(self, section: &'static str) -> Self {
        let len = usize::from(self.len);
        let kept = len.min(MAX_SEGMENTS - 1);
        let mut segments = [""; MAX_SEGMENTS];
        segments[0] = section;
        segments[1..=kept].copy_from_slice(&self.segments[len - kept..len]);
        Self {
            segments,
            len: (kept + 1) as u8,
        }
    }

    /// The segments, outermost first.
    #[must_use]
    pub fn segments(&self) -> &[&'static str] {
        &self.segments[..usize::from(self.len)]
    }

    /// The field itself: the last segment.
    #[must_use]
    pub fn field(&self) -> &'static str {
        self.segments[usize::from(self.len) - 1]
    }

    /// Whether the joined path reads `dotted` (`"weights.glue"`).
    #[must_use]
    pub fn is(&self, dotted: &str) -> bool {
        let mut rest = dotted;
        for (i, segment) in self.segments().iter().enumerate() {
            if i > 0 {
                let Some(after) = rest.strip_prefix('.') else {
                    return false;
                };
                rest = after;
            }
            let Some(after) = rest.strip_prefix(segment) else {
                return false;
            };
            rest = after;
        }
        rest.is_empty()
    }
}

impl fmt::Display for SettingPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.segments().iter().enumerate() {
            if i > 0 {
                f.write_str(".")?;
            }
            f.write_str(segment)?;
        }
        Ok(())
    }
}

impl fmt::Debug for SettingPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{self}\"")
    }
}

/// What a field must be: it completes "`<path>` must be ...".
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Requirement {
    /// The rule in words, with its range where it has one (`finite and > 0`, `from 1 to
    /// 16`, `at most a tenth of the page's smaller side`).
    Rule(&'static str),
    /// Finite and in the closed range `[min, max]` (a range its type computes, or keeps as
    /// numbers: written once, as numbers).
    Within {
        /// The smallest value allowed.
        min: f64,
        /// The largest value allowed.
        max: f64,
    },
    /// At least a bound the type computes from other fields, and why.
    AtLeast {
        /// The smallest value allowed.
        min: f64,
        /// Why, in words (it completes "at least `min` (...)").
        reason: &'static str,
    },
}

impl fmt::Display for Requirement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Rule(words) => f.write_str(words),
            Self::Within { min, max } => write!(f, "in [{}, {}]", Shown(min), Shown(max)),
            Self::AtLeast { min, reason } => write!(f, "at least {} ({reason})", Shown(min)),
        }
    }
}

/// A setting that is NaN, infinite or outside its documented range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SettingError {
    /// The field, from the settings type that was validated.
    pub path: SettingPath,
    /// What the field must be.
    pub requirement: Requirement,
    /// The value refused, where it is a number (counts as numbers too).
    pub value: Option<f64>,
}

impl SettingError {
    /// `field` of the type that validates it must be `requirement`.
    #[must_use]
    pub const fn new(field: &'static str, requirement: &'static str) -> Self {
        Self {
            path: SettingPath::new(field),
            requirement: Requirement::Rule(requirement),
            value: None,
        }
    }

    /// The same refusal, saying which value was refused.
    #[must_use]
    pub const fn with_value(mut self, value: f64) -> Self {
        self.value = Some(value);
        self
    }

    /// The same refusal seen from the type that holds the validated one under `section`.
    #[must_use]
    pub fn within(mut self, section: &'static str) -> Self {
        self.path = self.path.within(section);
        self
    }
}

impl SettingError {
    /// The refusal in the words of a reader who knows the field by another name `key` (a
    /// scene file's `book.params.page_width`, a C struct's `page_width`): "`key` must be RULE, not VALUE",
    /// the one wording of a refused setting.
    #[must_use]
    pub fn named<K: fmt::Display>(&self, key: K) -> Named<'_, K> {
        Named { error: self, key }
    }
}

/// A [`SettingError`] under the name its reader knows the field by ([`SettingError::named`]).
#[derive(Clone, Copy, Debug)]
pub struct Named<'a, K> {
    error: &'a SettingError,
    key: K,
}

impl<K: fmt::Display> fmt::Display for Named<'_, K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` must be {}", self.key, self.error.requirement)?;
        if let Some(v) = self.error.value {
            write!(f, ", not {}", Shown(v))?;
        }
        Ok(())
    }
}

impl fmt::Display for SettingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.named(self.path).fmt(f)
    }
}

impl core::error::Error for SettingError {}

/// `Ok` when `ok`, else `field` must be `requirement`, not `value`: the one check every
/// `validate` is made of.
///
/// # Errors
/// The [`SettingError`] when `ok` is false.
pub fn require(
    ok: bool,
    field: &'static str,
    requirement: &'static str,
    value: f64,
) -> Result<(), SettingError> {
    if ok {
        Ok(())
    } else {
        Err(SettingError::new(field, requirement).with_value(value))
    }
}

/// `Ok` when `value` is finite and > 0.
///
/// # Errors
/// `field` must be finite and > 0, not `value`.
pub fn require_positive(field: &'static str, value: f64) -> Result<(), SettingError> {
    require(
        value.is_finite() && value > 0.0,
        field,
        "finite and > 0",
        value,
    )
}

/// `Ok` when `value` is finite and >= 0.
///
/// # Errors
/// `field` must be finite and >= 0, not `value`.
pub fn require_non_negative(field: &'static str, value: f64) -> Result<(), SettingError> {
    require(
        value.is_finite() && value >= 0.0,
        field,
        "finite and >= 0",
        value,
    )
}

/// `Ok` when a model's time step `h` (seconds, the field `time_step`) is finite and at least
/// [`MIN_TIME_STEP`].
///
/// # Errors
/// `time_step` must be finite and at least 1e-6 seconds, not `h`.
pub fn require_time_step(h: f64) -> Result<(), SettingError> {
    let rule = "finite and at least 1e-6 seconds";
    require(h.is_finite() && h >= MIN_TIME_STEP, "time_step", rule, h)
}

/// `Ok` when `value` is finite and in `[min, max]`, else `field` must be in `[min, max]`,
/// not `value`.
///
/// # Errors
/// The [`SettingError`] when `value` is NaN, infinite or outside the range.
pub fn require_range(
    field: &'static str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<(), SettingError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(SettingError {
            path: SettingPath::new(field),
            requirement: Requirement::Within { min, max },
            value: Some(value),
        })
    }
}

/// `Ok` when `value` is at least `min` (a bound computed from other fields), else `field`
/// must be at least `min` because of `reason`, not `value`.
///
/// # Errors
/// The [`SettingError`] when `value` is NaN or below `min`.
pub fn require_at_least(
    field: &'static str,
    value: f64,
    min: f64,
    reason: &'static str,
) -> Result<(), SettingError> {
    if value >= min {
        Ok(())
    } else {
        Err(SettingError {
            path: SettingPath::new(field),
            requirement: Requirement::AtLeast { min, reason },
            value: Some(value),
        })
    }
}

/// A number in a message as a reader would write it, short: plain between $10^{-4}$ and
/// $10^6$ (`12`, `0.0075`, `120000`), scientific elsewhere (`1e300`, `4e-320`), never the
/// 309 digits `{}` prints for `1e300`; `0`, `NaN` and `inf` as themselves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown(pub f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let plain = v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs());
        if plain {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate alloc;
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn a_path_reads_from_the_outermost_type() {
        let e = SettingError::new("time_step", "in [1e-6, 0.1]")
            .with_value(1e300)
            .within("solver");
        assert!(e.path.is("solver.time_step"));
        assert!(!e.path.is("solver.time"));
        assert!(!e.path.is("solver"));
        assert_eq!(e.path.field(), "time_step");
        assert_eq!(
            e.to_string(),
            "`solver.time_step` must be in [1e-6, 0.1], not 1e300"
        );
        let dotted = SettingError::new("weights.glue", "in [100, 3000]").within("book");
        assert!(dotted.path.is("book.weights.glue"));
        assert_eq!(dotted.path.to_string(), "book.weights.glue");
    }

    #[test]
    fn a_deep_path_keeps_its_deepest_segments() {
        let mut path = SettingPath::new("seed");
        for section in ["fibers", "tearing"] {
            path = path.within(section);
        }
        assert_eq!(path.to_string(), "tearing.fibers.seed");
        assert_eq!(path.within("sheet").to_string(), "sheet.fibers.seed");
        assert!(core::mem::size_of::<SettingError>() <= 104);
    }

    #[test]
    fn a_range_is_written_once_as_numbers() {
        assert_eq!(require_range("gain", 0.5, 0.05, 1.0), Ok(()));
        let e = require_range("gain", 2.0, 0.05, 1.0).unwrap_err();
        assert_eq!(e.to_string(), "`gain` must be in [0.05, 1], not 2");
        let nan = require_range("gain", f64::NAN, 0.05, 1.0).unwrap_err();
        assert_eq!(nan.to_string(), "`gain` must be in [0.05, 1], not NaN");
        let thin = require_at_least("thickness", 1e-9, 1.2e-5, "1e-6 of the width").unwrap_err();
        assert_eq!(
            thin.to_string(),
            "`thickness` must be at least 1.2e-5 (1e-6 of the width), not 1e-9"
        );
        let wide = require_range("scale", 1e9, 1e-6, 1e6).unwrap_err();
        assert_eq!(wide.to_string(), "`scale` must be in [1e-6, 1e6], not 1e9");
    }

    #[test]
    fn numbers_are_short() {
        let show = |v: f64| Shown(v).to_string();
        assert_eq!(show(1e300), "1e300");
        assert_eq!(show(-1e300), "-1e300");
        assert_eq!(show(4e-320), "4e-320");
        assert_eq!(show(f64::MAX).len(), "1.7976931348623157e308".len());
        assert_eq!(show(12.0), "12");
        assert_eq!(show(0.0075), "0.0075");
        assert_eq!(show(120_000.0), "120000");
        assert_eq!(show(0.0), "0");
        assert_eq!(show(f64::NAN), "NaN");
    }
}
