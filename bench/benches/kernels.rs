//! Throughput of every `folio-kernels` kernel in f32 and f64 (stars, edges or vertices per
//! second), and the batched cone map against the seed's per-vertex scalar loop, side by side.
//!
//! `cargo bench -p folio-bench --bench kernels`; CI runs it with `-- --test` (each once).
#![allow(missing_docs)] // `criterion_group!` generates an undocumented public function.

use core::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use folio_bench::{Inputs, page_grid, seed_cone_loop_f32, seed_cone_loop_f64};
use folio_kernels::cone::ConeCurl;
use folio_kernels::dog::{DogInnerStar, FlatStarRemedy};
use folio_kernels::glue::Glue;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::spring::Spring;
use folio_kernels::{Constraint, Potential, Real, curve_laplacian, dog_laplacian};

const STARS: usize = 1024;

fn per_precision<T: Real>(c: &mut Criterion, precision: &str) {
    let mut inputs = Inputs::new(7);
    let inner = inputs.stars::<T, 5>(STARS);
    let edges = inputs.stars::<T, 2>(STARS);
    let triples = inputs.stars::<T, 3>(STARS);
    let quads = inputs.stars::<T, 4>(STARS);
    let lambda = [T::ONE, T::HALF, -T::ONE];
    let one = T::ONE;

    let mut g = c.benchmark_group("kernels");
    g.throughput(Throughput::Elements(STARS as u64));
    let dog = DogInnerStar::<T>::new();
    g.bench_function(
        BenchmarkId::new("dog_inner_value_jacobian", precision),
        |b| {
            b.iter(|| {
                inner
                    .iter()
                    .map(|x| (dog.value(x), dog.jacobian(x)))
                    .map(black_box)
                    .count()
            })
        },
    );
    g.bench_function(
        BenchmarkId::new("dog_inner_constraint_hessian", precision),
        |b| {
            b.iter(|| {
                inner
                    .iter()
                    .map(|x| dog.hessian(x, &lambda))
                    .map(black_box)
                    .count()
            })
        },
    );
    let remedy = FlatStarRemedy::<T>::default();
    g.bench_function(
        BenchmarkId::new("dog_inner_remedied_jacobian", precision),
        |b| {
            b.iter(|| {
                inner
                    .iter()
                    .map(|x| remedy.inner_jacobian(x))
                    .map(black_box)
                    .count()
            })
        },
    );
    let lap = dog_laplacian::inner([one; 4]).expect("unit rest lengths");
    g.bench_function(BenchmarkId::new("dog_laplacian_gradient", precision), |b| {
        b.iter(|| inner.iter().map(|x| lap.gradient(x)).map(black_box).count())
    });
    let curve = curve_laplacian::new([one, one]).expect("unit rest lengths");
    g.bench_function(
        BenchmarkId::new("curve_laplacian_gradient", precision),
        |b| {
            b.iter(|| {
                triples
                    .iter()
                    .map(|x| curve.gradient(x))
                    .map(black_box)
                    .count()
            })
        },
    );
    let iso = Iso3d::new(one).expect("unit rest length");
    g.bench_function(BenchmarkId::new("iso3d_gradient_hessian", precision), |b| {
        b.iter(|| {
            edges
                .iter()
                .map(|x| (iso.gradient(x), iso.hessian(x)))
                .map(black_box)
                .count()
        })
    });
    let glue = Glue::<T>::new();
    g.bench_function(BenchmarkId::new("glue_gradient_hessian", precision), |b| {
        b.iter(|| {
            quads
                .iter()
                .map(|x| (glue.gradient(x), glue.hessian(x)))
                .map(black_box)
                .count()
        })
    });
    let spring = Spring::new(one, one).expect("unit spring");
    g.bench_function(BenchmarkId::new("spring_force_jacobian", precision), |b| {
        b.iter(|| {
            edges
                .iter()
                .map(|x| (spring.force(x), spring.force_jacobian(x)))
                .map(black_box)
                .count()
        })
    });
    g.finish();
}

fn kernels(c: &mut Criterion) {
    per_precision::<f32>(c, "f32");
    per_precision::<f64>(c, "f64");
}

/// The batched cone map vs the seed's scalar loop on a 64 x 64 grid (vertices per second).
fn cone(c: &mut Criterion) {
    const N: usize = 64;
    let (theta, apex, rho) = (0.7, -6.0, 0.9);
    let mut g = c.benchmark_group("cone_map");
    g.throughput(Throughput::Elements((N * N) as u64));

    let (xs, ys) = page_grid::<f32>(N);
    let curl = ConeCurl::<f32>::new(theta as f32, apex as f32, rho as f32);
    let (mut ox, mut oy, mut oz) = (vec![0.0; N * N], vec![0.0; N * N], vec![0.0; N * N]);
    g.bench_function(BenchmarkId::new("batched", "f32"), |b| {
        b.iter(|| curl.map_batch(&mut ox, &mut oy, &mut oz, black_box(&xs), black_box(&ys)))
    });
    let mut aos = vec![[0.0f32; 3]; N * N];
    g.bench_function(BenchmarkId::new("seed_scalar_loop", "f32"), |b| {
        b.iter(|| {
            seed_cone_loop_f32(
                &mut aos,
                black_box(&xs),
                black_box(&ys),
                theta as f32,
                apex as f32,
                rho as f32,
            )
        })
    });

    let (xs, ys) = page_grid::<f64>(N);
    let curl = ConeCurl::<f64>::new(theta, apex, rho);
    let (mut ox, mut oy, mut oz) = (vec![0.0; N * N], vec![0.0; N * N], vec![0.0; N * N]);
    g.bench_function(BenchmarkId::new("batched", "f64"), |b| {
        b.iter(|| curl.map_batch(&mut ox, &mut oy, &mut oz, black_box(&xs), black_box(&ys)))
    });
    let mut aos = vec![[0.0f64; 3]; N * N];
    g.bench_function(BenchmarkId::new("seed_scalar_loop", "f64"), |b| {
        b.iter(|| seed_cone_loop_f64(&mut aos, black_box(&xs), black_box(&ys), theta, apex, rho))
    });
    g.finish();
}

criterion_group!(benches, kernels, cone);
criterion_main!(benches);
