//! Solver layer: symbolic analysis, numeric refactor, solve and a full step on DOG-shaped
//! KKTs of 11x8 to 32x24 quads, side by side with faer's sparse LDL^T from scratch (and
//! refactorized simplicial / supernodal, one and two threads) and, at 11x8, a dense LU.
#![allow(missing_docs)] // `criterion_group!` generates an undocumented public function.

use core::hint::black_box;
use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};
use faer::Par;
use folio_bench::kkt::{DogKkt, SIZES, faer_factor_and_solve, faer_from_scratch, faer_symbolic};
use folio_solvers::symbolic::Symbolic;
use folio_solvers::{Ordering, Solver};

fn name((x, y): (usize, usize)) -> String {
    format!("{x}x{y}")
}

fn folio(c: &mut Criterion) {
    let mut g = c.benchmark_group("kkt");
    for quads in SIZES {
        let id = name(quads);
        for ordering in [Ordering::AmdDelayedDuals, Ordering::Amd] {
            let tag = format!("{ordering:?}");
            let mut system = DogKkt::new(quads, ordering);
            let mut z = vec![0.0; system.rhs.len()];
            g.bench_function(
                BenchmarkId::new(format!("folio symbolic {tag}"), &id),
                |b| {
                    b.iter(|| black_box(Symbolic::analyse(system.kkt.pattern(), ordering)));
                },
            );
            let s = system.settings;
            g.bench_function(
                BenchmarkId::new(format!("folio refactor {tag}"), &id),
                |b| {
                    b.iter(|| black_box(system.kkt.factorize(s.pivot_epsilon, s.regularization)));
                },
            );
            g.bench_function(BenchmarkId::new(format!("folio solve {tag}"), &id), |b| {
                b.iter(|| {
                    black_box(system.kkt.solve_refined(
                        &mut z,
                        &system.rhs,
                        s.refinement_steps,
                        s.refinement_tolerance,
                    ))
                });
            });
            g.bench_function(
                BenchmarkId::new(format!("folio refactor+solve {tag}"), &id),
                |b| {
                    b.iter(|| black_box(system.refactor_and_solve(&mut z)));
                },
            );
            g.bench_function(
                BenchmarkId::new(format!("folio full step {tag}"), &id),
                |b| {
                    let mut solver = Solver::new(s).expect("valid settings");
                    let mut state = system.state.clone();
                    solver.step(&system.sheet, &mut state).expect("step");
                    b.iter_batched_ref(
                        || system.state.clone(),
                        |state| black_box(solver.step(&system.sheet, state).expect("step")),
                        BatchSize::SmallInput,
                    );
                },
            );
            g.bench_function(
                BenchmarkId::new(format!("folio analysis+factor+solve {tag}"), &id),
                |b| {
                    b.iter(|| {
                        let mut fresh =
                            folio_solvers::Kkt::<f64>::new(system.kkt.pattern().clone(), ordering);
                        fresh.values_mut().copy_from_slice(system.kkt.values());
                        fresh.factorize(s.pivot_epsilon, s.regularization);
                        black_box(fresh.solve_refined(
                            &mut z,
                            &system.rhs,
                            s.refinement_steps,
                            s.refinement_tolerance,
                        ))
                    });
                },
            );
        }
    }
    g.finish();
}

fn faer_baselines(c: &mut Criterion) {
    let mut g = c.benchmark_group("kkt");
    for quads in SIZES {
        let id = name(quads);
        let system = DogKkt::new(quads, Ordering::AmdDelayedDuals);
        let signs = system.signs();
        let mut z = vec![0.0; system.rhs.len()];
        g.bench_function(BenchmarkId::new("faer from scratch", &id), |b| {
            b.iter(|| faer_from_scratch(&system, &signs, black_box(&mut z)));
        });
        for (label, supernodal) in [("simplicial", false), ("supernodal", true)] {
            let symbolic = faer_symbolic(&system, Some(supernodal));
            let mut l = vec![0.0; symbolic.len_val()];
            for (threads, par) in [(1, Par::Seq), (2, Par::rayon(2))] {
                if !supernodal && threads == 2 {
                    continue; // faer's simplicial factorization is sequential
                }
                let bench = format!("faer refactor+solve {label} {threads}t");
                g.bench_function(BenchmarkId::new(bench, &id), |b| {
                    b.iter(|| {
                        faer_factor_and_solve(&system, &symbolic, &mut l, &signs, &mut z, par);
                        black_box(&z);
                    });
                });
            }
        }
        if quads == SIZES[0] {
            let dense = system.dense();
            let rhs = faer::Mat::from_fn(system.rhs.len(), 1, |i, _| system.rhs[i]);
            g.bench_function(BenchmarkId::new("faer dense LU", &id), |b| {
                b.iter(|| {
                    use faer::linalg::solvers::Solve;
                    black_box(dense.partial_piv_lu().solve(&rhs))
                });
            });
        }
    }
    g.finish();
}

criterion_group!(benches, folio, faer_baselines);
criterion_main!(benches);
