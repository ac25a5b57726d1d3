//! The path through which generated code reaches the run time: `__private` of `dpd` when the
//! calling crate depends on it, else of `dpd-core` (which `dpd-schemes` uses, as it cannot
//! depend on `dpd`), `crate::__private` inside either crate's library.

use proc_macro2::{Span, TokenStream};
use proc_macro_crate::{crate_name, Error, FoundCrate};
use quote::quote;
use syn::Ident;

/// Packages that re-export the run time as `__private`, preferred first.
const RUNTIME_PACKAGES: [&str; 2] = ["dpd", "dpd-core"];

/// `::dpd::__private`, `::dpd_core::__private` or `crate::__private`, read from the calling
/// crate's `Cargo.toml` (renamed dependencies included).
pub fn path() -> syn::Result<TokenStream> {
    for package in RUNTIME_PACKAGES {
        match crate_name(package) {
            Ok(FoundCrate::Itself) if compiling_library(package) => {
                return Ok(quote!(crate::__private))
            }
            Ok(FoundCrate::Itself) => return Ok(extern_path(&package.replace('-', "_"))),
            Ok(FoundCrate::Name(name)) => return Ok(extern_path(&name)),
            Err(Error::CrateNotFound { .. }) => continue,
            Err(e) => {
                return Err(syn::Error::new(
                    Span::call_site(),
                    format!("dpd_scheme! cannot find the crate `dpd` among the dependencies: {e}"),
                ))
            }
        }
    }
    Err(syn::Error::new(
        Span::call_site(),
        "dpd_scheme! needs the crate `dpd` (or `dpd-core`) as a dependency of this crate",
    ))
}

fn extern_path(name: &str) -> TokenStream {
    let name = Ident::new(name, Span::call_site());
    quote!(::#name::__private)
}

/// Whether rustc is compiling the library of `package` (not one of its binaries, examples,
/// tests or doc tests, which reach the library by name). Cargo sets these variables for rustc,
/// and rustdoc sets `UNSTABLE_RUSTDOC_TEST_PATH` when it compiles a doc test (whose
/// `CARGO_CRATE_NAME` is still the library's), so the macro sees them.
fn compiling_library(package: &str) -> bool {
    std::env::var_os("CARGO_BIN_NAME").is_none()
        && std::env::var_os("UNSTABLE_RUSTDOC_TEST_PATH").is_none()
        && std::env::var("CARGO_CRATE_NAME").is_ok_and(|c| c == package.replace('-', "_"))
}
