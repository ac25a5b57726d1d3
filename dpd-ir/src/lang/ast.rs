//! The parsed scheme, before names are resolved. Every node keeps its source span.

use crate::program::{Flow, SweepOrder};
use std::ops::Range;

pub type Span = Range<usize>;

/// A binary operator of a coefficient expression.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

/// A coefficient expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Number(String, Span),
    /// A constant or a parameter.
    Name(String, Span),
    Neg(Box<Expr>, Span),
    Binary(BinOp, Box<Expr>, Box<Expr>, Span),
    /// A function of one argument (`sqrt`, `cbrt`).
    Call(String, Box<Expr>, Span),
}

impl Expr {
    pub fn span(&self) -> Span {
        match self {
            Expr::Number(_, s)
            | Expr::Name(_, s)
            | Expr::Neg(_, s)
            | Expr::Binary(_, _, _, s)
            | Expr::Call(_, _, s) => s.clone(),
        }
    }
}

/// An application of a letter or a sub-scheme: `O<(1/2)`, `S(x1)`, `BAB`, `B[bond](1/8)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Apply {
    pub name: String,
    pub name_span: Span,
    /// The force group in brackets after the name (`B[pair]`), with its span.
    pub group: Option<(String, Span)>,
    /// Explicit sweep order (`<` or `>` after the name).
    pub order: Option<SweepOrder>,
    /// `None` when written without parentheses.
    pub args: Option<Vec<Expr>>,
    pub span: Span,
}

/// A partitioned Runge-Kutta table `prk(b = [...], bh = [...], kick = F)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Prk {
    pub b: Vec<Expr>,
    pub bh: Vec<Expr>,
    /// `F` (full force, frozen noise) or `B` (conservative kick).
    pub kick: Flow,
    pub span: Span,
}

/// A repetition `( steps )^count`.
#[derive(Clone, Debug, PartialEq)]
pub struct Repeat {
    pub body: Vec<Step>,
    /// How many times the body runs: an expression that must be a positive integer.
    pub count: Expr,
    pub span: Span,
}

/// A Metropolis-adjusted part `{ steps }`.
#[derive(Clone, Debug, PartialEq)]
pub struct Adjusted {
    pub body: Vec<Step>,
    pub span: Span,
}

/// One element of a step sequence.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    Apply(Apply),
    Prk(Prk),
    Repeat(Repeat),
    Adjusted(Adjusted),
}

impl Step {
    pub fn span(&self) -> Span {
        match self {
            Step::Apply(a) => a.span.clone(),
            Step::Prk(p) => p.span.clone(),
            Step::Repeat(r) => r.span.clone(),
            Step::Adjusted(a) => a.span.clone(),
        }
    }
}

/// `let name = value;`
#[derive(Clone, Debug, PartialEq)]
pub struct Let {
    pub name: String,
    pub name_span: Span,
    pub value: Expr,
}

/// `def Name(params) = body;`
#[derive(Clone, Debug, PartialEq)]
pub struct Def {
    pub name: String,
    pub name_span: Span,
    pub params: Vec<(String, Span)>,
    pub body: Vec<Step>,
}

/// `param name in lo..hi;`
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub name: String,
    pub name_span: Span,
    pub lo: Expr,
    pub hi: Expr,
    /// The whole declaration.
    pub span: Span,
}

/// A whole scheme source: its definitions and the step sequence.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Script {
    pub params: Vec<Param>,
    pub lets: Vec<Let>,
    pub defs: Vec<Def>,
    pub steps: Vec<Step>,
}
