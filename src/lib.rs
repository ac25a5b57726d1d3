//! dpd: compose, check and run splitting integrators for dissipative particle dynamics.
//!
//! - [`dpd_scheme!`] turns a scheme string into a step function specialised at compile time;
//!   the language is documented in [`lang`].
//! - [`analysis`] checks consistency, deterministic order and the invariant-measure order bound.
//! - [`schemes`] holds the named schemes of the literature and their registry.
//! - The core ([`System`], sub-flows in [`flow`], observables in [`observe`], checkpoints) comes
//!   from `dpd-core`.
//!
//! The formulas are in `docs/algorithms.md` of the repository.
//!
//! A quick start (build the standard box, step it with a `dpd_scheme!`, read the temperatures)
//! is `examples/quick_start.rs`, shown in README.md and run by `tests/readme.rs`.

pub use dpd_core::{
    bonded, boundary, checkpoint, error, flow, init, metropolis, neighbour, observe, pairs, params,
    reference, rng, scheme, system, Acceptance, AdvanceError, BlowUp, CheckpointError, DynScheme,
    Flow, ForceGroup, ParamError, Params, PeriodicBox, Scheme, Stage, SweepOrder, System,
    SystemBuilder, Vec3,
};
pub use dpd_ir::{analysis, design, lang, program, Analysis, Program};
#[doc = include_str!("dpd_scheme.md")]
pub use dpd_macros::dpd_scheme;
pub use dpd_schemes as schemes;

#[doc(hidden)]
pub use dpd_core::__private;
