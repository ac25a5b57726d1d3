//! The command-line program's tests, one module per command or topic, in one test binary: one link
//! of the crate and its dependencies, and generic code instantiated once rather than once per file
//! (the files were separate binaries until 2026-12-07: CI time). The files keep their paths under
//! `tests/`.

mod cli_support;

mod cli_check;
mod cli_design;
mod cli_docs;
mod cli_flows;
mod cli_kl;
mod cli_pipe;
mod cli_predict;
mod cli_reproduce;
mod cli_run;
mod cli_sweep;
