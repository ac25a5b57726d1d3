//! The options after the scheme string, and the one table that names them.

use proc_macro2::TokenStream;
use quote::quote;
use syn::parse::ParseStream;
use syn::{Ident, LitInt, LitStr, Token};

/// What an option sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    Name,
    AllowInconsistent,
    Order,
    InvariantOrder,
}

/// An option of `dpd_scheme!`: its keyword, how it is written and what it does.
pub struct Opt {
    pub key: Key,
    pub keyword: &'static str,
    pub syntax: &'static str,
    pub meaning: &'static str,
}

/// Every option. The crate docs list the same rows (checked by a test) and messages quote the
/// syntax column.
pub const OPTIONS: [Opt; 4] = [
    Opt {
        key: Key::Name,
        keyword: "name",
        syntax: "name = \"...\"",
        meaning: "the name `Scheme::name` returns (default: the scheme source)",
    },
    Opt {
        key: Key::AllowInconsistent,
        keyword: "allow_inconsistent",
        syntax: "allow_inconsistent",
        meaning: "accept coefficient sums other than 1 (e.g. M-Shardlow-1 as published)",
    },
    Opt {
        key: Key::Order,
        keyword: "order",
        syntax: "order >= N",
        meaning: "assert that the Hamiltonian part has deterministic order at least N (1..=12)",
    },
    Opt {
        key: Key::InvariantOrder,
        keyword: "invariant_order",
        syntax: "invariant_order >= N",
        meaning: "assert that the invariant-measure order bound is at least N (1..=5)",
    },
];

/// Largest `N` of `order >= N`: the highest degree the order analysis compares.
pub const MAX_ORDER: u32 = 12;
/// Largest `N` of `invariant_order >= N`: the highest `L_n` the analysis checks.
pub const MAX_INVARIANT_ORDER: u32 = 5;

/// A lower bound `keyword >= N`, with its tokens for messages about it.
pub struct Bound {
    pub min: u32,
    pub tokens: TokenStream,
}

/// The options given after the scheme string.
#[derive(Default)]
pub struct Args {
    pub name: Option<LitStr>,
    pub allow_inconsistent: bool,
    pub order: Option<Bound>,
    pub invariant_order: Option<Bound>,
}

impl Args {
    /// Parses one option into `self`.
    pub fn parse_option(&mut self, input: ParseStream) -> syn::Result<()> {
        let keyword: Ident = input.parse().map_err(|e| {
            syn::Error::new(
                e.span(),
                format!("expected an option; the options are:{}", option_list()),
            )
        })?;
        let Some(opt) = OPTIONS.iter().find(|o| keyword == o.keyword) else {
            return Err(syn::Error::new(
                keyword.span(),
                format!(
                    "unknown option `{keyword}`; the options are:{}",
                    option_list()
                ),
            ));
        };
        let given_twice = || syn::Error::new(keyword.span(), format!("`{keyword}` given twice"));
        match opt.key {
            Key::Name => {
                input.parse::<Token![=]>().map_err(|e| expected(opt, e))?;
                let name: LitStr = input.parse().map_err(|e| expected(opt, e))?;
                if name.value().is_empty() {
                    return Err(syn::Error::new(name.span(), "the name must not be empty"));
                }
                self.name
                    .replace(name)
                    .map_or(Ok(()), |_| Err(given_twice()))
            }
            Key::AllowInconsistent => {
                if input.peek(Token![=]) {
                    return Err(syn::Error::new(
                        input.span(),
                        "`allow_inconsistent` is a flag: write it alone, without a value",
                    ));
                }
                if std::mem::replace(&mut self.allow_inconsistent, true) {
                    return Err(given_twice());
                }
                Ok(())
            }
            Key::Order | Key::InvariantOrder => {
                let (slot, max) = match opt.key {
                    Key::Order => (&mut self.order, MAX_ORDER),
                    _ => (&mut self.invariant_order, MAX_INVARIANT_ORDER),
                };
                let bound = parse_bound(input, opt, &keyword, max)?;
                slot.replace(bound).map_or(Ok(()), |_| Err(given_twice()))
            }
        }
    }
}

/// `>= N` after `keyword`, with `1 <= N <= max`.
fn parse_bound(input: ParseStream, opt: &Opt, keyword: &Ident, max: u32) -> syn::Result<Bound> {
    let ge: Token![>=] = input.parse().map_err(|e| expected(opt, e))?;
    let n: LitInt = input.parse().map_err(|e| expected(opt, e))?;
    let min = n
        .base10_parse::<u32>()
        .ok()
        .filter(|m| (1..=max).contains(m))
        .ok_or_else(|| {
            syn::Error::new(
                n.span(),
                format!("`{keyword} >= {n}`: N must be an integer from 1 to {max}, the highest order the analysis checks"),
            )
        })?;
    Ok(Bound {
        min,
        tokens: quote!(#keyword #ge #n),
    })
}

/// The error for an option written wrongly: what was found and how to write it.
fn expected(opt: &Opt, found: syn::Error) -> syn::Error {
    syn::Error::new(found.span(), format!("{found}; write `{}`", opt.syntax))
}

/// Every option, one a line with its meaning, for messages.
fn option_list() -> String {
    OPTIONS
        .iter()
        .map(|o| format!("\n  {:<22} {}", o.syntax, o.meaning))
        .collect()
}
