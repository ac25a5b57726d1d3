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
//! | `B` | conservative kick p += h F^C(q), all forces or one group: B[pair], B[bond] |
//! | `O` | pairwise Ornstein-Uhlenbeck sweep, exact per pair |
//! | `Ob` | pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update |
//! | `T` | pairwise conservative + Ornstein-Uhlenbeck sweep, exact per pair |
//! | `F` | explicit full-force kick p += h (F^C + F^D + F^R), all forces or F[pair] |
//! | `L` | Lowe-Andersen pairwise collisions at rate Gamma, exact in distribution |
//! | `Oa` | adaptive pairwise Ornstein-Uhlenbeck sweep (PAdL): friction xi gamma_ij, noise sigma_ij fixed |
//! | `On` | pairwise Nose-Hoover sweep (PNHL): Oa without the pair noise, u *= exp(-xi gamma_ij w_D mu_ij h) |
//! | `Xi` | the friction factor xi += h/mu sum gamma_ij w_D (u_ij^2 - kbt (1/m_i + 1/m_j)); OU around 0 with thermostat_friction (PNHL) |
//!
//! Names of sub-flows and sub-schemes start with an uppercase letter and continue with
//! lowercase letters, digits or `_`, so an uppercase letter always starts a new name:
//! `ObBAB` is `Ob B A B`, `ABOBA` is five letters.
//!
//! # Force groups
//!
//! `B` and `F` apply all forces. A force group in brackets right after the letter selects
//! part of them (module [`crate::forces`]):
//!
//! | group | forces |
//! |---|---|
//! | `pair` | the pair forces (in F also their dissipative and random parts) and the body force |
//! | `bond` | the bonded forces: bonds and angles (B only: they have no dissipative or random part) |
//!
//! so `B[pair](1/2)` kicks with the pair forces for half a step, `B[bond](1/8)` with the bonded
//! forces for an eighth, `F[pair]` is the full-force kick of the pair forces; `T` applies the
//! pair forces (with its Ornstein-Uhlenbeck part) and takes no group. A scheme that names a
//! group runs only on a system that has it (`B[bond]` needs bonds: the run-time check refuses
//! it before the first step otherwise), and a system with bonded forces needs a scheme that
//! applies them (`B`, `F` or `B[bond]`). Brackets after a letter are always a group: the
//! letter spellings never contain them, and `[` elsewhere only opens a `prk` list.
//!
//! # Repetition
//!
//! `( steps )^n` runs the steps in parentheses `n` times, `n` a whole number from 1 to 10 000
//! (a number, a constant, a parameter of the enclosing sub-scheme or an expression in
//! parentheses): multiple time stepping writes the inner loop once,
//!
//! ```text
//! B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)
//! def Inner(c, n) = (B[bond](c/(2n)) A(c/n) B[bond](c/(2n)))^n;
//! ```
//!
//! Repetitions nest and may appear in sub-scheme bodies. A parenthesis after a letter holds
//! its coefficient unless a step starts inside it (an uppercase name or `prk`, after any
//! further `(`), which no coefficient does: `A (B A B)^2` is `A` and a repetition,
//! `A((1/2))` is `A` with one coefficient.
//!
//! # Metropolis-adjusted parts
//!
//! Braces around the Hamiltonian part of a step, `{B(1/2) A B(1/2)} O`, make it a proposal:
//! at `{` the state and its energy `H = K + U` are kept, at `}` the state reached is kept with
//! probability `min(1, exp(-Delta H / k_B T))`, else the kept state returns with its momenta
//! negated (generalised hybrid Monte Carlo). The step then samples the Gibbs measure
//! `exp(-H / k_B T)` exactly at any dt, which needs every part to keep it by itself: inside the
//! braces only `A` and `B` (force groups allowed) in a word that reads the same backwards
//! with equal fractions, after merging (`B(1/2) A B(1/2)`, `A(1/2) B A(1/2)`, an MTS word),
//! so that the map is reversible and volume-preserving; outside only `O`, `Ob` and `L`, which
//! keep the Maxwellian of every pair exactly. Braces do not nest and are not empty; a step may
//! hold several parts. The braces print without coefficients: `{ B(1/2) A(1) B(1/2) } O(1)`.
//!
//! # Step lengths
//!
//! A letter with a coefficient in parentheses, `A(1/2)`, runs for `1/2 dt`. Letters written
//! without one share what the explicit occurrences of the same letter leave of `dt`,
//! equally: `ABOBA` = `A(1/2) B(1/2) O(1) B(1/2) A(1/2)`, and in `A(1/4) B A A` each of the
//! two bare `A` runs `3/8 dt`. The sharing is counted over the whole expanded step, sub-schemes
//! and repetitions included, separately per letter and force group (`O` and `Ob` are different
//! letters, `B` and `B[bond]` share apart): `B[pair] (B[bond] A B[bond])^4 O B[pair]` is the
//! multiple-time-stepping example above.
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
//! # Free parameters
//!
//! `param l in 0..1/2;` declares a free parameter with its range, usable in every coefficient
//! (module [`family`]): `param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O`. Such a
//! family is compiled by [`compile_family`], analysed at a point and designed; [`compile`]
//! refuses it, naming the parameter. At most [`MAX_PARAMETERS`] parameters; the range must
//! not be empty; every parameter must be used and must not also be a `let` constant.
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
//!         | "param" name "in" expr ".." expr ";"
//!         | "def" Name [ "(" name { "," name } ")" ] "=" step { step } ";"
//!         | step ;
//! step    = Name [ "[" group "]" ] [ "<" | ">" ] [ "(" expr { "," expr } ")" ]
//!         | "prk" "(" prkarg { "," prkarg } ")"
//!         | "(" step { step } ")" "^" atom
//!         | "{" step { step } "}" ;
//! group   = "pair" | "bond" ;
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
//! - the scheme must not be empty, must contain an `A`, and a `B`, `T` or `F` applying the
//!   pair forces;
//! - a force group only after `B` or `F` (`F[bond]` is `B[bond]`), a known group, a
//!   repetition count a whole number from 1 to 10 000;
//! - coefficients must be finite (division by zero, overflow);
//! - `O`, `Ob` and `T` need a positive coefficient: a stochastic sweep cannot run backwards;
//! - consistency: the coefficients of each generator sum to 1 — A: `A`; B: `B`, `T`, `F`;
//!   O: `O`, `Ob`, `T`, `F` (not checked for a scheme without any stochastic flow). A scheme
//!   that names force groups has a generator per group instead of B — B[pair]: `B`,
//!   `B[pair]`, `T`, `F`, `F[pair]`; B[bond], where some stage applies bonded forces: `B`,
//!   `B[bond]`, `F`. Exact sums must equal 1 exactly, others within 1e-12.
//!   [`Options::allow_inconsistent`] turns this check off (M-Shardlow-1 as published);
//! - at most 255 random streams per step.
//!
//! # Lowering
//!
//! Adjacent applications of `A`, `B` or `F` (of the same force group) merge into one (drifts
//! commute; a kick reuses its force while positions do not change) and those with a zero
//! coefficient are dropped;
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
pub mod family;
pub mod letters;
mod lexer;
pub mod list;
mod lower;
mod parse;
mod validate;
mod value;

pub use diagnostic::{escape, Diagnostic};
pub use family::{compile_family, Family, Parameter, MAX_PARAMETERS};
pub use letters::{Letter, LETTERS};
pub use list::split_schemes;

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

/// Compiles a scheme: parse, expand, check, lower. A scheme with free parameters (`param`)
/// is refused, naming each; see [`compile_family`].
pub fn compile_with(src: &str, options: &Options) -> Result<Program, Vec<Diagnostic>> {
    let prelude = parse_source(PRELUDE)?;
    let script = parse_source(src)?;
    let free = family::refuse_free_parameters(&script);
    if !free.is_empty() {
        return Err(free);
    }
    build(src, &script, &prelude, &[], options)
}

/// Expands, checks and lowers a parsed scheme with its free parameters bound.
fn build(
    src: &str,
    script: &ast::Script,
    prelude: &ast::Script,
    bindings: &[(String, value::Value)],
    options: &Options,
) -> Result<Program, Vec<Diagnostic>> {
    let apps = expand::expand(src, script, prelude, bindings).map_err(distinct)?;
    let errors = validate::validate(&apps, src.len(), options);
    if !errors.is_empty() {
        return Err(distinct(errors));
    }
    lower::lower(src, apps)
}

/// `errors` with repeats left out: a repeated step (`(O(-1) A)^4`) reports its error once.
fn distinct(mut errors: Vec<Diagnostic>) -> Vec<Diagnostic> {
    let mut seen = Vec::with_capacity(errors.len());
    errors.retain(|e| {
        let new = !seen.contains(e);
        if new {
            seen.push(e.clone());
        }
        new
    });
    errors
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
