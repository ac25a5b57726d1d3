//! The member of a scheme family with the longest predicted critical step per force
//! evaluation (`dpd design --objective predicted`).
//!
//! The objective is not smooth (it is flat where the stability limit decides and kinks where
//! a mode's error takes over), so the search is a grid over the family's box followed by a
//! compass search (each parameter stepped up and down, the step halved when no neighbour is
//! better) from the best grid point.

use crate::predict::{Critical, Predictor, SEARCH_DT_MAX};
use dpd_ir::lang::Family;
use serde::Serialize;

/// Grid points per parameter for 1, 2 and 3 or more parameters.
const GRID: [usize; 3] = [41, 13, 7];
/// The compass search stops when its step is below this fraction of each range.
const TOLERANCE: f64 = 1e-4;

/// The best member found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Best {
    /// Parameter values in declaration order, with their names.
    pub parameters: Vec<(String, f64)>,
    /// The merged stages.
    pub program: String,
    pub critical_dt_10: Critical,
    pub force_evaluations_per_step: usize,
    /// The critical step per force evaluation (a step beyond the search counts as its end).
    pub efficiency: f64,
    /// Members predicted.
    pub evaluated: usize,
}

/// The member of `family` (inside its box) with the largest predicted critical step of 10 %
/// T_C error per force evaluation, searched from the grid and the points `also` (e.g. the
/// norm design's solutions and notable points, where a stage vanishes and the cost drops);
/// `None` when no point compiles.
pub fn best_member(family: &Family, predictor: &Predictor, also: &[Vec<f64>]) -> Option<Best> {
    let ranges: Vec<(f64, f64)> = family.parameters.iter().map(|p| (p.lo, p.hi)).collect();
    let mut evaluated = 0;
    let mut score = |x: &[f64]| -> f64 {
        evaluated += 1;
        efficiency(family, predictor, x).map_or(f64::NEG_INFINITY, |(e, _, _)| e)
    };
    let per = GRID[ranges.len().clamp(1, 3) - 1];
    // Cell centres, so that no end of a range (where a sweep may get a zero step) is tried.
    let mut best: Option<(Vec<f64>, f64)> = None;
    let total = per.pow(ranges.len() as u32);
    let grid = (0..total).map(|k| {
        ranges
            .iter()
            .enumerate()
            .map(|(d, &(lo, hi))| {
                let i = (k / per.pow(d as u32)) % per;
                lo + (hi - lo) * (i as f64 + 0.5) / per as f64
            })
            .collect::<Vec<f64>>()
    });
    for x in grid.chain(also.iter().filter(|x| x.len() == ranges.len()).cloned()) {
        let s = score(&x);
        if best.as_ref().is_none_or(|(_, b)| s > *b) {
            best = Some((x, s));
        }
    }
    let (mut x, mut s) = best?;
    let mut step: Vec<f64> = ranges
        .iter()
        .map(|&(lo, hi)| (hi - lo) / per as f64 / 2.0)
        .collect();
    while step
        .iter()
        .zip(&ranges)
        .any(|(h, &(lo, hi))| *h > TOLERANCE * (hi - lo))
    {
        let mut moved = false;
        for d in 0..x.len() {
            for sign in [1.0, -1.0] {
                let mut y = x.clone();
                let (lo, hi) = ranges[d];
                y[d] = (y[d] + sign * step[d]).clamp(lo, hi);
                let t = score(&y);
                if t > s {
                    (x, s, moved) = (y, t, true);
                }
            }
        }
        if !moved {
            step.iter_mut().for_each(|h| *h /= 2.0);
        }
    }
    let (efficiency, critical, program) = efficiency(family, predictor, &x)?;
    Some(Best {
        parameters: family
            .parameters
            .iter()
            .map(|p| p.name.clone())
            .zip(x)
            .collect(),
        force_evaluations_per_step: program.force_evaluations_per_step(),
        program: program.to_string(),
        critical_dt_10: critical,
        efficiency,
        evaluated,
    })
}

/// The predicted critical step per force evaluation at `x`, with the critical step and the
/// program; `None` where the family does not compile or the prediction fails.
fn efficiency(
    family: &Family,
    predictor: &Predictor,
    x: &[f64],
) -> Option<(f64, Critical, dpd_ir::Program)> {
    let program = family.at(x).ok()?;
    let critical = predictor.critical_dt(&program, 0.1).ok()?;
    let dt = critical.dt().unwrap_or(SEARCH_DT_MAX);
    let forces = program.force_evaluations_per_step().max(1) as f64;
    Some((dt / forces, critical, program))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Spectrum;

    /// On one oscillator the search returns a member of the box at least as efficient as
    /// every point it was given and as McLachlan's l = 0.1932.
    #[test]
    fn the_best_member_beats_the_points_it_was_given() {
        let family =
            dpd_ir::lang::compile_family("param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O")
                .unwrap();
        let spectrum = Spectrum::oscillator(100.0, 4.5, 1.0);
        let predictor = Predictor::new(&spectrum);
        let given = [vec![0.1932], vec![0.25]];
        let best = best_member(&family, &predictor, &given).unwrap();
        let l = best.parameters[0].1;
        assert!((0.0..=0.5).contains(&l), "{l}");
        for x in &given {
            let (e, _, _) = efficiency(&family, &predictor, x).unwrap();
            assert!(best.efficiency >= e, "{} < {e} at {x:?}", best.efficiency);
        }
        assert!(best.evaluated > GRID[0]);
    }
}
