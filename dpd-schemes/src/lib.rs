//! The named DPD integrators of the literature, each one item with its sequence and source,
//! and the [`registry`] that finds them by name.
//!
//! Splitting schemes are written in the scheme language and compiled by `dpd_scheme!`; the
//! methods that are not splittings of exact flows (Groot-Warren with a general lambda, SETD,
//! MSETD) are written by hand on the core sub-flows behind the same `Scheme` trait.
//!
//! What each scheme claims (evaluations per step, deterministic and invariant-measure order,
//! symmetry, consistency, momentum conservation) is written once, in its [`registry`] entry,
//! and listed by `dpd schemes`. `tests/claims.rs` checks every claim: against the order
//! analysis of the scheme's program and the evaluation counters for splitting schemes, against
//! the counters and the measured convergence at `gamma = 0` for hand-written ones.
//!
//! | module | schemes |
//! |---|---|
//! | [`verlet`] | velocity Verlet (`vv`), Groot-Warren with general lambda (`gw-0.65`) |
//! | [`shardlow`] | DPD-S1, DPD-S2, M-Shardlow-1 (inconsistent, as published), M-Shardlow-2 |
//! | [`langevin`] | ABOBA, BAOAB, BAOOAB, OBABO with exact pairwise O |
//! | [`trotter`] | SAS (DPD-Trotter, `TAT`), ASA (`ATA`) |
//! | [`prk`] | PRK3 Ruth, Iwatsu A and B (frozen noise); Ruth's sequence with exact O |
//! | [`composition`] | Yoshida's triple jump composed symmetrically with exact O |
//! | [`exponential`] | SETD, MSETD for small masses |
//! | [`lowe`] | Lowe-Andersen collisions: Lowe's velocity Verlet + L, the ABOBA ordering ABLBA |
//! | [`adaptive`] | the pairwise adaptive Langevin thermostat (PAdL) in the BAOAB and ABOBA orderings, the pairwise Nose-Hoover-Langevin thermostat (PNHL) in the BAOAB one |
//! | [`peters`] | Peters' scheme: velocity Verlet, then Peters' pair thermostat (= the O sweep) |
//! | [`adjusted`] | Metropolis-adjusted (generalised hybrid Monte Carlo): velocity Verlet in braces, then O |
//!
//! [`check`] reports the analysis of a registry name or a scheme string (`dpd check`).
//! [`stability`] runs every registered scheme over a matrix of friction, mass and time step.
//!
//! Not included: the second-order SETD of the same source. It needs the previous step's
//! acceleration, state that `dpd_core::System` does not carry between steps (nor write to a
//! checkpoint), so it could not restart exactly.

pub mod adaptive;
pub mod adjusted;
pub mod check;
pub mod composition;
pub mod exponential;
pub mod langevin;
pub mod lowe;
pub mod peters;
pub mod prk;
pub mod registry;
pub mod shardlow;
pub mod stability;
pub mod trotter;
pub mod verlet;

pub use registry::{entries, lookup, resolve, Entry, ResolveError, UnknownScheme};
