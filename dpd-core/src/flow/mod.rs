//! The sub-flows of algorithms.md section 2, each a plain function of the system and a step
//! length `h = c * dt`.
//!
//! | letter | function | update |
//! |---|---|---|
//! | A | [`drift`] | `q_i += h p_i / m_i` (exact) |
//! | B | [`kick`] | `p_i += h F^C_i(q)` (exact) |
//! | O | [`ou`] | pairwise Ornstein-Uhlenbeck, exact in distribution per pair |
//! | O-BBK | [`bbk`] | Shardlow's pair update, weakly second order |
//! | T | [`trotter`] | pairwise conservative + OU, exact per pair |
//! | F | [`full_force`] | `p_i += h F_i` with the full DPD force (explicit) |
//!
//! The pairwise sweeps (O, O-BBK, T) visit the interacting pairs successively in the core's
//! documented order, `(i, j)` ascending for [`SweepOrder::Forward`] and descending for
//! [`SweepOrder::Reverse`]; each pair sees the momenta already updated by earlier pairs and
//! draws one standard normal keyed by `(seed, step, stream, i, j)`. All of them change the two
//! momenta by equal and opposite amounts, so total momentum is conserved to rounding error.
//!
//! A, B and F accept any sign of `h`. The stochastic sweeps have no backward-in-time version:
//! for `h < 0` they apply only their deterministic part (no noise); schemes never do this, the
//! scheme language rejects it.
//!
//! Not a letter of the scheme language: [`exponential_velocity`], the per-particle
//! exponential-time-differencing velocity update of SETD and MSETD (algorithms.md section 5),
//! for the hand-written schemes of `dpd-schemes`.

mod drift;
mod exponential;
mod kick;
mod pair_sweep;

pub use drift::drift;
pub use exponential::{exponential_velocity, EtdNoise};
pub use kick::{full_force, kick};
pub use pair_sweep::{bbk, ou, trotter};

pub use dpd_ir::SweepOrder;
