//! Core of dpd: the state of a dissipative-particle-dynamics system, neighbour search, pair
//! random numbers, the exact and explicit sub-flows that splitting schemes are built from,
//! observables and checkpoints.
//!
//! Conventions used throughout (see `docs/algorithms.md` in the repository):
//! - Reduced DPD units: lengths in units of the cutoff's unit, energies in units of k_B T's unit,
//!   masses in the unit of the particle mass. Nothing is rescaled internally.
//! - `q` positions (wrapped into the periodic box), `p` momenta, `m` masses; for a pair
//!   `q_ij = q_i - q_j` under minimum image, `e_ij = q_ij / r_ij` points from j to i.
//! - A sub-flow advances the state by a step length `h = c * dt`.
//! - Shear ([`LeesEdwards`]): flow along x, gradient along y; a pair across the sliding
//!   boundary carries the image's velocity shift in [`pairs::PairTable::shifts`].
//! - Pairwise sweeps visit the interacting pairs in one documented order, colour by colour of
//!   a colouring of units of cells (see [`neighbour`]), or exactly that order reversed. The
//!   order does not depend on the thread count; units of one colour are processed in parallel.

mod avx2;
pub mod bonded;
pub mod boundary;
pub mod checkpoint;
pub mod chunked;
mod disjoint;
pub mod error;
pub mod flow;
pub mod force;
pub mod init;
mod lanes;
pub mod metropolis;
pub mod neighbour;
pub mod observe;
pub mod pairs;
mod parallel;
pub mod params;
pub mod potential;
pub mod reference;
pub mod rng;
pub mod scheme;
mod stamp;
pub mod system;
pub mod walls;

#[doc(hidden)]
pub mod __private;

/// `f()` on a rayon pool of `threads` threads: unit tests compare one thread with several.
#[cfg(test)]
pub(crate) fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

pub use bonded::Topology;
pub use boundary::{LeesEdwards, PeriodicBox};
pub use dpd_ir::{Flow, ForceGroup, Stage, SweepOrder};
pub use error::{AdvanceError, BlowUp, CheckpointError, ParamError};
pub use params::Params;
pub use scheme::{DynScheme, Scheme};
pub use system::{Acceptance, System, SystemBuilder};
pub use walls::Walls;

/// Three-vector of `f64`, the type of positions, momenta and forces.
pub type Vec3 = nalgebra::Vector3<f64>;

/// The components of `v` as one slice, `[x_0, y_0, z_0, x_1, ...]`: loops over it vectorise
/// where loops over the vectors do not.
pub(crate) fn components(v: &[Vec3]) -> &[f64] {
    bytemuck::cast_slice(v)
}

/// [`components`], mutable.
pub(crate) fn components_mut(v: &mut [Vec3]) -> &mut [f64] {
    bytemuck::cast_slice_mut(v)
}

/// 3 x 3 matrix of `f64`, the type of stress and virial tensors (row index: position
/// component, column index: force component).
pub type Tensor = nalgebra::Matrix3<f64>;
