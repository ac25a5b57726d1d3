//! What the macro expands to on error: the error, plus a stub scheme so that the code using
//! the value still type-checks and the user sees one message, not a cascade.

use proc_macro2::TokenStream;
use quote::quote;

use crate::expand::scheme_value;

/// `error` as `compile_error!`s, and a value of a type implementing `Scheme` whose methods
/// are never run (compilation stops at the error).
pub fn expand(rt: &TokenStream, error: syn::Error) -> TokenStream {
    let error = error.to_compile_error();
    let stub = scheme_value(
        rt,
        &quote! {
            fn name(&self) -> &str {
                ::core::unreachable!()
            }
            fn step(&self, _: &mut #rt::System) {
                ::core::unreachable!()
            }
        },
    );
    quote!({
        #error
        #stub
    })
}

/// All of `errors` as one, reported together; `None` if there are none.
pub fn combine(errors: impl IntoIterator<Item = syn::Error>) -> Option<syn::Error> {
    errors.into_iter().reduce(|mut all, e| {
        all.combine(e);
        all
    })
}
