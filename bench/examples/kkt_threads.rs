//! Times one numeric factorization of the DOG-sheet KKT on one and on two threads
//! (`Parallelism`), in one run, for the four issue sizes or one `--grid WxH`: AMD on one
//! thread (the default order), and the split order (one-level nested dissection, AMD in
//! each part) on one thread and on two. The three are timed in turns, `--rounds N` rounds
//! (default 15) of a median of 5 calls each, and the median round is reported. It also
//! checks that the two-thread factor is bit for bit the one-thread factor of the split
//! order, and prints the parts' sizes, their share of the factor's multiply-adds (row by
//! row, as the up-looking factor spends them), fill and flops.
//!
//! `cargo run --release -p folio-bench --example kkt_threads -- --grid 22x16`

use folio_bench::kkt::{DogKkt, SIZES, exit_code, flag_value, median_us, parse_grid};
use folio_solvers::symbolic::Symbolic;
use folio_solvers::{Kkt, Ordering, Parallelism};
use std::process::ExitCode;

/// Calls per timed round.
const CALLS: usize = 5;

fn main() -> ExitCode {
    exit_code("kkt_threads", run())
}

fn run() -> Result<(), Box<dyn core::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let grid = flag_value(&args, "--grid")?.map(parse_grid).transpose()?;
    let rounds: usize = flag_value(&args, "--rounds")?.map_or(Ok(15), str::parse)?;
    println!(
        "{:<6} {:>5} {:>13} {:>9} {:>9} {:>8} {:>8} {:>10} {:>8} {:>8} {:>8} {:>6} {:>6}",
        "quads",
        "n",
        "parts A/B/S",
        "nnz(L)",
        "nnz(L)ND",
        "flops",
        "flopsND",
        "work %A/B/S",
        "AMD µs",
        "ND1 µs",
        "ND2 µs",
        "ND1/2",
        "AMD/2"
    );
    for quads in grid.map_or(SIZES.to_vec(), |g| vec![g]) {
        let mut amd = DogKkt::try_new(quads, Ordering::Amd)?;
        let pattern = amd.kkt.pattern().clone();
        let mut split = Kkt::with_parallelism(pattern, Ordering::Amd, Parallelism::Two);
        split.values_mut().copy_from_slice(amd.kkt.values());
        let s = amd.settings;
        let limits = (s.pivot_epsilon, s.regularization);
        // Bit for bit: one thread against two on the split order.
        let mut factors = Vec::new();
        for threads in [1, 2] {
            split.set_threads(threads);
            split.factorize(limits.0, limits.1);
            factors.push((split.factor().l().to_vec(), split.factor().d().to_vec()));
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        if bits(&factors[0].0) != bits(&factors[1].0) || bits(&factors[0].1) != bits(&factors[1].1)
        {
            return Err(format!("{quads:?}: the two-thread factor differs").into());
        }
        let mut times = [Vec::new(), Vec::new(), Vec::new()];
        for _ in 0..rounds {
            times[0].push(median_us(CALLS, || {
                amd.kkt.factorize(limits.0, limits.1);
            }));
            for threads in [1, 2] {
                split.set_threads(threads);
                times[threads].push(median_us(CALLS, || {
                    split.factorize(limits.0, limits.1);
                }));
            }
        }
        let [t_amd, t_one, t_two] = times.map(|mut t| {
            t.sort_by(f64::total_cmp);
            t[t.len() / 2]
        });
        let symbolic = split.symbolic();
        let parts = symbolic.split().ok_or("no split")?;
        let n = symbolic.order();
        println!(
            "{:<6} {:>5} {:>13} {:>9} {:>9} {:>8.2e} {:>8.2e} {:>10} {:>8.0} {:>8.0} {:>8.0} {:>6.2} {:>6.2}",
            format!("{}x{}", quads.0, quads.1),
            n,
            format!("{}/{}/{}", parts.a, parts.b - parts.a, n - parts.b),
            amd.kkt.symbolic().nnz_l(),
            symbolic.nnz_l(),
            amd.kkt.symbolic().factor_flops(),
            symbolic.factor_flops(),
            {
                let [a, b, s] = work_shares(symbolic, parts.a, parts.b);
                format!("{a:.0}/{b:.0}/{s:.0}")
            },
            t_amd,
            t_one,
            t_two,
            t_one / t_two,
            t_amd / t_two
        );
    }
    Ok(())
}

/// The shares (%) of the factor's multiply-adds in the columns of half $A$ (`..a`), half
/// $B$ (`a..b`) and the separator (`b..`, the serial phase): column $j$ updates, for each
/// of its rows, the rows above it in the column.
fn work_shares(symbolic: &Symbolic, a: usize, b: usize) -> [f64; 3] {
    let ptr = symbolic.l_col_ptr();
    let mut work = [0.0; 3];
    for j in 0..symbolic.order() {
        let c = f64::from(ptr[j + 1] - ptr[j]);
        work[usize::from(j >= a) + usize::from(j >= b)] += c * (c + 1.0) / 2.0;
    }
    let total: f64 = work.iter().sum();
    work.map(|w| 100.0 * w / total)
}
