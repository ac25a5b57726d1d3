//! Observables of algorithms.md section 6, measured on the state at the end of a full step.
//!
//! Measuring may evaluate the pair geometry and conservative forces at the current positions
//! (for ABOBA those are not otherwise needed at the end of a step, so sample every k steps);
//! it never changes the trajectory.

mod average;
mod energy;
mod profile;
mod rdf;
mod stress;
mod thermo;
mod vacf;

pub use average::{block_mean, block_ratio_error, Running, ThermoAverages, ThermoSummary};
pub use energy::{balance_defined, hamiltonian, potential_energy, Balance, EnergyBalance};
pub use profile::{fit_line, write_profile_csv, Profile, ProfileRow};
pub use rdf::Rdf;
pub use stress::{
    state_dissipative_stress, stop_recording, stress, ShearViscosity, Stress, ViscositySummary,
    VISCOSITY_BLOCKS,
};
pub use thermo::{kinetic_temperature, processed_thermo, thermo, Thermo};
pub use vacf::Vacf;

use crate::pairs::Pair;
use crate::potential::Soft;
use crate::system::System;

/// `sum_pairs term(soft_ij, pair)` over the interacting pairs at the current positions, with
/// each pair's repulsion (without moving the neighbour-list rebuilds, see
/// `System::with_forces`).
fn pair_sum<T: std::iter::Sum>(sys: &mut System, term: impl Fn(Soft, &Pair) -> T) -> T {
    sys.with_forces(|sys, pairs, _| pairs.sum_soft(sys.params(), sys.kinds(), term))
}
