//! Checks of an expanded scheme. Each check is a small function saying why the rule exists.

use super::ast::Span;
use super::diagnostic::Diagnostic;
use super::expand::Application;
use super::letters::spelling;
use super::value::Value;
use super::Options;
use crate::forces::{kicks, ForceGroup, Kick};
use crate::program::Flow;
use num_traits::One;

/// Tolerance of the consistency check when a coefficient sum is not exact.
pub const SUM_TOLERANCE: f64 = 1e-12;

/// Every problem of `apps`, a scheme of source length `len`.
pub fn validate(apps: &[Application], len: usize, options: &Options) -> Vec<Diagnostic> {
    let whole = 0..len;
    if apps.is_empty() {
        return vec![Diagnostic::new(
            "empty scheme: write the sub-flows of one step, e.g. ABOBA",
            whole,
        )];
    }
    let mut errors = finite(apps);
    errors.extend(stochastic_steps_positive(apps));
    errors.extend(has_drift(apps, &whole));
    errors.extend(has_conservative_force(apps, &whole));
    errors.extend(one_thermostat(apps));
    errors.extend(adaptive_pair(apps));
    errors.extend(adjusted(apps));
    if !options.allow_inconsistent {
        errors.extend(consistent(apps));
    }
    errors
}

/// Every coefficient must be a finite `f64` at run time.
fn finite(apps: &[Application]) -> Vec<Diagnostic> {
    apps.iter()
        .filter_map(|a| a.coeff.to_coeff().err().map(|m| (m, a.span.clone())))
        .map(|(m, span)| Diagnostic::new(format!("non-finite coefficient: {m}"), span))
        .collect()
}

/// O, Ob, T and L cannot run backwards: the variance factor 1 - exp(-2 tau h) of the exact OU
/// step (L: the collision probability 1 - exp(-Gamma h)) turns negative for h < 0, and a zero
/// step is a wasted sweep.
fn stochastic_steps_positive(apps: &[Application]) -> Vec<Diagnostic> {
    apps.iter()
        .filter(|a| a.flow.needs_positive_step() && !a.coeff.is_positive())
        .map(|a| {
            Diagnostic::new(
                format!(
                    "{} is a stochastic sweep and cannot run backwards: its coefficient must be positive, found {}",
                    spelling(a.flow),
                    a.coeff
                ),
                a.span.clone(),
            )
        })
        .collect()
}

/// Without a drift the particles never move.
fn has_drift(apps: &[Application], whole: &Span) -> Option<Diagnostic> {
    (!apps.iter().any(|a| a.flow == Flow::A)).then(|| {
        Diagnostic::new(
            "scheme has no drift: it needs an A (or a sub-scheme or prk table containing one)",
            whole.clone(),
        )
    })
}

/// Without B, T or F (or their pair-group forms) the conservative pair force is never
/// applied.
fn has_conservative_force(apps: &[Application], whole: &Span) -> Option<Diagnostic> {
    let pair = Kick::Group(ForceGroup::Pair);
    (!apps.iter().any(|a| pair.advanced_by(a.flow, a.group))).then(|| {
        let bond_only = match apps.iter().any(|a| a.group == Some(ForceGroup::Bond)) {
            true => " (B[bond] applies the bonded forces only)",
            false => "",
        };
        Diagnostic::new(
            format!("scheme has no conservative force: it needs a B, T or F{bond_only}"),
            whole.clone(),
        )
    })
}

/// Lowe-Andersen collisions (L) thermostat a scheme alone: with the pairwise friction of O,
/// Ob, T or F as well, the step would approximate a dynamics with two thermostats, and the
/// order analysis counts every stochastic stage as one thermostat generator (its O sum).
fn one_thermostat(apps: &[Application]) -> Option<Diagnostic> {
    let collision = apps.iter().find(|a| a.flow == Flow::L)?;
    let friction = apps
        .iter()
        .find(|a| a.flow.is_stochastic() && a.flow != Flow::L)?;
    Some(Diagnostic::new(
        format!(
            "L (Lowe-Andersen collisions) cannot be combined with the pairwise friction of {}: a scheme thermostats with L alone or with O, Ob, T and F",
            spelling(friction.flow)
        ),
        collision.span.clone(),
    ))
}

/// The adaptive thermostats are an adaptive sweep, Oa (PAdL) or On (PNHL, without pair noise),
/// with friction xi gamma_ij, and Xi (the update of xi): the sweep without Xi is DPD at a frozen
/// friction, Xi without the sweep a variable nothing reads; and with another pairwise sweep (O,
/// Ob, T, F, L, or the other adaptive one) the step would approximate two thermostats at once.
fn adaptive_pair(apps: &[Application]) -> Option<Diagnostic> {
    let sweep = apps.iter().find(|a| matches!(a.flow, Flow::Oa | Flow::On));
    let xi = apps.iter().find(|a| a.flow == Flow::Xi);
    let other = |s: &Application| {
        apps.iter()
            .find(|a| a.flow.is_stochastic() && a.flow != s.flow)
    };
    let (message, at) = match (sweep, xi) {
        (None, None) => return None,
        (Some(s), _) if other(s).is_some() => (
            format!(
                "{} (the adaptive pairwise thermostat) cannot be combined with the pairwise thermostat of {}: a scheme thermostats with Oa and Xi or On and Xi alone",
                spelling(s.flow),
                spelling(other(s)?.flow)
            ),
            s,
        ),
        (Some(s), None) => (
            format!(
                "{} needs an Xi stage: its friction xi gamma_ij adapts only through the updates of xi by Xi (PAdL: e.g. B A Xi(1/2) Oa Xi(1/2) A B; PNHL: B A Xi(1/2) On Xi(1/2) A B)",
                spelling(s.flow)
            ),
            s,
        ),
        (None, Some(xi)) => (
            "Xi needs an Oa or On stage: xi scales the friction of the adaptive sweeps Oa and On, which no other letter reads".to_string(),
            xi,
        ),
        (Some(_), Some(_)) => return None,
    };
    Some(Diagnostic::new(message, at.span.clone()))
}

/// A Metropolis-adjusted scheme (`{B(1/2) A B(1/2)} O`) samples the Gibbs measure
/// `exp(-H / k_B T)` exactly when every part of the step leaves it invariant by itself: inside
/// the braces a deterministic, reversible, volume-preserving map (a symmetric word of A and B:
/// its inverse is itself with the momenta negated) followed by the accept/reject on
/// `exp(-Delta H / k_B T)`, with the momenta negated on rejection; outside the braces sweeps
/// that preserve it exactly per pair (O, Ob and L each move a pair's relative normal velocity
/// by an autoregression whose stationary law is the Maxwellian, at fixed positions).
fn adjusted(apps: &[Application]) -> Vec<Diagnostic> {
    if !apps.iter().any(|a| a.flow.is_brace()) {
        return Vec::new();
    }
    let mut errors = Vec::new();
    let mut open: Option<&Application> = None;
    let mut inside: Vec<&Application> = Vec::new();
    for a in apps {
        match (a.flow, open) {
            (Flow::Propose, _) => open = Some(a),
            (Flow::Accept, Some(brace)) => {
                errors.extend(asymmetric(&inside, brace));
                inside.clear();
                open = None;
            }
            (Flow::A | Flow::B, Some(_)) => inside.push(a),
            (flow, Some(_)) => errors.push(Diagnostic::new(
                format!(
                    "{} cannot stand inside braces: the accept/reject keeps the Gibbs measure exact only after a deterministic, reversible, volume-preserving map, a symmetric word of A and B (force groups allowed)",
                    spelling(flow),
                ),
                a.span.clone(),
            )),
            (Flow::O | Flow::Bbk | Flow::L, None) => {}
            (flow, None) => errors.push(Diagnostic::new(
                format!(
                    "{} cannot stand outside the braces of a Metropolis-adjusted scheme: {}",
                    spelling(flow),
                    match flow {
                        Flow::A | Flow::B => "it changes the energy, and only inside braces is that change tested; put every A and B inside",
                        Flow::T | Flow::F => "it does not leave the Gibbs measure invariant (T relaxes pairs towards the conservative force, F is an explicit kick); outside the braces only O, Ob and L, which preserve it exactly per pair, may stand",
                        _ => "the adaptive thermostat samples a measure extended by xi, not the Gibbs measure; outside the braces only O, Ob and L, which preserve it exactly per pair, may stand",
                    }
                ),
                a.span.clone(),
            )),
        }
    }
    errors
}

/// Why the A and B applications `inside` the braces opened at `brace` do not make a symmetric
/// word, if they do not: merged as the program merges them, mirrored stages must have the same
/// letter, force group and coefficient. Only then is the map its own inverse up to negated
/// momenta, which the accept/reject needs to keep the Gibbs measure exact.
fn asymmetric(inside: &[&Application], brace: &Application) -> Option<Diagnostic> {
    let mut merged: Vec<(Flow, Option<crate::forces::ForceGroup>, Value)> = Vec::new();
    for a in inside {
        match merged.last_mut() {
            Some((flow, group, c)) if *flow == a.flow && *group == a.group => {
                *c = c.add(&a.coeff).ok()?;
            }
            _ => merged.push((a.flow, a.group, a.coeff.clone())),
        }
        if merged.last().is_some_and(|(_, _, c)| c.is_zero()) {
            merged.pop();
        }
    }
    let spell = |(flow, group, c): &(Flow, Option<crate::forces::ForceGroup>, Value)| match group {
        Some(g) => format!(
            "{}[{}]({c})",
            spelling(*flow),
            super::letters::group_spelling(*g)
        ),
        None => format!("{}({c})", spelling(*flow)),
    };
    let n = merged.len();
    let (x, y) =
        merged
            .iter()
            .zip(merged.iter().rev())
            .take(n / 2)
            .find(|((f, g, c), (f2, g2, c2))| {
                let same = match (c.to_coeff(), c2.to_coeff()) {
                    (Ok(a), Ok(b)) => crate::program::coeffs_equal(&a, &b),
                    _ => false,
                };
                !(f == f2 && g == g2 && same)
            })?;
    Some(Diagnostic::new(
        format!(
            "the word inside the braces is not symmetric: {} mirrors {}; the accept/reject keeps the Gibbs measure exact only for a reversible proposal, a word that reads the same backwards with equal fractions, as B(1/2) A B(1/2) or A(1/2) B A(1/2)",
            spell(x),
            spell(y)
        ),
        brace.span.clone(),
    ))
}

/// A generator of the DPD dynamics (algorithms.md section 4): the drift, a kick (all forces,
/// or one force group in a scheme that names groups), the thermostat, and in adaptive schemes
/// the friction variable's update.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Generator {
    A,
    Kick(Kick),
    O,
    Xi,
}

impl Generator {
    /// Whether application `a` advances the generator (T and F carry a kick and O).
    fn advanced_by(self, a: &Application) -> bool {
        match self {
            Generator::A => a.flow == Flow::A,
            Generator::Kick(k) => k.advanced_by(a.flow, a.group),
            Generator::O => a.flow.is_stochastic(),
            Generator::Xi => a.flow == Flow::Xi,
        }
    }

    /// The generator and its carriers, for messages: `B[bond] (B, B[bond] and F stages)`.
    fn describe(self) -> String {
        match self {
            Generator::A => "A coefficients (A stages)".to_string(),
            Generator::Kick(k) => format!("{k} coefficients ({} stages)", k.carriers()),
            Generator::O => "O coefficients (O, Ob, T, F, L, Oa and On stages)".to_string(),
            Generator::Xi => "Xi coefficients (Xi stages)".to_string(),
        }
    }
}

/// First-order consistency: the step lengths of each generator add up to one step. A scheme
/// without any stochastic flow is a deterministic (Hamiltonian) scheme; its O sum is not
/// checked. In a scheme that names force groups each group it applies is a generator of its
/// own: a kick of the bonded forces cannot stand in for a kick of the pair forces.
fn consistent(apps: &[Application]) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    let kicks = kicks(apps.iter().map(|a| (a.flow, a.group)));
    let generators = std::iter::once(Generator::A)
        .chain(kicks.into_iter().map(Generator::Kick))
        .chain([Generator::O, Generator::Xi]);
    for g in generators {
        let of_g: Vec<&Application> = apps.iter().filter(|a| g.advanced_by(a)).collect();
        let (Some(first), Some(last)) = (of_g.first(), of_g.last()) else {
            continue;
        };
        let span = first.span.start..last.span.end;
        let mut sum = Value::int(0);
        for a in &of_g {
            match sum.add(&a.coeff) {
                Ok(s) => sum = s,
                Err(m) => {
                    errors.push(Diagnostic::new(m, span.clone()));
                    break;
                }
            }
        }
        let one = match &sum {
            Value::Exact(r) => r.is_one(),
            Value::Float(x) => (x - 1.0).abs() <= SUM_TOLERANCE,
        };
        if !one {
            errors.push(Diagnostic::new(
                format!(
                    "inconsistent scheme: the {} sum to {sum}, not 1; accept it anyway with allow_inconsistent (a flag of dpd_scheme!, a keyword of Python's Simulation, --allow-inconsistent of dpd run, dpd sweep and dpd export)",
                    g.describe()
                ),
                span,
            ));
        }
    }
    errors
}
