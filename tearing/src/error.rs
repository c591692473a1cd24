//! Typed errors of the tearing setup APIs (settings and rasters). Evaluation never fails.

use core::fmt;

/// Why a tearing setting or raster was refused. Each variant names the offending field as
/// `Type.field` (for example `"FiberSettings.scale"`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum TearingError {
    /// A setting is NaN or infinite.
    NonFinite {
        /// The field, as `Type.field`.
        field: &'static str,
    },
    /// A setting is finite but outside its documented range `[min, max]`.
    OutOfRange {
        /// The field, as `Type.field`.
        field: &'static str,
        /// The refused value (integers converted to `f64`).
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
}

impl fmt::Display for TearingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { field } => write!(f, "`{field}` is not finite"),
            Self::OutOfRange {
                field,
                value,
                min,
                max,
            } => write!(f, "`{field}` = {value} is outside [{min}, {max}]"),
        }
    }
}

/// `std::error::Error` is this trait (re-exported by `std`), so the impl holds with and
/// without the `std` feature.
impl core::error::Error for TearingError {}

/// `Ok(())` if `value` is finite and in `[min, max]`, else the matching [`TearingError`].
pub(crate) fn check_range(
    field: &'static str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<(), TearingError> {
    if !value.is_finite() {
        Err(TearingError::NonFinite { field })
    } else if value < min || value > max {
        Err(TearingError::OutOfRange {
            field,
            value,
            min,
            max,
        })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn check_range_names_the_field() {
        assert_eq!(check_range("S.x", 0.5, 0.0, 1.0), Ok(()));
        assert_eq!(
            check_range("S.x", f64::NAN, 0.0, 1.0),
            Err(TearingError::NonFinite { field: "S.x" })
        );
        let e = check_range("S.x", 2.0, 0.0, 1.0).unwrap_err();
        assert!(matches!(e, TearingError::OutOfRange { field: "S.x", .. }));
        assert_eq!(e.to_string(), "`S.x` = 2 is outside [0, 1]");
    }
}
