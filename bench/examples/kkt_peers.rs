//! Times Folio's and faer's analysis, numeric $LDL^\top$ and solve of one DOG-sheet KKT
//! (`--grid WxH`), median of `--reps N` calls each, for `bench/peers/run.sh`, which times
//! CHOLMOD and Eigen on the same matrix exported by `kkt_report`. `--check PATH` first
//! verifies that the Matrix Market file at PATH is this very matrix.
//!
//! One line per solver, tab-separated: solver, ordering, analysis µs, numeric factor µs,
//! solve µs, nnz(L) (strictly lower), relative residual $\lVert b - Kz\rVert_\infty /
//! \lVert b\rVert_\infty$ of the plain solve, status (Folio: how many pivots it
//! regularized).
//!
//! `cargo run --release -p folio-bench --example kkt_peers -- --grid 22x16 --reps 51`

use core::hint::black_box;
use faer::Par;
use faer::dyn_stack::MemStack;
use folio_bench::kkt::{
    DogKkt, exit_code, faer_factor, faer_scratch, faer_solve, faer_symbolic, flag_value, median_us,
    parse_grid,
};
use folio_solvers::Ordering;
use folio_solvers::ldlt::FactorOutcome;
use folio_solvers::matrix_market::write_matrix_market;
use folio_solvers::symbolic::Symbolic;
use std::process::ExitCode;

fn main() -> ExitCode {
    exit_code("kkt_peers", run())
}

/// $\lVert b - Kz\rVert_\infty / \lVert b\rVert_\infty$ on the unregularized matrix.
fn relative_residual(system: &DogKkt, z: &[f64]) -> f64 {
    let mut kz = vec![0.0; z.len()];
    system.kkt.multiply(&mut kz, z);
    let r = kz
        .iter()
        .zip(&system.rhs)
        .fold(0.0_f64, |m, (a, b)| m.max((b - a).abs()));
    r / system.rhs.iter().fold(0.0_f64, |m, b| m.max(b.abs()))
}

fn run() -> Result<(), Box<dyn core::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quads = parse_grid(flag_value(&args, "--grid")?.ok_or("--grid WxH is required")?)?;
    let reps: usize = match flag_value(&args, "--reps")? {
        None => 51,
        Some(r) => r
            .parse()
            .ok()
            .filter(|&r| r > 0)
            .ok_or(format!("--reps expects a positive integer, not {r:?}"))?,
    };
    if let Some(path) = flag_value(&args, "--check")? {
        let system = DogKkt::try_new(quads, Ordering::default())?;
        let mut text = String::new();
        write_matrix_market(&mut text, system.kkt.pattern(), system.kkt.values())?;
        let file = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
        if file != text {
            return Err(format!("{path} is not the {}x{} KKT matrix", quads.0, quads.1).into());
        }
    }
    for ordering in [Ordering::Amd, Ordering::AmdDelayedDuals] {
        let mut system = DogKkt::try_new(quads, ordering)?;
        let s = system.settings;
        let mut z = vec![0.0; system.rhs.len()];
        let analysis = median_us(reps, || {
            black_box(Symbolic::analyse(system.kkt.pattern(), ordering));
        });
        let factor = median_us(reps, || {
            black_box(system.kkt.factorize(s.pivot_epsilon, s.regularization));
        });
        let status = match system.kkt.factorize(s.pivot_epsilon, s.regularization) {
            FactorOutcome::Factored { regularized, .. } => format!("regularized {regularized}"),
            other => format!("{other:?}"),
        };
        let solve = median_us(reps, || {
            black_box(system.kkt.solve_refined(&mut z, &system.rhs, 0, 0.0));
        });
        let nnz_l = system.kkt.symbolic().nnz_l();
        let residual = relative_residual(&system, &z);
        println!(
            "Folio\t{ordering:?}\t{analysis:.1}\t{factor:.1}\t{solve:.1}\t{nnz_l}\t{residual:.1e}\t{status}"
        );
    }
    let system = DogKkt::try_new(quads, Ordering::default())?;
    let signs = system.signs();
    let n = system.rhs.len();
    for (label, supernodal) in [("faer supernodal", true), ("faer simplicial", false)] {
        let analysis = median_us(reps, || {
            black_box(faer_symbolic(&system, Some(supernodal)));
        });
        let symbolic = faer_symbolic(&system, Some(supernodal));
        let mut l = vec![0.0; symbolic.len_val()];
        let mut buffer = faer_scratch(&symbolic, Par::Seq);
        let stack = MemStack::new(&mut buffer);
        let factor = median_us(reps, || {
            faer_factor(&system, &symbolic, &mut l, &signs, Par::Seq, stack);
        });
        let mut z = vec![0.0; n];
        let solve = median_us(reps, || {
            faer_solve(&system, &symbolic, &l, &mut z, Par::Seq, stack);
            black_box(&z);
        });
        let nnz_l = symbolic.len_val() - n;
        let residual = relative_residual(&system, &z);
        println!(
            "{label}\tAMD (faer)\t{analysis:.1}\t{factor:.1}\t{solve:.1}\t{nnz_l}\t{residual:.1e}\t-"
        );
    }
    Ok(())
}
