//! Families of schemes: `param NAME in LO..HI;` declares a free parameter, usable in every
//! coefficient expression of the scheme (and in its constants).
//!
//! ```text
//! param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O
//! param x in -2..2;  S((1 - x)/2) S(x) S((1 - x)/2) O
//! ```
//!
//! A family can be analysed at a point ([`Family::at`]) and designed (`dpd design`), not run:
//! [`super::compile`] refuses a source with free parameters, naming them. The bounds are plain
//! numbers or expressions of numbers; the range must not be empty (`LO < HI`).

use super::ast::{Expr, Script, Step};
use super::diagnostic::Diagnostic;
use super::expand::RESERVED;
use super::expr::{eval, Scope, FUNCTIONS};
use super::value::Value;
use super::{parse_source, Options, PRELUDE};
use crate::program::Program;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// Most free parameters of a family: the design solver starts from a grid over the box of
/// parameters, whose size grows as a power of their number.
pub const MAX_PARAMETERS: usize = 3;

/// A free parameter and its range.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Parameter {
    pub name: String,
    pub lo: f64,
    pub hi: f64,
}

/// A scheme with free parameters, checked once and compiled at any point.
#[derive(Clone, Debug)]
pub struct Family {
    source: String,
    prelude: Script,
    script: Script,
    pub parameters: Vec<Parameter>,
}

/// Parses and checks a family: the parameter declarations (range, use, names, number) and
/// the scheme itself at a generic point of the box (inconsistency allowed: consistency is a
/// condition the design solves for).
pub fn compile_family(src: &str) -> Result<Family, Vec<Diagnostic>> {
    let prelude = parse_source(PRELUDE)?;
    let script = parse_source(src)?;
    let mut errors = Vec::new();
    let mut parameters = Vec::new();
    let used = used_names(&script);
    let mut seen = BTreeSet::new();
    for (i, p) in script.params.iter().enumerate() {
        let at = |m: String| Diagnostic::new(m, p.name_span.clone());
        if i == MAX_PARAMETERS {
            errors.push(Diagnostic::new(
                format!(
                    "too many free parameters: {} declared, the design solver supports at most {MAX_PARAMETERS}",
                    script.params.len()
                ),
                p.span.clone(),
            ));
        }
        if RESERVED.contains(&p.name.as_str()) || FUNCTIONS.iter().any(|(f, _)| *f == p.name) {
            errors.push(at(format!(
                "'{}' is reserved and cannot name a free parameter",
                p.name
            )));
            continue;
        }
        if !seen.insert(p.name.as_str()) {
            errors.push(at(format!("free parameter '{}' is declared twice", p.name)));
            continue;
        }
        if script.lets.iter().any(|l| l.name == p.name) {
            errors.push(at(format!(
                "'{}' is both a free parameter and a constant (let {} = ...); rename one",
                p.name, p.name
            )));
            continue;
        }
        if !used.contains(p.name.as_str()) {
            errors.push(at(format!(
                "free parameter '{}' is not used by any coefficient; remove it or use it",
                p.name
            )));
            continue;
        }
        let bound = |e: &Expr| {
            let consts = BTreeMap::new();
            let scope = Scope {
                params: &[],
                consts: &consts,
            };
            eval(e, &scope).map(|v| v.to_f64())
        };
        match (bound(&p.lo), bound(&p.hi)) {
            (Ok(lo), Ok(hi)) if lo < hi => parameters.push(Parameter {
                name: p.name.clone(),
                lo,
                hi,
            }),
            (Ok(lo), Ok(hi)) => errors.push(Diagnostic::new(
                format!(
                    "{} range of free parameter '{}': {lo}..{hi}; the lower bound must be below the upper one",
                    if lo == hi { "empty" } else { "inverted" },
                    p.name
                ),
                p.span.clone(),
            )),
            (Err(e), _) | (_, Err(e)) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let family = Family {
        source: src.to_string(),
        prelude,
        script,
        parameters,
    };
    let options = Options {
        allow_inconsistent: true,
    };
    family.at_with(&family.generic_point(), &options)?;
    Ok(family)
}

impl Family {
    /// The source as written.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// A point of the box where no special relation is expected to hold: each parameter at
    /// the golden section of its range (a midpoint such as l = 1/4 is often special).
    pub fn generic_point(&self) -> Vec<f64> {
        const GOLDEN: f64 = 0.381_966_011_250_105_1;
        self.parameters
            .iter()
            .map(|p| p.lo + GOLDEN * (p.hi - p.lo))
            .collect()
    }

    /// The program at `values` (one per parameter, in declaration order), with the default
    /// [`Options`].
    pub fn at(&self, values: &[f64]) -> Result<Program, Vec<Diagnostic>> {
        self.at_with(values, &Options::default())
    }

    /// The program at `values`; the values need not lie in the ranges.
    pub fn at_with(&self, values: &[f64], options: &Options) -> Result<Program, Vec<Diagnostic>> {
        if values.len() != self.parameters.len() || values.iter().any(|v| !v.is_finite()) {
            return Err(vec![Diagnostic::new(
                format!(
                    "{} finite values needed for the free parameters ({}), found {values:?}",
                    self.parameters.len(),
                    self.names().join(", ")
                ),
                0..self.source.len(),
            )]);
        }
        let bindings: Vec<(String, Value)> = self
            .parameters
            .iter()
            .zip(values)
            .map(|(p, &v)| (p.name.clone(), Value::Float(v)))
            .collect();
        super::build(
            &self.source,
            &self.script,
            &self.prelude,
            &bindings,
            options,
        )
    }

    /// The parameter names in declaration order.
    pub fn names(&self) -> Vec<&str> {
        self.parameters.iter().map(|p| p.name.as_str()).collect()
    }
}

/// The errors of a source that declares free parameters but is to be run: one per parameter,
/// on its name.
pub(crate) fn refuse_free_parameters(script: &Script) -> Vec<Diagnostic> {
    script
        .params
        .iter()
        .map(|p| {
            Diagnostic::new(
                format!(
                    "'{}' is a free parameter: a scheme with free parameters can be analysed and designed (dpd check --at, dpd design) but not run; give it a value, e.g. let {} = ...;",
                    p.name, p.name
                ),
                p.name_span.clone(),
            )
        })
        .collect()
}

/// Every name used in an expression of `script` (constants, steps, sub-scheme bodies,
/// repetition counts).
fn used_names(script: &Script) -> BTreeSet<&str> {
    let mut names = BTreeSet::new();
    let mut exprs: Vec<&Expr> = script.lets.iter().map(|l| &l.value).collect();
    let mut steps: Vec<&Step> = script
        .steps
        .iter()
        .chain(script.defs.iter().flat_map(|d| &d.body))
        .collect();
    while let Some(step) = steps.pop() {
        match step {
            Step::Apply(a) => exprs.extend(a.args.iter().flatten()),
            Step::Prk(p) => exprs.extend(p.b.iter().chain(&p.bh)),
            Step::Repeat(r) => {
                exprs.push(&r.count);
                steps.extend(&r.body);
            }
            Step::Adjusted(a) => steps.extend(&a.body),
        }
    }
    while let Some(e) = exprs.pop() {
        match e {
            Expr::Number(..) => {}
            Expr::Name(n, _) => {
                names.insert(n.as_str());
            }
            Expr::Neg(inner, _) | Expr::Call(_, inner, _) => exprs.push(inner),
            Expr::Binary(_, a, b, _) => exprs.extend([a.as_ref(), b.as_ref()]),
        }
    }
    names
}
