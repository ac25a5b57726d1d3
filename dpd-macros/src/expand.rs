//! The generated scheme: a zero-sized type whose `step` calls the sub-flows in a straight line.

use dpd_ir::{Flow, ForceGroup, Program, Stage, SweepOrder};
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
    let group = match stage.group {
        Some(g) => {
            let g = force_group(g, rt);
            quote!(::core::option::Option::Some(#g))
        }
        None => quote!(::core::option::Option::None),
    };
    quote! {
        #rt::Stage {
            flow: #rt::Flow::#flow,
            coeff: #rt::coeff(#bits, #exact),
            stream: #stream,
            order: #order,
            group: #group,
        }
    }
}

fn force_group(group: ForceGroup, rt: &TokenStream) -> TokenStream {
    match group {
        ForceGroup::Pair => quote!(#rt::ForceGroup::Pair),
        ForceGroup::Bond => quote!(#rt::ForceGroup::Bond),
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
    let group = stage.group.map(|g| force_group(g, rt));
    match (stage.flow, group) {
        (Flow::A, _) => quote!(#rt::drift(sys, #h);),
        (Flow::B, None) => quote!(#rt::kick(sys, #h);),
        (Flow::B, Some(g)) => quote!(#rt::kick_group(sys, #h, #g);),
        (Flow::O, _) => quote!(#rt::ou(sys, #h, #stream, #order);),
        (Flow::Bbk, _) => quote!(#rt::bbk(sys, #h, #stream, #order);),
        (Flow::T, _) => quote!(#rt::trotter(sys, #h, #stream, #order);),
        (Flow::F, None) => quote!(#rt::full_force(sys, #h, #stream);),
        (Flow::F, Some(g)) => quote!(#rt::full_force_group(sys, #h, #stream, #g);),
        (Flow::L, _) => quote!(#rt::collide(sys, #h, #stream, #order);),
        (Flow::Oa, _) => quote!(#rt::adaptive_ou(sys, #h, #stream, #order, true);),
        (Flow::On, _) => quote!(#rt::adaptive_ou(sys, #h, #stream, #order, false);),
        (Flow::Xi, _) => quote!(#rt::xi_update(sys, #h, #stream);),
        (Flow::Propose, _) => quote!(#rt::propose(sys);),
        (Flow::Accept, _) => quote!(#rt::accept(sys, #stream);),
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
        let grouped = dpd_ir::compile("B[pair] A B[bond] A B[pair] O").unwrap();
        let calls: Vec<String> = grouped
            .stages
            .iter()
            .map(|s| stage(s, &rt).to_string())
            .collect();
        assert_eq!(
            calls[2],
            format!("rt :: kick_group (sys , {h} , rt :: ForceGroup :: Bond) ;")
                .replace("0x3fe0000000000000u64", "0x3ff0000000000000u64")
        );
    }
}
