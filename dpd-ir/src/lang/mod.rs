//! The scheme language: a splitting integrator written as a string, compiled to a
//! [`Program`].
//!
//! The `dpd_scheme!` macro calls [`compile`] at expansion time and the run-time crates call
//! it for schemes given as strings, so both see the same program, the same errors and the
//! same `f64` coefficients, bit for bit. `compile` never panics, whatever the input.
//!
//! # Letters
//!
//! A scheme lists the sub-flows of one step in the order they are applied, left first
//! (algorithms.md section 2). White space is ignored.
//!
//! | letter | sub-flow |
//! |---|---|
//! | `A` | drift q += h p / m |
//! | `B` | conservative kick p += h F^C(q) |
//! | `O` | pairwise Ornstein-Uhlenbeck sweep, exact per pair |
//! | `Ob` | pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update |
//! | `T` | pairwise conservative + Ornstein-Uhlenbeck sweep, exact per pair |
//! | `F` | explicit full-force kick p += h (F^C + F^D + F^R) |
//!
//! Names of sub-flows and sub-schemes start with an uppercase letter and continue with
//! lowercase letters, digits or `_`, so an uppercase letter always starts a new name:
//! `ObBAB` is `Ob B A B`, `ABOBA` is five letters.
//!
//! # Step lengths
//!
//! A letter with a coefficient in parentheses, `A(1/2)`, runs for `1/2 dt`. Letters written
//! without one share what the explicit occurrences of the same letter leave of `dt`,
//! equally: `ABOBA` = `A(1/2) B(1/2) O(1) B(1/2) A(1/2)`, and in `A(1/4) B A A` each of the
//! two bare `A` runs `3/8 dt`. The sharing is counted over the whole expanded step, sub-schemes
//! included, separately per letter (`O` and `Ob` are different letters).
//!
//! Coefficients are expressions: numbers (`3`, `0.25`, `1e-3`), `+ - * /`, unary minus, `^`
//! (right associative, binds tighter than unary minus: `-2^2 = -4`, `2^-1 = 1/2`),
//! parentheses, `sqrt(..)`, `cbrt(..)` and constants. A number or a `)` directly followed by a
//! name or `(` multiplies it, like `*`: `1-2x1` = `1 - 2*x1`, `(2/9)(1 + sqrt(38/11))`. Values stay exact rationals where they
//! are rational (`sqrt(9/4)` = `3/2`, `2^10`, `0.1` = `1/10`, `5e-9`); otherwise they are `f64`
//! computed by a fixed sequence of IEEE operations, without any platform `libm` function, so
//! they are identical at compile time and run time. Exponents must be rational with a
//! denominator of at most 32; exact values are limited to 4096-bit numerators and
//! denominators, and an expression to 200 levels of nesting (each parenthesis, sign, power and
//! operator of a chain counts one level).
//!
//! ## Typed coefficients
//!
//! A number literal with 13 or more significant digits (leading and trailing zeros not
//! counted) is a typed approximation of a real number, as when coefficients are copied from a
//! paper: it is read as the nearest `f64` and makes every value computed from it inexact, like
//! `sqrt(2)`. The order analysis then works in `f64` and treats a defect below 1e-12 of its
//! bound as zero (see `analysis::FLOAT_TOLERANCE`): Yoshida's sixth-order weights typed to 21
//! or 15 digits give order 6, while `x0 + 5e-9` in a triple jump, a perturbation far above
//! that precision, gives order 2. Shorter literals are exact, so `0.1`, `5e-9` and
//! `0.123456789` mean exactly what they say. A printed [`Program`] writes exact values as
//! fractions and inexact ones with 17 significant digits, so it compiles back to the same
//! coefficients and the same analysis.
//!
//! # Sweep order
//!
//! The successive sweeps `O`, `Ob` and `T` visit pairs one after the other, so their order
//! matters. By default the sweeps of a step alternate in order of appearance, all three
//! letters counted together: the first runs forward, the second in reverse, the third forward,
//! and so on (`BAOOAB`: forward then reverse, a symmetric step). `<` right after the letter
//! forces reverse, `>` forward: `O<`, `Ob>(1/2)`, `T<(1/2)`.
//!
//! # Constants and sub-schemes
//!
//! ```text
//! let x = 1/(2 - 2^(1/3));                 constant (lowercase name)
//! def S(c) = A(c/2) B(c) A(c/2);           sub-scheme with parameters (uppercase name)
//! def H = B(1/2) A B(1/2);                 sub-scheme without parameters, used as `H`
//! S(x) S(1-2x) S(x) O                      the step
//! ```
//!
//! Definitions end with `;` and may appear anywhere; the step is everything else, in order.
//! A constant may use the constants defined before it; sub-schemes and the step may use any
//! constant. A sub-scheme body is a sequence of applications whose coefficients may use its
//! parameters; it may call other sub-schemes (at most 32 deep), but not itself. Body
//! coefficients are in units of `dt`, like everywhere else: `S(c)` passes `c` and the body
//! decides how to use it.
//!
//! Predefined, and replaceable by a definition of the same name:
//!
//! ```text
//! let x1 = 1/(2 - 2^(1/3));                Yoshida triple jump, outer steps
//! let x0 = -2^(1/3)/(2 - 2^(1/3));         Yoshida triple jump, inner step
//! def S(c) = B(c/2) A(c) B(c/2);           second-order base step of length c dt
//! ```
//!
//! so `S(x1) S(x0) S(x1)` is the fourth-order triple jump and `S(x1) S(x0) S(x1) Ob` is
//! M-Shardlow-2.
//!
//! # Partitioned Runge-Kutta tables
//!
//! `prk(b = [b1, ..., bn], bh = [bh1, ..., bhn], kick = F)` expands to
//! `F(b1) A(bh1) F(b2) A(bh2) ... F(bn) A(bhn)`. With `kick = F` (the default) all F stages of
//! the table share one random stream: the published full-force form with frozen noise. With
//! `kick = B` the table is a Hamiltonian part, to be composed with a sweep:
//! `prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O`.
//!
//! # Grammar
//!
//! ```text
//! scheme  = { item } ;
//! item    = "let" name "=" expr ";"
//!         | "def" Name [ "(" name { "," name } ")" ] "=" step { step } ";"
//!         | step ;
//! step    = Name [ "<" | ">" ] [ "(" expr { "," expr } ")" ]
//!         | "prk" "(" prkarg { "," prkarg } ")" ;
//! prkarg  = "b" "=" list | "bh" "=" list | "kick" "=" ( "F" | "B" ) ;
//! list    = "[" expr { "," expr } "]" ;
//! expr    = product { ( "+" | "-" ) product } ;
//! product = unary { ( "*" | "/" ) unary | power (right after a number or ")") } ;
//! unary   = ( "-" | "+" ) unary | power ;
//! power   = atom [ "^" unary ] ;
//! atom    = number | name | ( "sqrt" | "cbrt" ) "(" expr ")" | "(" expr ")" ;
//! Name    = uppercase letter { lowercase letter | digit | "_" } ;
//! name    = ( lowercase letter | "_" ) { lowercase letter | digit | "_" } ;
//! number  = digits [ "." digits ] [ ( "e" | "E" ) [ "+" | "-" ] digits ] | "." digits ... ;
//! ```
//!
//! # Checks
//!
//! Every error has a byte span into the source ([`Diagnostic`]); independent errors are
//! reported together. Besides syntax and name errors (unknown letter or name, unbalanced
//! brackets, wrong number of arguments, recursion, undefined constants):
//!
//! - the scheme must not be empty, must contain an `A`, and a `B`, `T` or `F`;
//! - coefficients must be finite (division by zero, overflow);
//! - `O`, `Ob` and `T` need a positive coefficient: a stochastic sweep cannot run backwards;
//! - consistency: the coefficients of each generator sum to 1 — A: `A`; B: `B`, `T`, `F`;
//!   O: `O`, `Ob`, `T`, `F` (not checked for a scheme without any stochastic flow). Exact sums
//!   must equal 1 exactly, others within 1e-12. [`Options::allow_inconsistent`] turns this
//!   check off (M-Shardlow-1 as published);
//! - at most 255 random streams per step.
//!
//! # Lowering
//!
//! Adjacent applications of `A`, `B` or `F` merge into one (drifts commute; a kick reuses its
//! force while positions do not change) and those with a zero coefficient are dropped;
//! sweeps never merge. Each stochastic stage gets the next random stream (0, 1, 2, ...), the
//! F stages of one `kick = F` table sharing one. See [`Program`].
//!
//! ```
//! let p = dpd_ir::lang::compile("ABOBA").unwrap();
//! assert_eq!(p.to_string(), "A(1/2) B(1/2) O(1) B(1/2) A(1/2)");
//! assert_eq!(p.force_evaluations_per_step(), 1);
//! ```

mod ast;
mod diagnostic;
mod expand;
mod expr;
pub mod letters;
mod lexer;
mod lower;
mod parse;
mod validate;
mod value;

pub use diagnostic::{escape, Diagnostic};
pub use letters::{Letter, LETTERS};

use crate::program::Program;

/// Options of [`compile_with`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// Accept schemes whose coefficient sums per generator are not 1.
    pub allow_inconsistent: bool,
}

/// The predefined constants and sub-schemes, written in the language itself.
pub const PRELUDE: &str = "
    let x1 = 1/(2 - 2^(1/3));
    let x0 = -2^(1/3)/(2 - 2^(1/3));
    def S(c) = B(c/2) A(c) B(c/2);
";

/// Compiles a scheme with the default [`Options`].
pub fn compile(src: &str) -> Result<Program, Vec<Diagnostic>> {
    compile_with(src, &Options::default())
}

/// Compiles a scheme: parse, expand, check, lower.
pub fn compile_with(src: &str, options: &Options) -> Result<Program, Vec<Diagnostic>> {
    let prelude = parse_source(PRELUDE)?;
    let script = parse_source(src)?;
    let apps = expand::expand(src, &script, &prelude)?;
    let errors = validate::validate(&apps, src.len(), options);
    if !errors.is_empty() {
        return Err(errors);
    }
    lower::lower(src, apps)
}

fn parse_source(src: &str) -> Result<ast::Script, Vec<Diagnostic>> {
    let (tokens, mut errors) = lexer::lex(src);
    match parse::parse(src, &tokens) {
        Ok(script) if errors.is_empty() => Ok(script),
        Ok(_) => Err(errors),
        Err(more) => {
            errors.extend(more);
            Err(errors)
        }
    }
}
