//! Lowering of validated applications to a [`Program`]: sweep orders, merging, streams.

use super::diagnostic::Diagnostic;
use super::expand::Application;
use crate::program::{Flow, Program, Stage, SweepOrder};
use std::collections::HashMap;

/// Most random streams one step may use (stream numbers are `u8`).
pub const MAX_STREAMS: usize = 255;

/// The program of the validated applications `apps` of `source`.
pub fn lower(source: &str, apps: Vec<Application>) -> Result<Program, Vec<Diagnostic>> {
    let apps = with_sweep_orders(apps);
    let unmerged_stages = stages(&apps)?;
    let stages = stages(&merge(apps)?)?;
    Ok(Program {
        source: source.to_string(),
        stages,
        unmerged_stages,
    })
}

/// Successive sweeps without an explicit order alternate Forward, Reverse, Forward, ... in
/// order of appearance (counting all O, Ob, T and L sweeps of the step); other flows are Forward.
fn with_sweep_orders(mut apps: Vec<Application>) -> Vec<Application> {
    let mut sweeps = 0;
    for a in &mut apps {
        if a.flow.is_successive_sweep() {
            a.order = Some(a.order.unwrap_or(SweepOrder::alternating(sweeps)));
            sweeps += 1;
        } else {
            a.order = Some(SweepOrder::Forward);
        }
    }
    apps
}

/// Whether two adjacent applications of `flow` are one application of the summed length:
/// drifts commute, and a kick reuses its force while positions do not change. Sweeps never
/// merge: each is a separate pass with its own random stream; nor do the braces.
fn merges(flow: Flow) -> bool {
    !flow.is_successive_sweep() && !flow.is_brace()
}

/// Merges adjacent applications of the same merging flow and force group (`B B[pair]` are two
/// kicks of different forces) and drops those left with a zero
/// coefficient (which may make their neighbours adjacent). A merged F keeps the noise of its
/// first part, as the force evaluation (noise included) is reused.
fn merge(apps: Vec<Application>) -> Result<Vec<Application>, Vec<Diagnostic>> {
    let mut merged: Vec<Application> = Vec::with_capacity(apps.len());
    for a in apps {
        match merged.last_mut() {
            Some(top) if top.flow == a.flow && top.group == a.group && merges(a.flow) => {
                top.coeff = top
                    .coeff
                    .add(&a.coeff)
                    .map_err(|m| vec![Diagnostic::new(m, a.span.clone())])?;
                top.span = top.span.start.min(a.span.start)..top.span.end.max(a.span.end);
            }
            _ => merged.push(a),
        }
        if merged
            .last()
            .is_some_and(|t| t.coeff.is_zero() && merges(t.flow))
        {
            merged.pop();
        }
    }
    Ok(merged)
}

/// Stages of `apps`: each stochastic application takes the next random stream, except that
/// applications of one frozen-noise group share the stream of the group's first one. An
/// accept/reject `}` draws from a stream apart (so `{B A B} O` sweeps with the noise of
/// `B A B O`): its stream field numbers the Metropolis-adjusted parts, 0, 1, ...; so does an
/// Xi's field number the Xi stages (their noise, with a thermostat friction, is drawn apart).
fn stages(apps: &[Application]) -> Result<Vec<Stage>, Vec<Diagnostic>> {
    let mut next = 0usize;
    let mut counts = [0usize; 2];
    let mut groups: HashMap<usize, u8> = HashMap::new();
    let mut errors = Vec::new();
    let mut out = Vec::with_capacity(apps.len());
    for a in apps {
        let mut stream = 0;
        // `}` numbers the Metropolis-adjusted parts, Xi its own stages, each from 0.
        let counted = match a.flow {
            Flow::Accept => Some((0, "Metropolis-adjusted parts")),
            Flow::Xi => Some((1, "Xi stages")),
            _ => None,
        };
        if let Some((k, what)) = counted {
            let Ok(number) = u8::try_from(counts[k]) else {
                errors.push(Diagnostic::new(
                    format!("scheme has more than 256 {what} per step"),
                    a.span.clone(),
                ));
                break;
            };
            stream = number;
            counts[k] += 1;
        } else if a.flow.is_stochastic() {
            if let Some(&s) = a.noise.and_then(|g| groups.get(&g)) {
                stream = s;
            } else if let Some(s) = u8::try_from(next).ok().filter(|_| next < MAX_STREAMS) {
                stream = s;
                next += 1;
                if let Some(g) = a.noise {
                    groups.insert(g, s);
                }
            } else {
                errors.push(Diagnostic::new(
                    format!("scheme needs more than {MAX_STREAMS} random streams per step"),
                    a.span.clone(),
                ));
                break;
            }
        }
        match a.coeff.to_coeff() {
            Ok(coeff) => out.push(Stage {
                flow: a.flow,
                coeff,
                stream,
                order: a.order.unwrap_or_default(),
                group: a.group,
            }),
            Err(m) => errors.push(Diagnostic::new(m, a.span.clone())),
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}
