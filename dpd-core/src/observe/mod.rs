//! Observables of algorithms.md section 6, measured on the state at the end of a full step.
//!
//! Measuring may evaluate the pair geometry and conservative forces at the current positions
//! (for ABOBA those are not otherwise needed at the end of a step, so sample every k steps);
//! it never changes the trajectory.

mod average;
mod rdf;
mod thermo;
mod vacf;

pub use average::{Running, ThermoAverages, ThermoSummary};
pub use rdf::Rdf;
pub use thermo::{kinetic_temperature, thermo, Thermo};
pub use vacf::Vacf;
