//! Evaluation of coefficient expressions.

use super::ast::{BinOp, Expr};
use super::diagnostic::Diagnostic;
use super::parse::{not_a_finite_number, not_finite};
use super::value::Value;
use std::collections::BTreeMap;

/// The functions of one argument, with their root index.
pub const FUNCTIONS: [(&str, u32); 2] = [("sqrt", 2), ("cbrt", 3)];

/// The names an expression may use: the parameters of the enclosing sub-scheme first,
/// then the constants.
pub struct Scope<'a> {
    pub params: &'a [(String, Value)],
    pub consts: &'a BTreeMap<String, Value>,
}

impl Scope<'_> {
    fn lookup(&self, name: &str) -> Option<&Value> {
        self.params
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v)
            .or_else(|| self.consts.get(name))
    }

    fn known_names(&self) -> String {
        let mut names: Vec<&str> = self.params.iter().map(|(n, _)| n.as_str()).collect();
        names.extend(self.consts.keys().map(String::as_str));
        names.join(", ")
    }
}

/// The value of `e` (recursion depth bounded by the parser's nesting limit).
pub fn eval(e: &Expr, scope: &Scope) -> Result<Value, Diagnostic> {
    let at = |msg: String| Diagnostic::new(msg, e.span());
    match e {
        Expr::Number(literal, _) => Value::parse(literal).map_err(at),
        Expr::Name(name, span) => scope.lookup(name).cloned().ok_or_else(|| {
            if let Some(word) = not_finite(name, 0).filter(|w| w.len() == name.len()) {
                return not_a_finite_number(word, span.start);
            }
            at(format!(
                "undefined constant '{name}'; known here: {}",
                scope.known_names()
            ))
        }),
        Expr::Neg(inner, _) => Ok(eval(inner, scope)?.neg()),
        Expr::Binary(op, lhs, rhs, _) => {
            let (a, b) = (eval(lhs, scope)?, eval(rhs, scope)?);
            match op {
                BinOp::Add => a.add(&b),
                BinOp::Sub => a.sub(&b),
                BinOp::Mul => a.mul(&b),
                BinOp::Div => a.div(&b),
                BinOp::Pow => a.pow(&b),
            }
            .map_err(at)
        }
        Expr::Call(name, arg, _) => {
            let Some(&(_, q)) = FUNCTIONS.iter().find(|(f, _)| f == name) else {
                return Err(at(format!(
                    "unknown function '{name}'; expected sqrt or cbrt"
                )));
            };
            eval(arg, scope)?.root(q).map_err(at)
        }
    }
}
