//! Recursive-descent parser from tokens to a [`Script`], with bounded nesting.

use super::ast::{Adjusted, Apply, BinOp, Def, Expr, Let, Param, Prk, Repeat, Script, Span, Step};
use super::diagnostic::{position, Diagnostic};
use super::lexer::{Tok, Token};
use crate::program::{Flow, SweepOrder};

/// Deepest expression tree accepted: each parenthesis, sign, power and binary operator of a
/// chain counts one level. Bounds the recursion of parsing, evaluation and dropping.
pub const MAX_NESTING: usize = 200;

/// Parses `tokens` of `src`. Unbalanced brackets are reported first, all of them; otherwise
/// each malformed item is reported and parsing resumes after the next `;`.
pub fn parse(src: &str, tokens: &[Token]) -> Result<Script, Vec<Diagnostic>> {
    let unbalanced = check_brackets(src, tokens);
    if !unbalanced.is_empty() {
        return Err(unbalanced);
    }
    let mut p = Parser {
        src,
        tokens,
        pos: 0,
        depth: 0,
    };
    let mut script = Script::default();
    let mut errors = Vec::new();
    while p.pos < tokens.len() {
        p.depth = 0;
        if let Err(e) = p.item(&mut script) {
            errors.push(e);
            p.skip_past_semicolon();
        }
    }
    if errors.is_empty() {
        Ok(script)
    } else {
        Err(errors)
    }
}

/// Every unmatched `(`, `)`, `[`, `]`, `{` or `}`.
fn check_brackets(src: &str, tokens: &[Token]) -> Vec<Diagnostic> {
    let mut open: Vec<&Token> = Vec::new();
    let mut errors = Vec::new();
    for t in tokens {
        match t.tok {
            Tok::Punct('(' | '[' | '{') => open.push(t),
            Tok::Punct(c @ (')' | ']' | '}')) => {
                let want = match c {
                    ')' => '(',
                    ']' => '[',
                    _ => '{',
                };
                match open.pop() {
                    Some(o) if o.tok == Tok::Punct(want) => {}
                    Some(o) => {
                        errors.push(Diagnostic::new(
                            format!(
                                "unbalanced parentheses: '{c}' at position {} does not match '{}' at position {}",
                                position(src, t.span.start),
                                punct(&o.tok),
                                position(src, o.span.start)
                            ),
                            t.span.clone(),
                        ));
                        return errors;
                    }
                    None => errors.push(Diagnostic::new(
                        format!(
                            "unbalanced parentheses: '{c}' at position {} has no matching opening bracket",
                            position(src, t.span.start)
                        ),
                        t.span.clone(),
                    )),
                }
            }
            _ => {}
        }
    }
    for o in open {
        errors.push(Diagnostic::new(
            format!(
                "unbalanced parentheses: '{}' at position {} is never closed",
                punct(&o.tok),
                position(src, o.span.start)
            ),
            o.span.clone(),
        ));
    }
    errors
}

fn punct(tok: &Tok) -> char {
    match tok {
        Tok::Punct(c) => *c,
        _ => '?',
    }
}

struct Parser<'a> {
    src: &'a str,
    tokens: &'a [Token],
    pos: usize,
    depth: usize,
}

type PResult<T> = Result<T, Diagnostic>;

impl Parser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.tokens.get(self.pos).map(|t| &t.tok)
    }

    /// Span of the next token, or an empty span at the end of the source.
    fn here(&self) -> Span {
        self.tokens
            .get(self.pos)
            .map_or(self.src.len()..self.src.len(), |t| t.span.clone())
    }

    fn prev_end(&self) -> usize {
        self.pos
            .checked_sub(1)
            .and_then(|i| self.tokens.get(i))
            .map_or(0, |t| t.span.end)
    }

    fn bump(&mut self) -> Option<&Token> {
        let t = self.tokens.get(self.pos);
        self.pos += 1;
        t
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(&Tok::Punct(c)) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    fn describe_next(&self) -> String {
        match self.peek() {
            None => "the end of the scheme".to_string(),
            Some(Tok::Upper(s) | Tok::Lower(s) | Tok::Number(s)) => format!("'{s}'"),
            Some(Tok::Punct(c)) => format!("'{c}'"),
            Some(Tok::DotDot) => "'..'".to_string(),
        }
    }

    fn expected(&self, what: &str) -> Diagnostic {
        Diagnostic::new(
            format!("expected {what}, found {}", self.describe_next()),
            self.here(),
        )
    }

    fn expect(&mut self, c: char, what: &str) -> PResult<()> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(self.expected(what))
        }
    }

    fn skip_past_semicolon(&mut self) {
        while let Some(t) = self.bump() {
            if t.tok == Tok::Punct(';') {
                break;
            }
        }
    }

    fn item(&mut self, script: &mut Script) -> PResult<()> {
        match self.peek() {
            Some(Tok::Lower(k)) if k == "let" => {
                self.pos += 1;
                let (name, name_span) = self.lower("a constant name after 'let'")?;
                self.expect('=', "'=' after the constant name")?;
                let value = self.expr()?;
                self.expect(';', "';' after the constant's value")?;
                script.lets.push(Let {
                    name,
                    name_span,
                    value,
                });
            }
            Some(Tok::Lower(k)) if k == "def" => {
                self.pos += 1;
                script.defs.push(self.def()?);
            }
            Some(Tok::Lower(k)) if k == "param" => {
                let start = self.here().start;
                self.pos += 1;
                let (name, name_span) = self.lower("a parameter name after 'param'")?;
                if !matches!(self.peek(), Some(Tok::Lower(k)) if k == "in") {
                    return Err(
                        self.expected("'in' after the parameter name, as in 'param l in 0..1/2;'")
                    );
                }
                self.pos += 1;
                let lo = self.expr()?;
                if self.peek() != Some(&Tok::DotDot) {
                    return Err(self.expected("'..' between the bounds of the range"));
                }
                self.pos += 1;
                let hi = self.expr()?;
                self.expect(';', "';' after the parameter's range")?;
                script.params.push(Param {
                    name,
                    name_span,
                    lo,
                    hi,
                    span: start..self.prev_end(),
                });
            }
            _ => script.steps.push(self.step()?),
        }
        Ok(())
    }

    fn lower(&mut self, what: &str) -> PResult<(String, Span)> {
        match self.tokens.get(self.pos) {
            Some(Token {
                tok: Tok::Lower(s),
                span,
            }) => {
                self.pos += 1;
                Ok((s.clone(), span.clone()))
            }
            _ => Err(self.expected(what)),
        }
    }

    fn def(&mut self) -> PResult<Def> {
        let (name, name_span) = match self.tokens.get(self.pos) {
            Some(Token {
                tok: Tok::Upper(s),
                span,
            }) => (s.clone(), span.clone()),
            _ => {
                return Err(self
                    .expected("a sub-scheme name starting with an uppercase letter after 'def'"))
            }
        };
        self.pos += 1;
        let mut params = Vec::new();
        if self.eat('(') {
            loop {
                params.push(self.lower("a parameter name (lowercase)")?);
                if self.eat(')') {
                    break;
                }
                self.expect(',', "',' or ')' in the parameter list")?;
            }
        }
        self.expect('=', "'=' after the sub-scheme's name and parameters")?;
        let mut body = Vec::new();
        while !self.eat(';') {
            if self.peek().is_none() {
                return Err(self.expected("';' at the end of the definition"));
            }
            body.push(self.step()?);
        }
        if body.is_empty() {
            return Err(Diagnostic::new(
                format!("sub-scheme '{name}' has an empty body"),
                name_span,
            ));
        }
        Ok(Def {
            name,
            name_span,
            params,
            body,
        })
    }

    fn step(&mut self) -> PResult<Step> {
        let start = self.here().start;
        match self.peek().cloned() {
            Some(Tok::Upper(name)) => {
                let name_span = self.here();
                self.pos += 1;
                let group = if self.eat('[') {
                    let group = self.lower("a force group name, as in B[pair] or B[bond]")?;
                    self.expect(']', "']' after the force group")?;
                    Some(group)
                } else {
                    None
                };
                let order = if self.eat('<') {
                    Some(SweepOrder::Reverse)
                } else if self.eat('>') {
                    Some(SweepOrder::Forward)
                } else {
                    None
                };
                let args = if !self.opens_steps() && self.eat('(') {
                    Some(self.list(')')?)
                } else {
                    None
                };
                Ok(Step::Apply(Apply {
                    name,
                    name_span,
                    group,
                    order,
                    args,
                    span: start..self.prev_end(),
                }))
            }
            Some(Tok::Lower(name)) if name == "prk" => {
                self.pos += 1;
                self.prk(start)
            }
            Some(Tok::Punct('(')) => self.nested(|p| p.repeat(start)),
            Some(Tok::Punct('{')) => self.nested(|p| p.adjusted(start)),
            Some(Tok::Lower(name)) if ["let", "def", "param"].contains(&name.as_str()) => {
                Err(Diagnostic::new(
                    format!(
                        "'{name}' starts a definition, which cannot stand inside a sub-scheme's body or a repetition"
                    ),
                    self.here(),
                ))
            }
            Some(Tok::Lower(name)) => Err(Diagnostic::new(
                format!(
                    "unknown sub-flow '{name}' at position {}; names of sub-flows and sub-schemes start with an uppercase letter (constants like '{name}' go inside parentheses, as in A({name}))",
                    position(self.src, start)
                ),
                self.here(),
            )),
            _ => Err(self.expected(
                "a sub-flow letter, a sub-scheme, a repetition '(...)^n', a Metropolis-adjusted part '{...}', 'prk', 'let' or 'def'",
            )),
        }
    }

    /// Whether the next token opens a parenthesis of steps (a repetition) rather than of
    /// coefficients: after any further `(`, a step starts with an uppercase name or `prk`,
    /// which no coefficient expression does. So `A (B A B)^2` is `A` followed by a
    /// repetition, while `A((1/2))` is `A` with one coefficient, and `A(NaN)` a coefficient
    /// that is refused as not finite.
    fn opens_steps(&self) -> bool {
        let mut k = self.pos;
        while matches!(self.tokens.get(k), Some(t) if t.tok == Tok::Punct('(')) {
            k += 1;
        }
        k > self.pos
            && self.tokens.get(k).is_some_and(|t| {
                is_step_start(&t.tok) && not_finite(self.src, t.span.start).is_none()
            })
    }

    /// `( steps )^count`, the `(` next.
    fn repeat(&mut self, start: usize) -> PResult<Step> {
        self.expect('(', "'('")?;
        let mut body = Vec::new();
        while !self.eat(')') {
            body.push(self.step()?);
        }
        if body.is_empty() {
            return Err(Diagnostic::new(
                "empty repetition: write the steps to repeat inside the parentheses, as in (B A B)^4",
                start..self.prev_end(),
            ));
        }
        if !self.eat('^') {
            return Err(self.expected("'^' and a count after the repeated steps, as in (B A B)^4"));
        }
        let count = self.atom()?;
        Ok(Step::Repeat(Repeat {
            body,
            count,
            span: start..self.prev_end(),
        }))
    }

    /// `{ steps }`, the `{` next: a Metropolis-adjusted part. Braces do not nest (one
    /// accept/reject per part; an inner one would have no energy difference of its own to test).
    fn adjusted(&mut self, start: usize) -> PResult<Step> {
        self.expect('{', "'{'")?;
        if self.peek() == Some(&Tok::Punct('}')) {
            return Err(Diagnostic::new(
                "empty braces: a Metropolis-adjusted part holds the A and B stages to accept or reject, as in {B(1/2) A B(1/2)} O",
                start..self.here().end,
            ));
        }
        let mut body = Vec::new();
        while !self.eat('}') {
            if self.peek() == Some(&Tok::Punct('{')) {
                return Err(Diagnostic::new(
                    "nested braces: a Metropolis-adjusted part cannot hold another; write one {...} around the whole Hamiltonian part",
                    self.here(),
                ));
            }
            body.push(self.step()?);
        }
        Ok(Step::Adjusted(Adjusted {
            body,
            span: start..self.prev_end(),
        }))
    }

    /// Comma-separated expressions up to `close` (the opening bracket is already consumed).
    fn list(&mut self, close: char) -> PResult<Vec<Expr>> {
        let mut items = vec![self.expr()?];
        while !self.eat(close) {
            self.expect(',', &format!("',' or '{close}'"))?;
            items.push(self.expr()?);
        }
        Ok(items)
    }

    fn prk(&mut self, start: usize) -> PResult<Step> {
        self.expect('(', "'(' after 'prk'")?;
        let (mut b, mut bh, mut kick) = (None, None, None);
        loop {
            let (key, key_span) = self.lower("'b', 'bh' or 'kick'")?;
            self.expect('=', &format!("'=' after '{key}'"))?;
            let duplicate = match key.as_str() {
                "b" | "bh" => {
                    self.expect('[', &format!("'[' to start the {key} list"))?;
                    let list = self.list(']')?;
                    let slot = if key == "b" { &mut b } else { &mut bh };
                    slot.replace(list).is_some()
                }
                "kick" => {
                    let flow = match self.peek() {
                        Some(Tok::Upper(s)) if s == "F" => Flow::F,
                        Some(Tok::Upper(s)) if s == "B" => Flow::B,
                        _ => return Err(self.expected("'F' or 'B' after 'kick ='")),
                    };
                    self.pos += 1;
                    kick.replace(flow).is_some()
                }
                _ => {
                    return Err(Diagnostic::new(
                        format!("unknown prk argument '{key}'; expected b, bh or kick"),
                        key_span,
                    ))
                }
            };
            if duplicate {
                return Err(Diagnostic::new(
                    format!("prk argument '{key}' given twice"),
                    key_span,
                ));
            }
            if self.eat(')') {
                break;
            }
            self.expect(',', "',' or ')' in prk")?;
        }
        let span = start..self.prev_end();
        let (Some(b), Some(bh)) = (b, bh) else {
            return Err(Diagnostic::new(
                "prk needs both 'b = [...]' and 'bh = [...]'",
                span,
            ));
        };
        if b.len() != bh.len() {
            return Err(Diagnostic::new(
                format!(
                    "prk needs as many b entries as bh entries (found {} and {})",
                    b.len(),
                    bh.len()
                ),
                span,
            ));
        }
        Ok(Step::Prk(Prk {
            b,
            bh,
            kick: kick.unwrap_or(Flow::F),
            span,
        }))
    }

    /// Enters one more level of the expression tree.
    fn deeper(&mut self) -> PResult<()> {
        if self.depth >= MAX_NESTING {
            return Err(Diagnostic::new(
                format!("expression nested more than {MAX_NESTING} levels deep"),
                self.here(),
            ));
        }
        self.depth += 1;
        Ok(())
    }

    /// Runs `f` one level deeper (the depth is reset per item after an error).
    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        self.deeper()?;
        let r = f(self)?;
        self.depth -= 1;
        Ok(r)
    }

    /// `sum := product (('+' | '-') product)*`
    fn expr(&mut self) -> PResult<Expr> {
        self.nested(|p| {
            let saved = p.depth;
            let mut lhs = p.product()?;
            loop {
                let op = if p.eat('+') {
                    BinOp::Add
                } else if p.eat('-') {
                    BinOp::Sub
                } else {
                    p.depth = saved;
                    return Ok(lhs);
                };
                p.deeper()?;
                let rhs = p.product()?;
                lhs = binary(op, lhs, rhs);
            }
        })
    }

    /// `product := unary (('*' | '/') unary | power)*`, the bare `power` only right after a
    /// number literal or `)` (`2x1`, `3(1 + x)`, `(2/9)(1 + x)`).
    fn product(&mut self) -> PResult<Expr> {
        let saved = self.depth;
        let mut lhs = self.unary()?;
        loop {
            let juxtaposed = matches!(
                self.pos.checked_sub(1).and_then(|i| self.tokens.get(i)),
                Some(Token {
                    tok: Tok::Number(_) | Tok::Punct(')'),
                    ..
                })
            );
            let (op, rhs) = if self.eat('*') {
                (BinOp::Mul, self.unary()?)
            } else if self.eat('/') {
                (BinOp::Div, self.unary()?)
            } else if juxtaposed && matches!(self.peek(), Some(Tok::Lower(_) | Tok::Punct('('))) {
                (BinOp::Mul, self.power()?)
            } else {
                self.depth = saved;
                return Ok(lhs);
            };
            self.deeper()?;
            lhs = binary(op, lhs, rhs);
        }
    }

    /// `unary := ('-' | '+') unary | power`
    fn unary(&mut self) -> PResult<Expr> {
        let start = self.here().start;
        if self.eat('-') {
            let e = self.nested(Self::unary)?;
            Ok(Expr::Neg(Box::new(e), start..self.prev_end()))
        } else if self.eat('+') {
            self.nested(Self::unary)
        } else {
            self.power()
        }
    }

    /// `power := atom ('^' unary)?` (right associative: `2^3^2 = 2^9`).
    fn power(&mut self) -> PResult<Expr> {
        let base = self.atom()?;
        if self.eat('^') {
            let exp = self.nested(Self::unary)?;
            Ok(binary(BinOp::Pow, base, exp))
        } else {
            Ok(base)
        }
    }

    /// `atom := number | name | function '(' expr ')' | '(' expr ')'`
    fn atom(&mut self) -> PResult<Expr> {
        let span = self.here();
        match self.peek().cloned() {
            Some(Tok::Number(n)) => {
                self.pos += 1;
                Ok(Expr::Number(n, span))
            }
            Some(Tok::Lower(name)) => {
                self.pos += 1;
                if self.eat('(') {
                    let arg = self.expr()?;
                    self.expect(')', &format!("')' after the argument of {name}"))?;
                    Ok(Expr::Call(name, Box::new(arg), span.start..self.prev_end()))
                } else {
                    Ok(Expr::Name(name, span))
                }
            }
            Some(Tok::Punct('(')) => {
                self.pos += 1;
                let e = self.expr()?;
                self.expect(')', "')'")?;
                Ok(e)
            }
            Some(Tok::Upper(name)) => Err(match not_finite(self.src, span.start) {
                Some(word) => not_a_finite_number(word, span.start),
                None => Diagnostic::new(
                    format!("'{name}' is a sub-flow, not a number; constants are lowercase"),
                    span,
                ),
            }),
            _ => Err(self.expected("a number, a constant or '('")),
        }
    }
}

/// Whether `tok` starts a step inside parentheses: a sub-flow or sub-scheme name, or `prk`.
fn is_step_start(tok: &Tok) -> bool {
    match tok {
        Tok::Upper(_) | Tok::Punct('{') => true,
        Tok::Lower(name) => name == "prk",
        _ => false,
    }
}

/// The spelling of NaN or infinity (`NaN`, `Inf`, `infinity`, any case) starting at byte `at`.
pub fn not_finite(src: &str, at: usize) -> Option<&str> {
    let rest = src.get(at..)?;
    let len = rest
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(rest.len());
    let word = &rest[..len];
    ["nan", "inf", "infinity"]
        .contains(&word.to_ascii_lowercase().as_str())
        .then_some(word)
}

/// The error for a NaN or infinite coefficient spelled `word` at byte `at`.
pub fn not_a_finite_number(word: &str, at: usize) -> Diagnostic {
    Diagnostic::new(
        format!("'{word}' is not a finite number; coefficients must be finite"),
        at..at + word.len(),
    )
}

fn binary(op: BinOp, lhs: Expr, rhs: Expr) -> Expr {
    let span = lhs.span().start..rhs.span().end;
    Expr::Binary(op, Box::new(lhs), Box::new(rhs), span)
}
