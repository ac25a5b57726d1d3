//! The catalogue's integration tests, one module per topic, in one test binary: one link of the
//! crate and its dependencies, and generic code instantiated once rather than once per file (the
//! files were separate binaries until 2026-12-07: CI time). The files keep their paths under
//! `tests/`.

mod common;

mod claims;
mod exponential_flows;
mod low_mass;
mod momentum;
mod peters;
mod registry;
mod stability;
mod temperature;
mod weak_order;
