//! Matrix Market export of an assembled KKT matrix, so other solvers can be timed on the very
//! matrix Folio factorizes.
//!
//! Format: `coordinate real symmetric`, 1-based, lower triangle (the transpose of Folio's
//! stored upper triangle), values in Rust's shortest round-trip exponent notation.

use core::fmt::{self, Write};
use folio_kernels::Real;

use crate::pattern::KktPattern;

/// Writes the symmetric matrix with upper-triangle `values` on `pattern` to `out`.
///
/// # Errors
/// Whatever `out` returns.
pub fn write_matrix_market<T: Real, W: Write>(
    out: &mut W,
    pattern: &KktPattern,
    values: &[T],
) -> fmt::Result {
    let n = pattern.order();
    writeln!(out, "%%MatrixMarket matrix coordinate real symmetric")?;
    writeln!(
        out,
        "% Folio KKT matrix: {} free coordinates, then {} constraint rows",
        pattern.dofs, pattern.rows
    )?;
    writeln!(out, "{n} {n} {}", pattern.nnz())?;
    for c in 0..n {
        let range = pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize;
        for (&r, v) in pattern.row_idx[range.clone()].iter().zip(&values[range]) {
            writeln!(out, "{} {} {:e}", c + 1, r + 1, v.to_f64())?;
        }
    }
    Ok(())
}
