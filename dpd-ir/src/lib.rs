//! The splitting-scheme language of dpd: parser, intermediate representation and order
//! analysis. Dependency-light on purpose: the `dpd_scheme!` macro runs this code at expansion
//! time, and the run-time crates use the same code for schemes given as strings.

pub mod analysis;
pub mod design;
pub mod forces;
pub mod lang;
pub mod program;

pub use analysis::{analyse, Analysis};
pub use forces::ForceGroup;
pub use lang::{compile, compile_with, Diagnostic, Options};
pub use program::{Coeff, Evaluations, Flow, Program, Stage, SweepOrder};
