//! The language's and the analysis' integration tests, one module per topic, in one test binary:
//! one link of the crate and its dependencies, and generic code instantiated once rather than once
//! per file (the files were separate binaries until 2026-12-07: CI time). The files keep their
//! paths under `tests/`.

mod analysis;
mod design;
mod groups;
mod lang;
mod typed_coefficients;
