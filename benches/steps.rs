//! Cost of one step of the main schemes at N = 500, 24 000 and 192 000 (density 3, a = 25,
//! gamma = 4.5, dt = 0.04, neighbour skin 0), on 1 thread and on 2; criterion reports
//! particle-steps per second (throughput), so ns per particle-step is its inverse.
//!
//! `cargo bench -p dpd-benches --bench steps`; results in docs/performance.md.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dpd::init::equilibrium_box;
use dpd::{Params, Scheme, System};
use std::time::Duration;

const SCHEMES: [&str; 5] = ["vv", "dpd-s1", "aboba", "baoab", "prk3-ruth"];

/// The equilibrium box of `n` particles, relaxed from its random start.
fn relaxed(n: usize, scheme: &dyn Scheme) -> System {
    let mut sys = equilibrium_box(Params::builder().build().unwrap(), n, 3.0, 1)
        .unwrap()
        .dt(0.04)
        .skin(0.0)
        .build()
        .unwrap();
    sys.advance(scheme, 20).unwrap();
    sys
}

fn steps(c: &mut Criterion) {
    for (n, threads) in [(500, &[1][..]), (24_000, &[1, 2]), (192_000, &[1, 2])] {
        let mut group = c.benchmark_group(format!("n={n}"));
        group.throughput(Throughput::Elements(n as u64));
        if n > 10_000 {
            group
                .sample_size(10)
                .measurement_time(Duration::from_secs(8));
        }
        for name in SCHEMES {
            let scheme = dpd::schemes::lookup(name).unwrap().scheme();
            for &t in threads {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .unwrap();
                let mut sys = pool.install(|| relaxed(n, &*scheme));
                group.bench_function(format!("scheme/{name}/threads={t}"), |b| {
                    b.iter(|| pool.install(|| sys.advance(&*scheme, 1).unwrap()))
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, steps);
criterion_main!(benches);
