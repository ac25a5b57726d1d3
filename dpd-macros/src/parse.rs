//! The macro input, and the scheme compiled from it with every diagnostic placed on the string
//! literal.

use std::ops::Range;

use dpd_ir::{Diagnostic, Options, Program};
use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::{LitStr, Token};

use crate::args::Args;
use crate::fallback::combine;

/// `dpd_scheme!("source", options...)`.
pub struct Input {
    pub source: LitStr,
    pub args: Args,
}

impl Parse for Input {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let source: LitStr = input.parse().map_err(|e| {
            syn::Error::new(
                e.span(),
                "expected the scheme as a string literal, e.g. dpd_scheme!(\"ABOBA\"); the macro \
                 reads it at compile time (for a scheme known only at run time use \
                 DynScheme::compile)",
            )
        })?;
        let mut args = Args::default();
        while !input.is_empty() {
            input.parse::<Token![,]>().map_err(|e| {
                syn::Error::new(e.span(), "expected `,` between the scheme and the options")
            })?;
            if input.is_empty() {
                break;
            }
            args.parse_option(input)?;
        }
        Ok(Input { source, args })
    }
}

impl Input {
    /// Compiles the scheme as the run time will; every diagnostic becomes an error at the
    /// string literal.
    pub fn compile(&self) -> syn::Result<Program> {
        let src = self.source.value();
        let options = Options {
            allow_inconsistent: self.args.allow_inconsistent,
        };
        dpd_ir::compile_with(&src, &options).map_err(|diagnostics| {
            combine(diagnostics.iter().map(|d| self.error(&src, d))).unwrap_or_else(|| {
                syn::Error::new(self.source.span(), "the scheme failed to compile")
            })
        })
    }

    /// The error for `d`: at the bytes it is about where the compiler can point inside a
    /// literal (nightly), else at the whole literal, with the offending part quoted.
    fn error(&self, src: &str, d: &Diagnostic) -> syn::Error {
        let span = self
            .subspan(src, &d.span)
            .unwrap_or_else(|| self.source.span());
        syn::Error::new(span, d.render(src))
    }

    /// The span of `range` (bytes of the value) inside the literal token, when the literal
    /// holds the value verbatim (no escapes), so that value and token offsets differ by the
    /// opening quote only.
    fn subspan(&self, src: &str, range: &Range<usize>) -> Option<Span> {
        let token = self.source.token();
        let repr = token.to_string();
        let start = repr.find('"')? + 1;
        let verbatim = repr.get(start..start + src.len()) == Some(src)
            && repr[start + src.len()..].trim_start_matches('#') == "\"";
        verbatim.then_some(())?;
        token.subspan(start + range.start..start + range.end)
    }
}
