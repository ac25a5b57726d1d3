//! Heap bytes per particle of a running system, split into the pair list and the rest.
//!
//! A counting global allocator records the bytes held after a few steps of velocity Verlet and
//! ABOBA on the equilibrium box (density 3, a = 25, gamma = 4.5, dt = 0.04, skin 0). The pair
//! list is the interacting pairs (`size_of::<Pair>()` each; with skin 0 the Verlet list keeps
//! no candidates); its spare capacity counts as "without the pair list", as do the per-thread
//! scratch buffers (the stencil of a cell, the normals of the run a noisy pass is at).
//!
//! Usage: `cargo run --release -p dpd --example memory -- N`

use dpd::init::equilibrium_box;
use dpd::pairs::Pair;
use dpd::reference::{Aboba, VelocityVerlet};
use dpd::{Params, Scheme};
use std::alloc::{GlobalAlloc, Layout, System as Heap};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the bytes currently held.
struct Counting;

static HELD: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        HELD.fetch_add(layout.size(), Ordering::Relaxed);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { Heap.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        HELD.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { Heap.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = match std::env::args().nth(1) {
        None => 24_000,
        Some(s) => s
            .parse()
            .map_err(|_| format!("N = {s:?} is not a particle count"))?,
    };
    for scheme in [&VelocityVerlet as &dyn Scheme, &Aboba] {
        let before = HELD.load(Ordering::Relaxed);
        let params = Params::builder().build()?;
        let mut sys = equilibrium_box(params, n, 3.0, 1)?
            .dt(0.04)
            .skin(0.0)
            .build()?;
        sys.advance(scheme, 5)?;
        let held = HELD.load(Ordering::Relaxed) - before;
        let pairs = sys.pairs().len();
        // With skin 0 the list keeps no candidates: the pair list is the pair table.
        let pair_list = pairs * std::mem::size_of::<Pair>();
        println!(
            "{{\"scheme\": \"{}\", \"n\": {n}, \"heap_bytes\": {held}, \"pairs\": {pairs}, \"pair_list_bytes\": {pair_list}, \"bytes_per_particle_without_pair_list\": {:.1}}}",
            scheme.name(),
            (held.saturating_sub(pair_list)) as f64 / n as f64
        );
    }
    Ok(())
}
