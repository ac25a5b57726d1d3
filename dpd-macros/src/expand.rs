//! The generated scheme: a zero-sized type whose `step` calls the sub-flows in a straight line.

use dpd_ir::{Flow, Program, Stage, SweepOrder};
use proc_macro2::{Literal, Span, TokenStream};
use quote::quote;
use syn::{Ident, LitInt};

use crate::parse::Input;
use crate::valid;

/// The scheme value for `input`, calling the run time through `rt` (`::dpd::__private` or
/// equivalent).
pub fn expand(input: &Input, rt: &TokenStream) -> syn::Result<TokenStream> {
    let program = input.compile()?;
    valid::check(&program, &input.args)?;
    let name = input.args.name.as_ref().unwrap_or(&input.source).value();
    let stages = program.stages.iter().map(|s| stage(s, rt));
    let program = program_value(&program, rt);
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
                ::core::option::Option::Some(PROGRAM.get_or_init(|| #program))
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

/// The program the macro compiled, written out as data: `Scheme::program` builds it from
/// these constants on first use instead of compiling the source again.
fn program_value(program: &Program, rt: &TokenStream) -> TokenStream {
    let source = &program.source;
    let stages = program.stages.iter().map(|s| stage_value(s, rt));
    let unmerged = program.unmerged_stages.iter().map(|s| stage_value(s, rt));
    quote! {
        #rt::Program {
            source: ::std::string::String::from(#source),
            stages: ::std::vec![#(#stages),*],
            unmerged_stages: ::std::vec![#(#unmerged),*],
        }
    }
}

/// One stage as a `Stage` value, the coefficient bit for bit and its exact value as text.
fn stage_value(stage: &Stage, rt: &TokenStream) -> TokenStream {
    let bits = coeff_bits(stage.coeff.value);
    let exact = match &stage.coeff.exact {
        Some(r) => {
            let r = r.to_string();
            quote!(::core::option::Option::Some(#r))
        }
        None => quote!(::core::option::Option::None),
    };
    let flow = Ident::new(&format!("{:?}", stage.flow), Span::call_site());
    let stream = Literal::u8_suffixed(stage.stream);
    let order = sweep_order(stage.order, rt);
    quote! {
        #rt::Stage {
            flow: #rt::Flow::#flow,
            coeff: #rt::coeff(#bits, #exact),
            stream: #stream,
            order: #order,
        }
    }
}

/// `c` as a `u64` literal of its bits.
fn coeff_bits(c: f64) -> LitInt {
    LitInt::new(&format!("{:#018x}u64", c.to_bits()), Span::call_site())
}

fn sweep_order(order: SweepOrder, rt: &TokenStream) -> TokenStream {
    match order {
        SweepOrder::Forward => quote!(#rt::SweepOrder::Forward),
        SweepOrder::Reverse => quote!(#rt::SweepOrder::Reverse),
    }
}

/// One stage as the call `dpd_core::scheme::apply_stage` makes: the same function with
/// `h = c * dt`, `c` bit for bit the program's `f64`.
fn stage(stage: &Stage, rt: &TokenStream) -> TokenStream {
    let bits = coeff_bits(stage.coeff.value);
    let h = quote!(::core::primitive::f64::from_bits(#bits) * dt);
    let stream = Literal::u8_suffixed(stage.stream);
    let order = sweep_order(stage.order, rt);
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
