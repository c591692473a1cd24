//! Numbers in messages: a value the user wrote is shown as written would read, short.
//! Values far from 1 are shown in scientific notation (`1e300`, `4e-320`), never as the
//! 309 digits `{}` prints for `1e300`.

/// `v` for a message: plain between $10^{-4}$ and $10^6$ (`12`, `0.0075`, `120000`),
/// scientific elsewhere (`1e300`, `4e-320`, `1.5e-9`); `0`, `NaN` and `inf` as themselves.
/// ([`folio_kernels::Shown`], which the models' setting errors use).
#[must_use]
pub fn show(v: f64) -> String {
    folio_kernels::Shown(v).to_string()
}

/// A measured value `v` for a message: four significant digits without trailing zeros,
/// plain between $10^{-4}$ and $10^6$ (`0.1004`, `12.35`, `750`), scientific elsewhere
/// (`1.235e-7`).
#[must_use]
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-4..6).contains(&magnitude) {
        let decimals = (3 - magnitude).max(0) as usize;
        let text = format!("{v:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        format!("{v:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn measured_values_have_four_digits() {
        assert_eq!(short(0.10042124529787388), "0.1004");
        assert_eq!(short(12.3456), "12.35");
        assert_eq!(short(750.0), "750");
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(1.23456e-7), "1.235e-7");
        assert_eq!(short(-2.5e300), "-2.500e300");
        assert_eq!(short(f64::NAN), "NaN");
    }
}
