//! Measuring what a scheme buys: scenes, single runs, dt sweeps, critical step sizes,
//! efficiency, and their reports (algorithms.md sections 6 to 8).
//!
//! Units are the reduced DPD units of `dpd-core`; times are in those units, except wall-clock
//! costs, which are in milliseconds per step and cover the integration only.
//!
//! From the bottom: a [`scene`] (sections that read and check their own keys) builds the
//! system; [`runner::run`] steps it once, sampled by the [`observer`]s the scene switches on,
//! into a [`RunResult`]; a [`batch::Batch`] runs many jobs of one scene in parallel and saves
//! after each; [`sweep`] plans a dt grid, runs it as a batch and summarises it (with
//! [`aggregate`], [`critical`]); [`report`] and [`plot`] print and draw it; [`paper`] compares
//! runs with published tables; [`kl`] estimates a KL divergence from shadow work.

pub mod aggregate;
pub mod batch;
pub mod chains;
pub mod cost;
pub mod critical;
pub mod data_bonds;
pub mod data_file;
pub mod images;
pub mod kl;
pub mod observer;
pub mod pair_coefficients;
pub mod paper;
pub mod plot;
pub mod report;
pub mod result;
pub mod runner;
pub mod scene;
pub mod start;
pub mod sweep;

pub use aggregate::Aggregate;
pub use batch::Batch;
pub use critical::{critical_dt, Critical};
pub use result::{ChainSizes, Job, RunResult, Viscosity};
pub use runner::{run, Control};
pub use scene::{Keys, Observable, Scene, SceneError};
pub use sweep::{SchemeSummary, SweepResults};
