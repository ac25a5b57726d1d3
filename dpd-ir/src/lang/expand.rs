//! Name resolution and expansion of a parsed scheme into the flat sequence of applications,
//! including the default (implicit) step lengths.

use super::ast::{Adjusted, Apply, Def, Prk, Repeat, Script, Span, Step};
use super::diagnostic::{position, Diagnostic};
use super::expr::{eval, Scope, FUNCTIONS};
use super::letters::{group, group_spelling, group_spellings, letter, spellings, Letter};
use super::value::Value;
use crate::forces::ForceGroup;
use crate::program::{Flow, SweepOrder};
use num_traits::ToPrimitive;
use std::collections::{BTreeMap, HashMap};

/// Deepest chain of sub-scheme calls.
pub const MAX_CALL_DEPTH: usize = 32;
/// Most sub-flow applications one step may expand to.
pub const MAX_APPLICATIONS: usize = 10_000;

/// Words that cannot name a constant.
pub(crate) const RESERVED: [&str; 4] = ["let", "def", "prk", "param"];

/// One sub-flow application of the flattened step.
#[derive(Clone, Debug, PartialEq)]
pub struct Application {
    pub flow: Flow,
    /// The force group the letter names (`B[bond]`), if any.
    pub group: Option<ForceGroup>,
    pub coeff: Value,
    /// Sweep order written in the scheme (`O<`, `O>`), if any.
    pub order: Option<SweepOrder>,
    /// Frozen-noise group: applications with the same group share one random stream.
    pub noise: Option<usize>,
    /// The top-level item of the scheme this application comes from.
    pub span: Span,
}

/// Expands `script`, whose names may refer to the definitions of `prelude` (which `script`
/// may shadow) and to the free parameters bound to the values `bindings`. Returns the
/// applications in order, with implicit coefficients filled in.
pub fn expand(
    src: &str,
    script: &Script,
    prelude: &Script,
    bindings: &[(String, Value)],
) -> Result<Vec<Application>, Vec<Diagnostic>> {
    let mut x = Expander {
        src,
        consts: BTreeMap::new(),
        defs: BTreeMap::new(),
        out: Vec::new(),
        errors: Vec::new(),
        stack: Vec::new(),
        next_noise: 0,
        adjusting: false,
    };
    x.define(prelude, true);
    x.consts.extend(bindings.iter().cloned());
    x.define(script, false);
    for step in &script.steps {
        x.step(step, &[], step.span(), false);
    }
    if !x.errors.is_empty() {
        return Err(x.errors);
    }
    fill_implicit(x.out).map_err(|e| vec![e])
}

/// An application whose coefficient is still a placeholder unless `explicit`.
struct Pending {
    app: Application,
    explicit: bool,
}

struct Expander<'a> {
    src: &'a str,
    consts: BTreeMap<String, Value>,
    /// Sub-schemes, with whether they come from the prelude.
    defs: BTreeMap<String, (&'a Def, bool)>,
    out: Vec<Pending>,
    errors: Vec<Diagnostic>,
    /// Names of the sub-schemes being expanded, outermost first.
    stack: Vec<String>,
    next_noise: usize,
    /// Inside the braces of a Metropolis-adjusted part.
    adjusting: bool,
}

impl<'a> Expander<'a> {
    /// Records the constants and sub-schemes of `script`; `builtin` ones may be shadowed.
    fn define(&mut self, script: &'a Script, builtin: bool) {
        let mut user_consts: Vec<&str> = Vec::new();
        for l in &script.lets {
            if RESERVED.contains(&l.name.as_str()) || FUNCTIONS.iter().any(|(f, _)| *f == l.name) {
                self.errors.push(Diagnostic::new(
                    format!("'{}' is reserved and cannot name a constant", l.name),
                    l.name_span.clone(),
                ));
                continue;
            }
            if user_consts.contains(&l.name.as_str()) {
                self.errors.push(Diagnostic::new(
                    format!("constant '{}' is defined twice", l.name),
                    l.name_span.clone(),
                ));
                continue;
            }
            user_consts.push(&l.name);
            let scope = Scope {
                params: &[],
                consts: &self.consts,
            };
            match eval(&l.value, &scope) {
                Ok(v) => {
                    self.consts.insert(l.name.clone(), v);
                }
                Err(e) => self.errors.push(e),
            }
        }
        let mut user_defs: Vec<&str> = Vec::new();
        for d in &script.defs {
            let problem = if letter(&d.name).is_some() {
                Some(format!(
                    "'{}' is a sub-flow letter and cannot be redefined",
                    d.name
                ))
            } else if user_defs.contains(&d.name.as_str()) {
                Some(format!("sub-scheme '{}' is defined twice", d.name))
            } else {
                d.params
                    .iter()
                    .enumerate()
                    .find(|(i, (p, _))| d.params[..*i].iter().any(|(q, _)| q == p))
                    .map(|(_, (p, _))| format!("parameter '{p}' of '{}' is listed twice", d.name))
            };
            if let Some(message) = problem {
                self.errors
                    .push(Diagnostic::new(message, d.name_span.clone()));
                continue;
            }
            user_defs.push(&d.name);
            self.defs.insert(d.name.clone(), (d, builtin));
        }
    }

    /// Expands one step. `site` is the span of the top-level item being expanded; inside
    /// prelude definitions (`builtin`) every error points there.
    fn step(&mut self, step: &Step, params: &[(String, Value)], site: Span, builtin: bool) {
        if self.out.len() > MAX_APPLICATIONS {
            return; // already reported
        }
        let result = match step {
            Step::Apply(a) => self.apply(a, params, &site, builtin),
            Step::Prk(p) => self.prk(p, params, &site),
            Step::Repeat(r) => self.repeat(r, params, &site, builtin),
            Step::Adjusted(a) => self.adjusted(a, params, &site, builtin),
        };
        if let Err(mut e) = result {
            if builtin {
                e.span = site;
            }
            self.errors.push(e);
        }
    }

    /// Appends an application; the one past the limit is kept as a marker that the
    /// overflow was reported, and stops the expansion.
    fn push(&mut self, app: Application, explicit: bool) -> Result<(), Diagnostic> {
        if self.out.len() >= MAX_APPLICATIONS {
            let span = app.span.clone();
            self.out.push(Pending { app, explicit });
            return Err(Diagnostic::new(
                format!("scheme expands to more than {MAX_APPLICATIONS} sub-flow applications"),
                span,
            ));
        }
        self.out.push(Pending { app, explicit });
        Ok(())
    }

    fn apply(
        &mut self,
        a: &Apply,
        params: &[(String, Value)],
        site: &Span,
        builtin: bool,
    ) -> Result<(), Diagnostic> {
        let args = self.args(a, params)?;
        if let Some(l) = letter(&a.name) {
            if a.order.is_some() && !l.flow.is_successive_sweep() {
                return Err(Diagnostic::new(
                    format!(
                        "sweep order '<' or '>' only applies to the successive sweeps O, Ob, T and L, not to {}",
                        a.name
                    ),
                    a.span.clone(),
                ));
            }
            let coeff = match args.as_deref() {
                None => None,
                Some([c]) => Some(c.clone()),
                Some(more) => {
                    return Err(Diagnostic::new(
                        format!(
                            "wrong number of arguments: {} takes one coefficient, found {}",
                            a.name,
                            more.len()
                        ),
                        a.span.clone(),
                    ))
                }
            };
            let explicit = coeff.is_some();
            let app = Application {
                flow: l.flow,
                group: force_group(self.src, l, a)?,
                coeff: coeff.unwrap_or(Value::int(0)),
                order: a.order,
                noise: None,
                span: site.clone(),
            };
            return self.push(app, explicit);
        }
        let Some(&(def, def_builtin)) = self.defs.get(&a.name) else {
            let defined: Vec<&str> = self.defs.keys().map(String::as_str).collect();
            return Err(Diagnostic::new(
                format!(
                    "unknown sub-flow '{}' at position {}; expected one of {}, {} or a defined name",
                    a.name,
                    position(self.src, a.name_span.start),
                    spellings(),
                    defined.join(", ")
                ),
                a.name_span.clone(),
            ));
        };
        if a.order.is_some() {
            return Err(Diagnostic::new(
                format!(
                    "sweep order '<' or '>' applies to letters, not to the sub-scheme {}",
                    a.name
                ),
                a.span.clone(),
            ));
        }
        if let Some((_, span)) = &a.group {
            return Err(Diagnostic::new(
                format!(
                    "force groups select the forces of the kick letters B and F, not of the sub-scheme {}; write the group on its letters",
                    a.name
                ),
                span.clone(),
            ));
        }
        let args = args.unwrap_or_default();
        if args.len() != def.params.len() {
            let names: Vec<&str> = def.params.iter().map(|(p, _)| p.as_str()).collect();
            return Err(Diagnostic::new(
                format!(
                    "wrong number of arguments: {}({}) takes {}, found {}",
                    a.name,
                    names.join(", "),
                    def.params.len(),
                    args.len()
                ),
                a.span.clone(),
            ));
        }
        if self.stack.contains(&a.name) {
            return Err(Diagnostic::new(
                format!(
                    "recursive sub-scheme: {} -> {}",
                    self.stack.join(" -> "),
                    a.name
                ),
                a.name_span.clone(),
            ));
        }
        if self.stack.len() >= MAX_CALL_DEPTH {
            return Err(Diagnostic::new(
                format!("sub-schemes nested more than {MAX_CALL_DEPTH} deep"),
                a.name_span.clone(),
            ));
        }
        let bound: Vec<(String, Value)> = def
            .params
            .iter()
            .map(|(p, _)| p.clone())
            .zip(args)
            .collect();
        self.stack.push(a.name.clone());
        for step in &def.body {
            self.step(step, &bound, site.clone(), builtin || def_builtin);
        }
        self.stack.pop();
        Ok(())
    }

    /// Where errors of `step`, nested in a repetition or braces at `site`, point: at the top
    /// level of the scheme each nested step is its own site; inside a sub-scheme the call stays
    /// the site.
    fn site_of(&self, step: &Step, site: &Span, builtin: bool) -> Span {
        if self.stack.is_empty() && !builtin {
            step.span()
        } else {
            site.clone()
        }
    }

    /// The body of `a` between the markers `{` ([`Flow::Propose`]) and `}` ([`Flow::Accept`]).
    /// Braces reached through a sub-scheme called inside braces are nested, and refused.
    fn adjusted(
        &mut self,
        a: &Adjusted,
        params: &[(String, Value)],
        site: &Span,
        builtin: bool,
    ) -> Result<(), Diagnostic> {
        if self.adjusting {
            return Err(Diagnostic::new(
                "nested braces: a Metropolis-adjusted part cannot hold another (here through a sub-scheme); write one {...} around the whole Hamiltonian part",
                a.span.clone(),
            ));
        }
        let marker = |flow| Application {
            flow,
            group: None,
            coeff: Value::int(0),
            order: None,
            noise: None,
            span: site.clone(),
        };
        self.push(marker(Flow::Propose), true)?;
        self.adjusting = true;
        for step in &a.body {
            self.step(step, params, self.site_of(step, site, builtin), builtin);
        }
        self.adjusting = false;
        self.push(marker(Flow::Accept), true)
    }

    /// The evaluated arguments of `a`, `None` without parentheses.
    fn args(
        &self,
        a: &Apply,
        params: &[(String, Value)],
    ) -> Result<Option<Vec<Value>>, Diagnostic> {
        let scope = Scope {
            params,
            consts: &self.consts,
        };
        a.args
            .as_ref()
            .map(|args| args.iter().map(|e| eval(e, &scope)).collect())
            .transpose()
    }

    /// Expands the body of `r` as many times as its count says (sites as [`Self::site_of`]).
    fn repeat(
        &mut self,
        r: &Repeat,
        params: &[(String, Value)],
        site: &Span,
        builtin: bool,
    ) -> Result<(), Diagnostic> {
        let scope = Scope {
            params,
            consts: &self.consts,
        };
        let count = repeat_count(&eval(&r.count, &scope)?, r.count.span())?;
        let errors = self.errors.len();
        for _ in 0..count {
            for step in &r.body {
                self.step(step, params, self.site_of(step, site, builtin), builtin);
            }
            // One pass reports every error of the body; the expansion limit stops the rest.
            if self.errors.len() > errors || self.out.len() > MAX_APPLICATIONS {
                break;
            }
        }
        Ok(())
    }

    fn prk(&mut self, p: &Prk, params: &[(String, Value)], site: &Span) -> Result<(), Diagnostic> {
        let scope = Scope {
            params,
            consts: &self.consts,
        };
        let b =
            p.b.iter()
                .map(|e| eval(e, &scope))
                .collect::<Result<Vec<_>, _>>()?;
        let bh =
            p.bh.iter()
                .map(|e| eval(e, &scope))
                .collect::<Result<Vec<_>, _>>()?;
        let noise = (p.kick == Flow::F).then(|| {
            self.next_noise += 1;
            self.next_noise
        });
        for (kick, drift) in b.into_iter().zip(bh) {
            for (flow, coeff, noise) in [(p.kick, kick, noise), (Flow::A, drift, None)] {
                let app = Application {
                    flow,
                    group: None,
                    coeff,
                    order: None,
                    noise,
                    span: site.clone(),
                };
                self.push(app, true)?;
            }
        }
        Ok(())
    }
}

/// The force group `a` names for the letter `l`, checked against the groups it takes.
fn force_group(src: &str, l: &Letter, a: &Apply) -> Result<Option<ForceGroup>, Diagnostic> {
    let Some((name, span)) = &a.group else {
        return Ok(None);
    };
    let at = |m: String| Err(Diagnostic::new(m, span.clone()));
    let Some(g) = group(name) else {
        return at(format!(
            "unknown force group '{name}' at position {}; expected one of {}",
            position(src, span.start),
            group_spellings()
        ));
    };
    if l.groups.contains(&g.group) {
        return Ok(Some(g.group));
    }
    let takes: Vec<&str> = l.groups.iter().map(|&g| group_spelling(g)).collect();
    at(match (takes.is_empty(), g.group) {
        (true, _) => format!(
            "{} takes no force group: groups select the forces of the kick letters B and F",
            l.spelling
        ),
        (false, ForceGroup::Bond) => format!(
            "{}[bond] is not a sub-flow: the bonded forces have no dissipative or random part, so their kick is B[bond]",
            l.spelling
        ),
        (false, _) => format!(
            "{} takes the force group {}, not {name}",
            l.spelling,
            takes.join(", ")
        ),
    })
}

/// The number of times a repetition runs: a positive integer, at most
/// [`MAX_APPLICATIONS`] (each pass adds at least one application).
fn repeat_count(count: &Value, span: Span) -> Result<usize, Diagnostic> {
    let n = match count {
        Value::Exact(r) if r.is_integer() => r.to_integer().to_usize(),
        _ => None,
    };
    n.filter(|n| (1..=MAX_APPLICATIONS).contains(n)).ok_or_else(|| {
        Diagnostic::new(
            format!(
                "a repetition count must be a whole number from 1 to {MAX_APPLICATIONS}, found {count}"
            ),
            span,
        )
    })
}

/// Gives every implicit application of a letter (with its force group) an equal share of
/// what the explicit applications of the same letter and group leave of 1.
fn fill_implicit(pending: Vec<Pending>) -> Result<Vec<Application>, Diagnostic> {
    let mut shares = HashMap::new();
    let groups = std::iter::once(None).chain(ForceGroup::ALL.map(Some));
    for (flow, group) in Flow::ALL
        .into_iter()
        .flat_map(|f| groups.clone().map(move |g| (f, g)))
    {
        let of_flow = || {
            pending
                .iter()
                .filter(|p| p.app.flow == flow && p.app.group == group)
        };
        let Some(first) = of_flow().find(|p| !p.explicit) else {
            continue;
        };
        let at = |m: String| Diagnostic::new(m, first.app.span.clone());
        let mut rest = Value::int(1);
        for p in of_flow().filter(|p| p.explicit) {
            rest = rest.sub(&p.app.coeff).map_err(at)?;
        }
        let implicit = of_flow().filter(|p| !p.explicit).count();
        let count = Value::int(i64::try_from(implicit).unwrap_or(i64::MAX));
        shares.insert((flow, group), rest.div(&count).map_err(at)?);
    }
    Ok(pending
        .into_iter()
        .map(|p| {
            let mut app = p.app;
            if let (false, Some(share)) = (p.explicit, shares.get(&(app.flow, app.group))) {
                app.coeff = share.clone();
            }
            app
        })
        .collect())
}
