//! Predicting a scheme's accuracy before running it (issue 49).
//!
//! Every sub-flow of the scheme language is linear on a harmonic system: A and B exactly, O,
//! Ob and T as affine maps with Gaussian noise, F with its noise frozen within an evaluation.
//! A compiled [`Program`](dpd_ir::Program) therefore steps a harmonic mode by a linear map
//! plus Gaussian noise, and its exact stationary covariance solves a discrete Lyapunov
//! equation ([`stationary`]). Weighted over the fluid's harmonic modes ([`Spectrum`], from a
//! configuration's pair network), this gives the scheme's errors of the configurational and
//! kinetic temperatures, the potential energy and the pressure at any dt, its stability limit
//! (spectral radius one) and its critical steps ([`predict`]), in milliseconds. The
//! configurational temperature adds the leading anharmonic correction ([`anharmonic`]): how
//! the scheme's weights of the modes bias the pairs inside the cut-off, with T_C's response
//! to them measured on equilibrium configurations.
//!
//! The crate needs the IR and linear algebra, not the engine: the configuration a spectrum is
//! built from comes from the caller (the `dpd` program samples it from the scene).
//! docs/design.md measures how well the predictions rank measured errors.

pub mod anharmonic;
pub mod design;
pub mod network;
pub mod predict;
pub mod spectrum;
pub mod stationary;
pub mod step_map;

pub use network::PairModel;
pub use predict::{Critical, Errors, Prediction, Predictor, Row};
pub use spectrum::{Mode, Spectrum};
pub use stationary::{stationary_covariance, Stationary};
pub use step_map::{ForcePoint, StepMap, StepMapError};
