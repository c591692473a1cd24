//! Prints the size, fill, flop count and solve accuracy of the DOG-shaped KKT systems per
//! ordering (refined to $\varepsilon^{3/4}$, the attainable accuracy, tighter than the
//! step's default `Settings::refinement_tolerance`), for the four issue sizes or for one
//! `--grid WxH`; `--export PATH` writes that grid's system (11x8 without `--grid`) as a
//! Matrix Market file, `--rhs PATH` its right-hand side as a Matrix Market array and
//! `--perm PATH` the permutation (`perm[new] = old`, 0-based, one a line) of `--ordering
//! NAME` (`Amd`, the default, `AmdDelayedDuals`, `AmdQuasiDefinite` or `Natural`).
//!
//! `cargo run --release -p folio-bench --example kkt_report -- --grid 22x16 --export out/kkt_22x16.mtx`

use folio_bench::kkt::{DogKkt, SIZES, exit_code, flag_value, parse_grid};
use folio_solvers::Ordering;
use folio_solvers::ldlt::FactorOutcome;
use folio_solvers::matrix_market::write_matrix_market;
use std::path::Path;
use std::process::ExitCode;

/// The flags, each followed by its value.
const FLAGS: [&str; 5] = ["--grid", "--export", "--rhs", "--perm", "--ordering"];

/// Grids at most this many quads also get the natural order (dense fill: a reference point).
const NATURAL_QUADS: usize = 11 * 8;

fn main() -> ExitCode {
    exit_code("kkt_report", run())
}

fn run() -> Result<(), Box<dyn core::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    for (i, a) in args.iter().enumerate() {
        let value = i > 0 && FLAGS.contains(&args[i - 1].as_str());
        if !value && !FLAGS.contains(&a.as_str()) {
            return Err(format!("unknown argument {a:?} (--grid WxH, --export PATH, --rhs PATH, --perm PATH, --ordering NAME)").into());
        }
    }
    let grid = flag_value(&args, "--grid")?.map(parse_grid).transpose()?;
    let export = flag_value(&args, "--export")?;
    let rhs = flag_value(&args, "--rhs")?;
    let perm = flag_value(&args, "--perm")?;
    let ordering = match flag_value(&args, "--ordering")? {
        None | Some("Amd") => Ordering::Amd,
        Some("AmdDelayedDuals") => Ordering::AmdDelayedDuals,
        Some("AmdQuasiDefinite") => Ordering::AmdQuasiDefinite,
        Some("Natural") => Ordering::Natural,
        Some(other) => {
            return Err(format!(
                "--ordering: Amd, AmdDelayedDuals, AmdQuasiDefinite or Natural, not {other:?}"
            )
            .into());
        }
    };
    let grids = grid.map_or(SIZES.to_vec(), |g| vec![g]);

    println!(
        "{:<7} {:<16} {:>6} {:>8} {:>9} {:>11} {:>12} {:>10}",
        "quads", "ordering", "n", "nnz(A)", "nnz(L)", "flops", "regularized", "residual"
    );
    for quads in grids {
        for ordering in [
            Ordering::Natural,
            Ordering::Amd,
            Ordering::AmdDelayedDuals,
            Ordering::AmdQuasiDefinite,
        ] {
            if ordering == Ordering::Natural && quads.0 * quads.1 > NATURAL_QUADS {
                continue;
            }
            let mut system = DogKkt::try_new(quads, ordering)?;
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
    if export.is_none() && rhs.is_none() && perm.is_none() {
        return Ok(());
    }
    let quads = grid.unwrap_or(SIZES[0]);
    let system = DogKkt::try_new(quads, ordering)?;
    let n = system.kkt.pattern().order();
    let name = format!("{}x{}", quads.0, quads.1);
    if let Some(path) = export {
        let mut text = String::new();
        write_matrix_market(&mut text, system.kkt.pattern(), system.kkt.values())?;
        write(path, &text)?;
        let nnz = system.kkt.pattern().nnz();
        println!("wrote {path}: the {name} DOG-sheet KKT, n = {n}, {nnz} stored entries");
    }
    if let Some(path) = rhs {
        let mut text = format!("%%MatrixMarket matrix array real general\n{n} 1\n");
        for v in &system.rhs {
            text.push_str(&format!("{v:e}\n"));
        }
        write(path, &text)?;
        println!("wrote {path}: the {name} right-hand side, {n} entries");
    }
    if let Some(path) = perm {
        let ordering = system.settings.ordering;
        let mut text =
            format!("% Folio {ordering:?} ordering of the {name} KKT: perm[new] = old\n");
        for p in system.kkt.symbolic().perm() {
            text.push_str(&format!("{p}\n"));
        }
        write(path, &text)?;
        println!("wrote {path}: Folio's {ordering:?} permutation of the {name} KKT");
    }
    Ok(())
}

/// Writes `text` to `path`, creating its directory.
fn write(path: &str, text: &str) -> Result<(), Box<dyn core::error::Error>> {
    if let Some(dir) = Path::new(path).parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, text).map_err(|e| format!("{path}: {e}").into())
}
