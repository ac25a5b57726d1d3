//! Design of a scheme family (`dpd design`): order first, then the error norm.
//!
//! 1. The orders at a generic point of the box are what almost every member reaches. For
//!    each invariant-measure order from there up to [`MAX_INVARIANT_ORDER`] the highest
//!    deterministic order (up to [`MAX_DETERMINISTIC_ORDER`]) with a solution is found: the
//!    order conditions ([`crate::analysis::order_residuals`]) are solved by Levenberg-Marquardt
//!    from every point of a grid over the box ([`GRID`] points per parameter), raising the deterministic order until no solution is found. The pairs of
//!    orders not beaten in both are the family's highest orders.
//! 2. Where the solutions form a set of positive dimension (fewer independent conditions than
//!    parameters, as in a family without conditions beyond its generic orders), the error norm
//!    is minimised over that set by a pattern search whose trial points are projected back
//!    onto the set by the same solver.
//!
//! The norm minimised is the invariant-measure error norm when the family has a thermostat
//! and the criterion applies, else the deterministic one ([`Objective`]).

mod solve;

use crate::analysis::{order_residuals, Analysis};
use crate::lang::{Family, Options};
use serde::Serialize;
use solve::{newton, rank, rationalise, Residuals};

/// Highest deterministic order the design solves for.
pub const MAX_DETERMINISTIC_ORDER: u32 = 6;
/// Highest invariant-measure order the design solves for.
pub const MAX_INVARIANT_ORDER: u32 = 4;
/// Grid points per parameter for the starts of the solver (3 parameters: 7^3 starts).
pub const GRID: [usize; 3] = [21, 11, 7];
/// Pair generators per sweep in the invariant-measure model (as in the analysis default).
const PAIRS: usize = 2;

/// Which error norm the design minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    Deterministic,
    InvariantMeasure,
}

/// One member of the family with its orders, norms and costs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Member {
    /// Parameter values in declaration order, with their names.
    pub parameters: Vec<(String, f64)>,
    /// The merged stages.
    pub program: String,
    pub deterministic_order: u32,
    pub invariant_measure_order: Option<u32>,
    pub deterministic_error_norm: Option<f64>,
    pub invariant_measure_error_norm: Option<f64>,
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
    /// Dimension of the solution set through this point (0: an isolated solution).
    pub freedom: usize,
    /// Set when the norm keeps decreasing towards an end of a range where the scheme cannot be
    /// built (a sweep would get a zero step): the member is then only a point next to the
    /// infimum, which this names, e.g. `c -> 0`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<String>,
}

/// The result of [`design`].
#[derive(Clone, Debug, Serialize)]
pub struct Design {
    pub family: String,
    pub objective: Objective,
    /// Orders at a generic point, (deterministic, invariant-measure).
    pub generic_orders: (u32, Option<u32>),
    /// The highest order pairs with solutions, each with its best members, lowest norm first.
    pub solutions: Vec<Member>,
    /// Members at the notable points: the ends of each range and the fractions with a
    /// denominator up to 6 inside it (one-parameter families), plus the points asked for.
    pub notable: Vec<Member>,
}

/// A member at `x`, or `None` if the scheme cannot be built there.
pub fn member(family: &Family, x: &[f64], freedom: usize) -> Option<Member> {
    let options = Options {
        allow_inconsistent: true,
    };
    let program = family.at_with(x, &options).ok()?;
    let a: Analysis = program.analysis();
    let cost = program.evaluations_per_step();
    Some(Member {
        parameters: family
            .names()
            .into_iter()
            .map(String::from)
            .zip(x.iter().copied())
            .collect(),
        program: program.to_string(),
        deterministic_order: a.deterministic_order,
        invariant_measure_order: a.invariant_measure_order,
        deterministic_error_norm: a.deterministic_error_norm,
        invariant_measure_error_norm: a.invariant_measure_error_norm,
        force_evaluations_per_step: cost.force,
        pair_distance_evaluations_per_step: cost.pair_distance,
        freedom,
        limit: None,
    })
}

impl Objective {
    /// The norm this objective minimises, of an analysis (`None`: order above the highest
    /// checked, or no invariant-measure analysis).
    pub fn norm_of(self, a: &Analysis) -> Option<f64> {
        match self {
            Objective::Deterministic => a.deterministic_error_norm,
            Objective::InvariantMeasure => a.invariant_measure_error_norm,
        }
    }
}

impl Member {
    /// The norm of `objective`; a missing norm (order above the highest checked) counts as
    /// zero.
    pub fn norm(&self, objective: Objective) -> f64 {
        match objective {
            Objective::Deterministic => self.deterministic_error_norm,
            Objective::InvariantMeasure => self.invariant_measure_error_norm,
        }
        .unwrap_or(0.0)
    }

    /// The (deterministic, invariant-measure) orders.
    pub fn orders(&self) -> (u32, Option<u32>) {
        (self.deterministic_order, self.invariant_measure_order)
    }
}

/// Designs `family`; `extra` are further points to report (each one value per parameter).
pub fn design(family: &Family, extra: &[Vec<f64>]) -> Option<Design> {
    let generic = member(family, &family.generic_point(), family.parameters.len())?;
    let objective = if generic.invariant_measure_order.is_some()
        && family
            .at_with(
                &family.generic_point(),
                &Options {
                    allow_inconsistent: true,
                },
            )
            .ok()?
            .stages
            .iter()
            .any(|s| s.flow.is_stochastic())
    {
        Objective::InvariantMeasure
    } else {
        Objective::Deterministic
    };
    let bounds: Vec<(f64, f64)> = family.parameters.iter().map(|p| (p.lo, p.hi)).collect();
    let starts = grid(&bounds);
    let inv_range: Vec<Option<u32>> = match generic.invariant_measure_order {
        Some(p) => (p..=MAX_INVARIANT_ORDER.max(p)).map(Some).collect(),
        None => vec![None],
    };
    let mut solutions: Vec<Member> = Vec::new();
    let mut best_det = MAX_DETERMINISTIC_ORDER;
    for inv in inv_range {
        // the highest deterministic order with a solution at this invariant-measure order
        // (solvable orders are downward closed: search upwards, stop at the first failure)
        let mut found = None;
        for det in generic.deterministic_order..=best_det {
            let f = conditions(family, det, inv.unwrap_or(0));
            // A root the analysis does not confirm is dropped: the conditions vanish there only
            // to within the solver's tolerance, e.g. next to a boundary where a stage vanishes.
            let mut points = solve_all(&f, &starts, &bounds);
            points.retain(|x| {
                member(family, &rationalise(&f, x), 0).is_some_and(|m| m.orders() >= (det, inv))
            });
            if points.is_empty() {
                break;
            }
            found = Some((det, points, f));
        }
        let Some((det, points, f)) = found else {
            break;
        };
        let mut members: Vec<Member> = points
            .iter()
            .filter_map(|x| member(family, &rationalise(&f, x), x.len() - rank(&f, x)))
            .collect();
        if members.iter().any(|m| m.freedom > 0) {
            let best = minimise(family, &f, &members, &bounds, objective)?;
            let x: Vec<f64> = best.parameters.iter().map(|(_, v)| *v).collect();
            let mut optimum = member(family, &rationalise(&f, &x), best.freedom)
                .filter(|m| m.orders() >= best.orders())
                .unwrap_or(best);
            optimum.limit = unbuildable_limit(family, &x, &bounds);
            members = vec![optimum];
        }
        members.sort_by(|a, b| a.norm(objective).total_cmp(&b.norm(objective)));
        // a higher invariant-measure order at the same deterministic order beats the lower
        solutions.retain(|s| s.deterministic_order > det);
        solutions.extend(members);
        best_det = det;
    }
    let mut notable: Vec<Vec<f64>> = extra.to_vec();
    if let [(lo, hi)] = bounds[..] {
        notable.extend([lo, hi].map(|v| vec![v]));
        for q in 2..=6 {
            for p in (lo * q as f64).ceil() as i64..=(hi * q as f64).floor() as i64 {
                let v = p as f64 / q as f64;
                if v > lo && v < hi && !notable.iter().any(|n| n[0] == v) {
                    notable.push(vec![v]);
                }
            }
        }
        notable.sort_by(|a, b| a[0].total_cmp(&b[0]));
    }
    let notable = notable
        .iter()
        .filter(|x| x.len() == bounds.len())
        .filter_map(|x| member(family, x, 0))
        .collect();
    Some(Design {
        family: family.source().to_string(),
        objective,
        generic_orders: (generic.deterministic_order, generic.invariant_measure_order),
        solutions,
        notable,
    })
}

/// `name -> end` for the first parameter of `x` that lies within the minimiser's resolution
/// of an end of its range where the family cannot be built.
fn unbuildable_limit(family: &Family, x: &[f64], bounds: &[(f64, f64)]) -> Option<String> {
    let names = family.names();
    bounds.iter().enumerate().find_map(|(k, &(lo, hi))| {
        let end = [lo, hi]
            .into_iter()
            .find(|end| (x[k] - end).abs() <= 1e-6 * (hi - lo))?;
        let mut at = x.to_vec();
        at[k] = end;
        member(family, &at, 0)
            .is_none()
            .then(|| format!("{} -> {end}", names[k]))
    })
}

/// The residuals of the order conditions (deterministic order `det`, invariant-measure
/// order `inv`) as a function of the parameters.
fn conditions(family: &Family, det: u32, inv: u32) -> impl Fn(&[f64]) -> Option<Vec<f64>> + '_ {
    move |x: &[f64]| {
        let options = Options {
            allow_inconsistent: true,
        };
        let p = family.at_with(x, &options).ok()?;
        order_residuals(&p.unmerged_stages, det, inv, PAIRS)
    }
}

/// The grid of starting points over the box.
fn grid(bounds: &[(f64, f64)]) -> Vec<Vec<f64>> {
    let n = GRID[bounds.len().clamp(1, GRID.len()) - 1];
    let mut points = vec![Vec::new()];
    for &(lo, hi) in bounds {
        points = points
            .into_iter()
            .flat_map(|p: Vec<f64>| {
                (0..n).map(move |i| {
                    let mut q = p.clone();
                    q.push(lo + (hi - lo) * i as f64 / (n - 1) as f64);
                    q
                })
            })
            .collect();
    }
    points
}

/// Every distinct solution reached from `starts` (closer than 1e-6 of the ranges: the same).
fn solve_all(f: &Residuals, starts: &[Vec<f64>], bounds: &[(f64, f64)]) -> Vec<Vec<f64>> {
    let mut found: Vec<Vec<f64>> = Vec::new();
    for x0 in starts {
        let Some(x) = newton(f, x0, bounds) else {
            continue;
        };
        let same = |y: &Vec<f64>| {
            y.iter()
                .zip(&x)
                .zip(bounds)
                .all(|((a, b), (lo, hi))| (a - b).abs() <= 1e-6 * (hi - lo))
        };
        if !found.iter().any(same) {
            found.push(x);
        }
    }
    found
}

/// The member of least norm on the solution set through `members`: a pattern search from
/// the best of them, each trial point clamped to the box and projected onto the set.
fn minimise(
    family: &Family,
    f: &Residuals,
    members: &[Member],
    bounds: &[(f64, f64)],
    objective: Objective,
) -> Option<Member> {
    let value = |m: &Member| m.norm(objective);
    let mut best = members
        .iter()
        .min_by(|a, b| value(a).total_cmp(&value(b)))?
        .clone();
    let values = |m: &Member| m.parameters.iter().map(|(_, v)| *v).collect::<Vec<f64>>();
    let mut step: Vec<f64> = bounds.iter().map(|(lo, hi)| (hi - lo) / 20.0).collect();
    while step
        .iter()
        .zip(bounds)
        .any(|(s, (lo, hi))| *s > 1e-10 * (hi - lo))
    {
        let mut improved = false;
        for k in 0..bounds.len() {
            for sign in [-1.0, 1.0] {
                let mut x = values(&best);
                x[k] = (x[k] + sign * step[k]).clamp(bounds[k].0, bounds[k].1);
                let Some(x) = newton(f, &x, bounds) else {
                    continue;
                };
                let Some(m) = member(family, &x, best.freedom) else {
                    continue;
                };
                // a point where rounding hides the orders solved for is not a better member
                if m.orders() == best.orders() && value(&m) < value(&best) {
                    best = m;
                    improved = true;
                }
            }
        }
        if !improved {
            step.iter_mut().for_each(|s| *s /= 2.0);
        }
    }
    Some(best)
}
