//! The flattened form of a scheme: the sequence of sub-flow applications of one step.
//!
//! This is the contract between the language front end (`lang`), the order analysis
//! (`analysis`), the proc macro (which turns a [`Program`] into straight-line calls) and the
//! run-time interpreter in `dpd-core` (which walks the same stages). Both back ends call the
//! same core function for each [`Stage`] with the same `f64` coefficient, which is what makes
//! macro-generated and dynamic schemes bitwise identical.

use crate::forces::ForceGroup;
use num_rational::BigRational;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A sub-flow of the DPD dynamics (algorithms.md section 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Flow {
    /// Drift `q += h p / m`. Exact; accepts any sign of `h`.
    A,
    /// Conservative kick `p += h F^C(q)`. Exact; accepts any sign of `h`.
    B,
    /// Pairwise Ornstein-Uhlenbeck sweep, exact in distribution per pair. Needs `h > 0`.
    O,
    /// Pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update (weakly second order).
    /// Needs `h > 0`.
    Bbk,
    /// Pairwise conservative + OU update, exact per pair (DPD-Trotter piece). Needs `h > 0`.
    T,
    /// Explicit full-force kick `p += h (F^C + F^D + F^R)`; not a splitting of exact flows.
    /// An evaluation is reused while positions do not change (velocity Verlet convention).
    F,
    /// Lowe-Andersen pairwise collisions: each pair within the cut-off, with probability
    /// `1 - exp(-Gamma h)`, draws its relative normal velocity afresh from the Maxwellian of
    /// its reduced mass. Exact in distribution for collisions at rate Gamma; needs `h > 0`.
    L,
    /// Adaptive pairwise Ornstein-Uhlenbeck sweep (PAdL): O with each pair's friction
    /// `xi gamma_ij` scaled by the system's adaptive friction factor `xi`, its noise
    /// `sigma_ij` fixed; exact in distribution per pair at fixed `xi`. Needs `h > 0`.
    Oa,
    /// Pairwise Nose-Hoover sweep (PNHL): [`Flow::Oa`] without the pair noise, each pair's
    /// relative normal velocity damped by `exp(-xi gamma_ij w_D mu_ij h)` (any sign of `xi`).
    /// Needs `h > 0`.
    On,
    /// Update of the adaptive friction factor of PAdL and PNHL, `xi += h G / mu` with
    /// `G = sum over pairs gamma_ij w_D (u_ij^2 - kbt (1/m_i + 1/m_j))`, exact at fixed
    /// positions and momenta (which it does not change); with a thermostat friction (PNHL)
    /// the exact Ornstein-Uhlenbeck flow of xi around 0 under that drift. Its
    /// [`Stage::stream`] numbers the Xi stages of the step (0, 1, ...), whose noise is drawn
    /// from a stream apart from the sweeps'.
    Xi,
    /// `{`, the start of a Metropolis-adjusted part: keeps the state and its energy
    /// `H = K + U` for the accept/reject at the matching [`Flow::Accept`]. No step length.
    Propose,
    /// `}`, the end of a Metropolis-adjusted part: keeps the state reached with probability
    /// `min(1, exp(-Delta H / k_B T))`, else restores the state kept at `{` with its momenta
    /// negated. Draws one uniform from a stream of its own, apart from the sweeps' streams
    /// (its [`Stage::stream`] numbers the parts of the step: 0, 1, ...). No step length.
    Accept,
}

impl Flow {
    /// Every flow, in the order of the enum.
    pub const ALL: [Flow; 12] = [
        Flow::A,
        Flow::B,
        Flow::O,
        Flow::Bbk,
        Flow::T,
        Flow::F,
        Flow::L,
        Flow::Oa,
        Flow::On,
        Flow::Xi,
        Flow::Propose,
        Flow::Accept,
    ];

    /// True for the flows that loop over pairs drawing random numbers: the successive sweeps
    /// and F (whose random force is explicit).
    pub fn is_stochastic(self) -> bool {
        self.is_successive_sweep() || self == Flow::F
    }

    /// True for the flows that visit pairs successively, so that their order matters.
    pub fn is_successive_sweep(self) -> bool {
        matches!(
            self,
            Flow::O | Flow::Bbk | Flow::T | Flow::L | Flow::Oa | Flow::On
        )
    }

    /// True for the flows that change positions.
    pub fn moves_positions(self) -> bool {
        matches!(self, Flow::A)
    }

    /// True for the flows that may not run with a zero or negative step (stochastic ones).
    pub fn needs_positive_step(self) -> bool {
        self.is_successive_sweep()
    }

    /// True for the braces of a Metropolis-adjusted part (`{`, `}`): markers without a step
    /// length, outside the generators of the order analysis.
    pub fn is_brace(self) -> bool {
        matches!(self, Flow::Propose | Flow::Accept)
    }
}

/// The order in which a successive pair sweep visits the pair list.
///
/// `Forward` is the documented base order of `dpd-core` (colour by colour of its cell
/// colouring); `Reverse` visits the same pairs last to first.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SweepOrder {
    #[default]
    Forward,
    Reverse,
}

impl SweepOrder {
    /// The default order of the `k`-th successive sweep of a step (from 0): Forward, Reverse,
    /// Forward, ... so that repeated sweeps mirror each other.
    pub fn alternating(k: usize) -> SweepOrder {
        if k & 1 == 0 {
            SweepOrder::Forward
        } else {
            SweepOrder::Reverse
        }
    }
}

/// A step-length coefficient: the step length of a stage is `value * dt`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Coeff {
    /// The coefficient as used at run time.
    pub value: f64,
    /// The exact rational value, where the coefficient is rational.
    #[serde(skip)]
    pub exact: Option<BigRational>,
}

/// One sub-flow application inside a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Stage {
    pub flow: Flow,
    pub coeff: Coeff,
    /// Random-number stream of this stage within the step (the `sweep` component of the pair
    /// RNG key). Distinct stochastic stages get distinct streams, except where a scheme asks for
    /// frozen noise (PRK tables: all full-force stages of a step share one stream). 0 for
    /// deterministic flows.
    pub stream: u8,
    /// Visiting order of a successive sweep (`Forward` for all other flows).
    pub order: SweepOrder,
    /// The forces a kick applies: `None` for the letter's own (all forces for B and F, the
    /// pair forces for T, none for A, O and Ob), or the one force group a B or F stage names
    /// (`B[bond]`, module [`crate::forces`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<ForceGroup>,
}

impl Stage {
    /// Whether the stage applies the forces of `g` (module [`crate::forces`]).
    pub fn applies(&self, g: ForceGroup) -> bool {
        crate::forces::applies(self.flow, self.group, g)
    }
}

/// A compiled scheme: the stages of one step, as run.
///
/// `stages` is the sequence after merging adjacent applications of A, B and F (and dropping
/// those with a zero coefficient); `unmerged_stages` is the sequence as written and expanded,
/// for the order analysis. Random streams are numbered separately in each sequence, by the
/// same rule; sweep orders are the same in both (sweeps never merge).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Program {
    /// The scheme as written.
    pub source: String,
    pub stages: Vec<Stage>,
    pub unmerged_stages: Vec<Stage>,
}

/// Relative tolerance of [`Program::is_symmetric`] for coefficients that are not exact.
pub const SYMMETRY_TOLERANCE: f64 = 1e-14;

/// Work of one step in the cyclic steady state (the step repeated, evaluations reused across
/// the step boundary). Pair and bonded evaluations are counted apart: a bonded evaluation
/// visits the bond list only and costs little next to a pair evaluation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Evaluations {
    /// Pair-force evaluations: conservative (for B and B[pair]), full (for F and F[pair]), and
    /// one per T sweep.
    pub force: usize,
    /// Pair-distance (geometry) evaluations.
    pub pair_distance: usize,
    /// Bonded-force evaluations (for B, F and B[bond]), on a system with bonded forces; a
    /// system without them evaluates none.
    pub bonded_force: usize,
}

impl Program {
    /// Evaluations per step under the run-time caching rules of `dpd-core`: A moves the
    /// particles and invalidates every cache; every stage but `B[bond]` needs the pair
    /// geometry of the current positions; B and B[pair] need a conservative pair-force
    /// evaluation and F and F[pair] a full pair-force evaluation of the current positions,
    /// each cached until positions change; every T sweep evaluates the conservative pair force
    /// inline; B, F and B[bond] need the bonded forces, cached the same way. The braces `{` and
    /// `}` read the pair geometry for the potential energy (an extra pass over the pair table,
    /// not a force evaluation); a rejection at `}` costs evaluations not counted here.
    pub fn evaluations_per_step(&self) -> Evaluations {
        #[derive(Default)]
        struct Cache {
            geometry: bool,
            conservative: bool,
            full: bool,
            bonded: bool,
        }
        // Whether `fresh` was stale, which makes it fresh.
        fn evaluate(fresh: &mut bool) -> usize {
            usize::from(!std::mem::replace(fresh, true))
        }
        let mut cache = Cache::default();
        let mut count = Evaluations::default();
        // The first pass reaches the steady state; the second one is counted.
        for _pass in 0..2 {
            count = Evaluations::default();
            for stage in &self.stages {
                if stage.flow.moves_positions() {
                    cache = Cache::default();
                    continue;
                }
                // Every stage reads the pair table but a kick of the bonded forces alone.
                let pair =
                    !matches!(stage.flow, Flow::B | Flow::F) || stage.applies(ForceGroup::Pair);
                if pair {
                    count.pair_distance += evaluate(&mut cache.geometry);
                }
                count.force += match stage.flow {
                    Flow::B if pair => evaluate(&mut cache.conservative),
                    Flow::F if pair => evaluate(&mut cache.full),
                    Flow::T => 1,
                    _ => 0,
                };
                if stage.applies(ForceGroup::Bond) {
                    count.bonded_force += evaluate(&mut cache.bonded);
                }
            }
        }
        count
    }

    /// The force groups the stages name (`B[bond]` names the bonded forces), each once: a
    /// system must have each of them to run the program.
    pub fn named_groups(&self) -> Vec<ForceGroup> {
        ForceGroup::ALL
            .into_iter()
            .filter(|&g| self.stages.iter().any(|s| s.group == Some(g)))
            .collect()
    }

    /// Whether some stage applies the forces of `g`: a system that has them needs it.
    pub fn applies(&self, g: ForceGroup) -> bool {
        self.stages.iter().any(|s| s.applies(g))
    }

    /// Whether the step has a Metropolis-adjusted part (`{ ... }`).
    pub fn is_adjusted(&self) -> bool {
        self.stages.iter().any(|s| s.flow == Flow::Propose)
    }

    /// Order analysis of the step (algorithms.md section 4).
    pub fn analysis(&self) -> crate::analysis::Analysis {
        crate::analysis::analyse(&self.unmerged_stages)
    }

    /// Force evaluations per step, see [`Program::evaluations_per_step`].
    pub fn force_evaluations_per_step(&self) -> usize {
        self.evaluations_per_step().force
    }

    /// Pair-distance evaluations per step, see [`Program::evaluations_per_step`].
    pub fn pair_distance_evaluations_per_step(&self) -> usize {
        self.evaluations_per_step().pair_distance
    }

    /// Bonded-force evaluations per step, see [`Program::evaluations_per_step`].
    pub fn bonded_force_evaluations_per_step(&self) -> usize {
        self.evaluations_per_step().bonded_force
    }

    /// Whether the merged step reads the same backwards: mirrored stages have the same flow
    /// and coefficient (equal when both are exact, else within [`SYMMETRY_TOLERANCE`]
    /// relative), and mirrored successive sweeps run in opposite orders (the adjoint of a
    /// sweep is the reversed sweep). A single central sweep is its own mirror and counts as
    /// symmetric in either order. Random streams are ignored.
    pub fn is_symmetric(&self) -> bool {
        let n = self.stages.len();
        self.stages
            .iter()
            .zip(self.stages.iter().rev())
            .take(n / 2)
            .all(|(a, b)| mirrored(a, b))
    }

    /// Whether the step, repeated, reads the same backwards: the cycle of merged stages (the
    /// last and first joined where they merge, as `A(2/3)` and `A(1/3)` across the step
    /// boundary) has a mirror axis, through a stage or between two stages. Its time reversal
    /// is then the same chain observed at another phase of the step: `OBAB` is `OBABO` with
    /// its two half sweeps joined. Mirrored stages as in [`Program::is_symmetric`].
    pub fn is_cyclically_symmetric(&self) -> bool {
        let mut cycle = self.stages.clone();
        if let [first, .., last] = &cycle[..] {
            if first.flow == last.flow
                && first.group == last.group
                && !first.flow.is_successive_sweep()
            {
                let joined = Coeff {
                    value: first.coeff.value + last.coeff.value,
                    exact: first
                        .coeff
                        .exact
                        .as_ref()
                        .zip(last.coeff.exact.as_ref())
                        .map(|(a, b)| a + b),
                };
                cycle.pop();
                cycle[0].coeff = joined;
            }
        }
        let n = cycle.len();
        let at = |k: usize| &cycle[k % n];
        // Axis through stage k (offset 0) or between stages k and k + 1 (offset 1): stage
        // k + i mirrors stage k - i + offset.
        (0..n).any(|k| {
            [0, 1]
                .iter()
                .any(|&offset| (1..=n).all(|i| mirrored(at(k + i), at(k + 2 * n + offset - i))))
        })
    }
}

/// Whether stages `a` and `b` are mirror images in a step read backwards: same flow, force
/// group and coefficient, and successive sweeps in opposite orders (the adjoint of a sweep is the
/// reversed sweep). A stage mirrored onto itself always is.
fn mirrored(a: &Stage, b: &Stage) -> bool {
    let braces = matches!(
        (a.flow, b.flow),
        (Flow::Propose, Flow::Accept) | (Flow::Accept, Flow::Propose)
    );
    std::ptr::eq(a, b)
        || braces
        || (a.flow == b.flow
            && a.group == b.group
            && coeffs_equal(&a.coeff, &b.coeff)
            && (!a.flow.is_successive_sweep() || a.order != b.order))
}

pub(crate) fn coeffs_equal(a: &Coeff, b: &Coeff) -> bool {
    match (&a.exact, &b.exact) {
        (Some(x), Some(y)) => x == y,
        _ => (a.value - b.value).abs() <= SYMMETRY_TOLERANCE * a.value.abs().max(b.value.abs()),
    }
}

impl fmt::Display for Coeff {
    /// Exact values as fractions (`1/2`, `-3`), others with 17 significant digits
    /// (`0.67560359597982889`, `-1.7024143839193153e-20`): the scheme language reads such a
    /// literal back as the same `f64`, and as inexact (it has at least 13 significant digits),
    /// so a printed program compiles to the same analysis.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.exact {
            Some(r) => write!(f, "{r}"),
            None => f.write_str(&seventeen_digits(self.value)),
        }
    }
}

/// `x` with 17 significant digits, positional for magnitudes in [1e-4, 1e15), else in
/// scientific notation; trailing zeros are kept (they mark the value as inexact).
fn seventeen_digits(x: f64) -> String {
    let sci = format!("{x:.16e}");
    let Some((mantissa, exponent)) = sci.split_once('e') else {
        return sci;
    };
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if x == 0.0 || !(-4..15).contains(&exponent) {
        return sci;
    }
    let (sign, digits) = match mantissa.strip_prefix('-') {
        Some(rest) => ("-", rest.replace('.', "")),
        None => ("", mantissa.replace('.', "")),
    };
    let text = if exponent < 0 {
        format!("0.{}{digits}", "0".repeat((-exponent - 1) as usize))
    } else {
        let point = exponent as usize + 1;
        format!("{}.{}", &digits[..point], &digits[point..])
    };
    format!("{sign}{text}")
}

impl fmt::Display for Program {
    /// The merged stages in the scheme language, e.g. `A(1/2) B(1/2) O(1) B(1/2) A(1/2)` or
    /// `B[pair](1/2) B[bond](1/8) A(1/4)`.
    /// A sweep whose order differs from the default alternation is marked `<` (reverse) or
    /// `>` (forward), so the output compiles back to the same stages (except the shared
    /// noise of PRK tables). The alternate form `{:#}` marks the order of every sweep and the
    /// random stream of every stochastic stage: `O>(1)@0`. The braces of a Metropolis-adjusted
    /// part print without a coefficient: `{ B(1/2) A(1) B(1/2) } O(1)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut sweeps = 0;
        for (i, stage) in self.stages.iter().enumerate() {
            if i > 0 {
                f.write_str(" ")?;
            }
            f.write_str(crate::lang::letters::spelling(stage.flow))?;
            if stage.flow.is_brace() {
                if f.alternate() && stage.flow == Flow::Accept {
                    write!(f, "@{}", stage.stream)?;
                }
                continue;
            }
            if let Some(g) = stage.group {
                write!(f, "[{}]", crate::lang::letters::group_spelling(g))?;
            }
            if stage.flow.is_successive_sweep() {
                let default = SweepOrder::alternating(sweeps);
                sweeps += 1;
                if f.alternate() || stage.order != default {
                    f.write_str(match stage.order {
                        SweepOrder::Forward => ">",
                        SweepOrder::Reverse => "<",
                    })?;
                }
            }
            write!(f, "({})", stage.coeff)?;
            if f.alternate() && stage.flow.is_stochastic() {
                write!(f, "@{}", stage.stream)?;
            }
        }
        Ok(())
    }
}
