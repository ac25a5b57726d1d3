//! The `dpd_scheme!` procedural macro (work in progress).

use proc_macro::TokenStream;

/// Placeholder until the macro lands.
#[proc_macro]
pub fn dpd_scheme(_input: TokenStream) -> TokenStream {
    TokenStream::new()
}
