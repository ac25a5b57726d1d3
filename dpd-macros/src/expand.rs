//! The generated scheme: a zero-sized type whose `step` calls the sub-flows in a straight line.

use dpd_ir::{Flow, Stage, SweepOrder};
use proc_macro2::{Literal, Span, TokenStream};
use quote::quote;
use syn::LitInt;

use crate::parse::Input;
use crate::valid;

/// The scheme value for `input`, calling the run time through `rt` (`::dpd::__private` or
/// equivalent).
pub fn expand(input: &Input, rt: &TokenStream) -> syn::Result<TokenStream> {
    let program = input.compile()?;
    valid::check(&program, &input.args)?;
    let name = input.args.name.as_ref().unwrap_or(&input.source).value();
    let source = &input.source;
    let allow_inconsistent = input.args.allow_inconsistent;
    let stages = program.stages.iter().map(|s| stage(s, rt));
    Ok(scheme_value(
        rt,
        &quote! {
            fn name(&self) -> &str {
                #name
            }
            fn step(&self, sys: &mut #rt::System) {
                let dt = sys.dt();
                #(#stages)*
            }
            fn program(&self) -> ::core::option::Option<&#rt::Program> {
                static PROGRAM: ::std::sync::OnceLock<#rt::Program> = ::std::sync::OnceLock::new();
                ::core::option::Option::Some(
                    PROGRAM.get_or_init(|| #rt::compile_program(#source, #allow_inconsistent)),
                )
            }
        },
    ))
}

/// A block defining a fresh zero-sized type that implements `Scheme` with `methods`, whose
/// value is an instance of it.
pub fn scheme_value(rt: &TokenStream, methods: &TokenStream) -> TokenStream {
    quote! {
        {
            #[derive(Clone, Copy, Debug, Default)]
            struct DpdScheme;
            impl #rt::Scheme for DpdScheme {
                #methods
            }
            DpdScheme
        }
    }
}

/// One stage as the call `dpd_core::scheme::apply_stage` makes: the same function with
/// `h = c * dt`, `c` bit for bit the program's `f64`.
fn stage(stage: &Stage, rt: &TokenStream) -> TokenStream {
    let bits = LitInt::new(
        &format!("{:#018x}u64", stage.coeff.value.to_bits()),
        Span::call_site(),
    );
    let h = quote!(::core::primitive::f64::from_bits(#bits) * dt);
    let stream = Literal::u8_suffixed(stage.stream);
    let order = match stage.order {
        SweepOrder::Forward => quote!(#rt::SweepOrder::Forward),
        SweepOrder::Reverse => quote!(#rt::SweepOrder::Reverse),
    };
    match stage.flow {
        Flow::A => quote!(#rt::drift(sys, #h);),
        Flow::B => quote!(#rt::kick(sys, #h);),
        Flow::O => quote!(#rt::ou(sys, #h, #stream, #order);),
        Flow::Bbk => quote!(#rt::bbk(sys, #h, #stream, #order);),
        Flow::T => quote!(#rt::trotter(sys, #h, #stream, #order);),
        Flow::F => quote!(#rt::full_force(sys, #h, #stream);),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stage_is_one_call_with_the_coefficient_bits() {
        let program = dpd_ir::compile("ABOBA").unwrap();
        let rt = quote!(rt);
        let calls: Vec<String> = program
            .stages
            .iter()
            .map(|s| stage(s, &rt).to_string())
            .collect();
        let h = ":: core :: primitive :: f64 :: from_bits (0x3fe0000000000000u64) * dt";
        assert_eq!(calls[0], format!("rt :: drift (sys , {h}) ;"));
        assert_eq!(calls[1], format!("rt :: kick (sys , {h}) ;"));
        assert_eq!(
            calls[2],
            "rt :: ou (sys , :: core :: primitive :: f64 :: from_bits (0x3ff0000000000000u64) \
             * dt , 0u8 , rt :: SweepOrder :: Forward) ;"
        );
    }
}
