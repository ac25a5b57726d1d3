//! The core's integration tests, one module per topic, in one test binary: one link of the crate
//! and its dependencies, and generic code instantiated once rather than once per file (the files
//! were separate binaries until 2026-12-07: CI time). The files keep their paths under `tests/`.

mod common;

mod adaptive;
mod blowup;
mod bonded_thermo;
mod bonds;
mod builder;
mod config_temperature;
mod determinism;
mod equilibrium;
mod exclusion;
mod lees_edwards;
mod lowe_andersen;
mod metropolis;
mod momentum;
mod ou_stationary;
mod reference;
mod restart;
mod type_pairs;
mod walls;
