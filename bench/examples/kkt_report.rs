//! Prints the size, fill, flop count and solve accuracy of the DOG-shaped KKT systems per
//! ordering (refined to $\varepsilon^{3/4}$, the attainable accuracy, tighter than the
//! step's default `Settings::refinement_tolerance`), and with `--export PATH` writes the 11x8 system as a Matrix Market file.
//!
//! `cargo run --release -p folio-bench --example kkt_report -- --export out/kkt_11x8.mtx`

use folio_bench::kkt::{DogKkt, SIZES};
use folio_solvers::Ordering;
use folio_solvers::ldlt::FactorOutcome;
use folio_solvers::matrix_market::write_matrix_market;

fn main() -> Result<(), Box<dyn core::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let export = args
        .iter()
        .position(|a| a == "--export")
        .map(|i| args.get(i + 1).cloned().ok_or("--export needs a path"))
        .transpose()?;

    println!(
        "{:<7} {:<16} {:>6} {:>8} {:>9} {:>11} {:>12} {:>10}",
        "quads", "ordering", "n", "nnz(A)", "nnz(L)", "flops", "regularized", "residual"
    );
    for quads in SIZES {
        for ordering in [Ordering::Natural, Ordering::Amd, Ordering::AmdDelayedDuals] {
            if ordering == Ordering::Natural && quads != SIZES[0] {
                continue; // dense fill: a reference point at the smallest size only
            }
            let mut system = DogKkt::new(quads, ordering);
            let s = system.settings;
            let outcome = system.kkt.factorize(s.pivot_epsilon, s.regularization);
            let regularized = match outcome {
                FactorOutcome::Factored { regularized, .. } => regularized.to_string(),
                FactorOutcome::NonFinite { pivot } => format!("NaN@{pivot}"),
                other => format!("{other:?}"),
            };
            let mut z = vec![0.0; system.rhs.len()];
            let residual = system
                .kkt
                .solve_refined(
                    &mut z,
                    &system.rhs,
                    s.refinement_steps,
                    f64::EPSILON.powf(0.75),
                )
                .relative_residual;
            println!(
                "{:<7} {:<16} {:>6} {:>8} {:>9} {:>11.3e} {:>12} {:>10.1e}",
                format!("{}x{}", quads.0, quads.1),
                format!("{ordering:?}"),
                system.kkt.pattern().order(),
                system.kkt.pattern().nnz(),
                system.kkt.symbolic().nnz_l(),
                system.kkt.symbolic().factor_flops(),
                regularized,
                residual
            );
        }
    }
    if let Some(path) = export {
        let system = DogKkt::new(SIZES[0], Ordering::default());
        let mut text = String::new();
        write_matrix_market(&mut text, system.kkt.pattern(), system.kkt.values())?;
        if let Some(dir) = std::path::Path::new(&path).parent() {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(&path, text)?;
        println!(
            "wrote {path}: the 11x8 DOG-sheet KKT, n = {}, {} stored entries",
            system.kkt.pattern().order(),
            system.kkt.pattern().nnz()
        );
    }
    Ok(())
}
