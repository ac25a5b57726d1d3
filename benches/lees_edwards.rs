//! What the Lees-Edwards code costs: one step of ABOBA (O sweep, conservative kicks, drifts)
//! and of velocity Verlet (full-force F kicks) on the equilibrium box of N = 24 000 (density 3,
//! a = 25, gamma = 4.5, dt = 0.04, default skin 0), on one thread, in three boundaries:
//! - `periodic`: no shear; the sweeps, drifts and neighbour search take their periodic paths;
//! - `lees-edwards/kappa=0`: the sliding-boundary paths with a zero shear rate (bitwise the
//!   periodic trajectory), i.e. the cost of the code itself;
//! - `lees-edwards/kappa=0.2`: a real shear (the images slide out of alignment, the rebuild
//!   test allows for the slide, crossing pairs are swept sequentially).
//!
//! `cargo bench -p dpd-benches --bench lees_edwards`; results in docs/performance.md.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dpd::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd::reference::{Aboba, VelocityVerlet};
use dpd::{Params, Scheme, System};
use std::time::Duration;

const N: usize = 24_000;

/// The equilibrium box, relaxed from its random start, sheared at `kappa` (`None`: periodic).
fn relaxed(kappa: Option<f64>, scheme: &dyn Scheme) -> System {
    let bx = cubic_box(N, 3.0).unwrap();
    let params = Params::builder().build().unwrap();
    let q = uniform_positions(&bx, N, 1);
    let p = maxwell_momenta(&vec![1.0; N], 1.0, 1);
    let builder = System::builder(params, bx, q).momenta(p).dt(0.04).seed(1);
    let mut sys = match kappa {
        Some(k) => builder.shear_rate(k),
        None => builder,
    }
    .build()
    .unwrap();
    sys.advance(scheme, 20).unwrap();
    sys
}

fn lees_edwards(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group(format!("n={N}"));
    group
        .throughput(Throughput::Elements(N as u64))
        .sample_size(20)
        .measurement_time(Duration::from_secs(10));
    let schemes: [(&str, &(dyn Scheme + Sync)); 2] = [("aboba", &Aboba), ("vv", &VelocityVerlet)];
    for (name, scheme) in schemes {
        for (boundary, kappa) in [
            ("periodic", None),
            ("lees-edwards/kappa=0", Some(0.0)),
            ("lees-edwards/kappa=0.2", Some(0.2)),
        ] {
            let mut sys = pool.install(|| relaxed(kappa, scheme));
            group.bench_function(format!("scheme/{name}/{boundary}"), |b| {
                b.iter(|| pool.install(|| sys.advance(scheme, 1).unwrap()))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, lees_edwards);
criterion_main!(benches);
