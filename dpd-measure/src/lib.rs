//! Measuring what a scheme buys: scenes, single runs, dt sweeps, critical step sizes,
//! efficiency, and their reports (algorithms.md sections 6 to 8).
//!
//! Units are the reduced DPD units of `dpd-core`; times are in those units, except wall-clock
//! costs, which are in milliseconds per step and cover the integration only.

pub mod aggregate;
pub mod critical;
pub mod flows;
pub mod images;
pub mod kl;
pub mod paper;
pub mod plot;
pub mod report;
pub mod runner;
pub mod scene;
pub mod sweep;
pub mod trajectory;

pub use aggregate::Aggregate;
pub use critical::{critical_dt, Critical};
pub use runner::{run, Control, RunResult};
pub use scene::{Observable, Overrides, Scene, SceneError, SchemeList, SweepOverrides};
pub use sweep::{SchemeSummary, SweepResults};
