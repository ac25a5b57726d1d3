//! The `dpd_scheme!` procedural macro: compiles a splitting scheme, written in the scheme
//! language of `dpd_ir::lang`, into a step function specialised at compile time. Users call it
//! as `dpd::dpd_scheme!`, where its documentation and examples are (`src/dpd_scheme.md` of the
//! `dpd` crate, whose doc tests and trybuild cases exercise it: a dev-dependency on `dpd` here
//! would build `dpd` and its dependency graph a second time, for the host, as a proc-macro
//! crate's tests are).
//!
//! # Pipeline
//!
//! `parse` reads the input (`args` the options, from one table), compiles the scheme with
//! `dpd_ir::compile_with` and places every diagnostic on the literal; `valid` checks the order
//! assertions; `expand` writes the scheme type; on any error `fallback` writes the error and a
//! stub. `runtime` finds the path of the run time.

mod args;
mod expand;
mod fallback;
mod parse;
mod runtime;
mod valid;

use proc_macro::TokenStream;

/// Compiles a splitting scheme into a step function specialised at compile time: see
/// `dpd::dpd_scheme!` for the syntax, the options and examples.
#[proc_macro]
pub fn dpd_scheme(input: TokenStream) -> TokenStream {
    let rt = match runtime::path() {
        Ok(rt) => rt,
        Err(e) => return e.to_compile_error().into(),
    };
    syn::parse::<parse::Input>(input)
        .and_then(|input| expand::expand(&input, &rt))
        .unwrap_or_else(|e| fallback::expand(&rt, e))
        .into()
}

#[cfg(test)]
mod tests {
    #[test]
    fn docs_list_every_option() {
        let docs = include_str!("../../src/dpd_scheme.md");
        for o in crate::args::OPTIONS {
            let row = format!("| `{}` | {} |", o.syntax, o.meaning);
            assert!(docs.contains(&row), "missing docs row {row}");
        }
    }
}
