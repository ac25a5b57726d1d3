//! `dpd orderings`: every distinct consistent splitting string up to a length over an
//! alphabet of sub-flow letters (each letter's occurrences sharing dt equally), with its
//! orders, cost and symmetry, best invariant-measure bound first, then cheapest.

use super::predict::{spectrum_of, SpectrumArgs};
use super::{bad_input, print_json};
use dpd::analysis::{analyse_with, Options};
use dpd::lang::letters::{letter, spellings, Letter};
use dpd::Flow;
use dpd_predict::{Critical, Predictor};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashSet;
use std::process::ExitCode;

/// Most strings enumerated (before removing duplicates).
const MAX_STRINGS: u64 = 1_000_000;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Longest string
    #[arg(long, allow_negative_numbers = true)]
    max_len: u32,
    /// Letters to combine, e.g. ABO or ABOb
    #[arg(long, default_value = "ABO")]
    alphabet: String,
    /// Order of the list within equal invariant-measure bounds: `cost` (force, then
    /// pair-distance evaluations) or `error` (higher deterministic order, then the smaller
    /// invariant-measure error norm, then the smaller deterministic error norm, then cost) or
    /// `predicted` (the longest predicted critical step of 10 % T_C error, `dpd predict`, per
    /// force evaluation; the prediction sees the error of schemes exact on Gaussians only
    /// through its anharmonic correction, so the bound still comes first)
    #[arg(long, value_enum, default_value_t = Rank::Cost)]
    rank: Rank,
    /// The modes `--rank predicted` predicts on
    #[command(flatten)]
    spectrum: SpectrumArgs,
    /// Print a JSON array on stdout
    #[arg(long)]
    json: bool,
}

/// How `dpd orderings` sorts schemes of equal invariant-measure bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Rank {
    Cost,
    Error,
    Predicted,
}

/// One distinct ordering.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Ordering {
    pub scheme: String,
    /// The merged stages.
    pub program: String,
    pub deterministic_order: u32,
    /// Left-ideal bound (`None` with F stages).
    pub invariant_measure_order: Option<u32>,
    /// Nothing was found up to the highest order checked: the bound is at least this.
    pub invariant_measure_order_capped: bool,
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
    pub symmetric: bool,
    /// Norm of the leading Hamiltonian error (Lyndon basis), see `dpd check`.
    pub deterministic_error_norm: Option<f64>,
    /// Norm of the first non-vanishing invariant-measure term, see `dpd check`.
    pub invariant_measure_error_norm: Option<f64>,
    /// With `--rank predicted`: the predicted critical step of 10 % T_C error (null: not
    /// reached below 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub predicted_critical_dt_10: Option<Option<f64>>,
}

impl Ordering {
    /// Predicted critical step per force evaluation (0 without a prediction); a critical step
    /// beyond the search counts as its end.
    fn predicted_efficiency(&self) -> f64 {
        let dt = match self.predicted_critical_dt_10 {
            Some(Some(dt)) => dt,
            Some(None) => dpd_predict::predict::SEARCH_DT_MAX,
            None => 0.0,
        };
        dt / self.force_evaluations_per_step.max(1) as f64
    }
}

pub fn main(args: Args) -> ExitCode {
    let letters = match parse_alphabet(&args.alphabet) {
        Ok(letters) => letters,
        Err(e) => return bad_input(format!("invalid --alphabet = {:?}: {e}", args.alphabet)),
    };
    let count: u64 = (1..=args.max_len)
        .map(|n| (letters.len() as u64).saturating_pow(n))
        .fold(0, u64::saturating_add);
    if args.max_len == 0 || count > MAX_STRINGS {
        return bad_input(format!(
            "invalid --max-len = {}: gives {count} strings over {} letters; \
             allowed are 1 to {MAX_STRINGS} strings",
            args.max_len,
            letters.len()
        ));
    }
    let predictor = match args.rank {
        Rank::Predicted => match spectrum_of(&args.spectrum) {
            Ok((spectrum, _, _)) => Some(Predictor::new(&spectrum)),
            Err(e) => return bad_input(e),
        },
        _ => None,
    };
    let list = orderings(&letters, args.max_len, args.rank, predictor.as_ref());
    if args.json {
        return print_json(&list);
    }
    outln!(
        "{:<width$}  det  inv  force  pairs  sym  {}program",
        "scheme",
        if predictor.is_some() {
            "dt_c 10 %  "
        } else {
            ""
        },
        width = args.max_len.max(6) as usize
    );
    for o in &list {
        let inv = o.invariant_measure_order.map_or("-".into(), |p| {
            format!(
                "{}{p}",
                if o.invariant_measure_order_capped {
                    ">="
                } else {
                    ""
                }
            )
        });
        let predicted = match o.predicted_critical_dt_10 {
            Some(Some(dt)) => format!("{dt:>9.4}  "),
            Some(None) => format!("{:>9}  ", "> 2"),
            None => String::new(),
        };
        outln!(
            "{:<width$}  {:>3}  {:>3}  {:>5}  {:>5}  {:>3}  {predicted}{}",
            o.scheme,
            o.deterministic_order,
            inv,
            o.force_evaluations_per_step,
            o.pair_distance_evaluations_per_step,
            if o.symmetric { "yes" } else { "no" },
            o.program,
            width = args.max_len.max(6) as usize
        );
    }
    outln!("{} distinct consistent orderings", list.len());
    ExitCode::SUCCESS
}

/// The letters of `alphabet`: each uppercase character starts one.
fn parse_alphabet(alphabet: &str) -> Result<Vec<&'static Letter>, String> {
    let mut letters: Vec<&'static Letter> = Vec::new();
    let mut rest = alphabet.trim();
    while let Some(first) = rest.chars().next() {
        let len = rest[first.len_utf8()..]
            .find(|c: char| !c.is_ascii_lowercase())
            .map_or(rest.len(), |k| k + first.len_utf8());
        let spelling = &rest[..len];
        let l = letter(spelling)
            .ok_or_else(|| format!("unknown letter {spelling:?}; letters are {}", spellings()))?;
        if letters.contains(&l) {
            return Err(format!("letter {spelling:?} appears twice"));
        }
        letters.push(l);
        rest = &rest[len..];
    }
    if letters.is_empty() {
        return Err(format!("no letters; letters are {}", spellings()));
    }
    Ok(letters)
}

/// Whether a string of these flows can be consistent: it needs A, a B carrier and, when the
/// alphabet has a stochastic letter, a thermostat.
fn can_be_consistent(flows: &[Flow], stochastic_alphabet: bool) -> bool {
    let has = |f: fn(Flow) -> bool| flows.iter().any(|&x| f(x));
    has(|f| f == Flow::A)
        && has(|f| matches!(f, Flow::B | Flow::T | Flow::F))
        && (!stochastic_alphabet || has(Flow::is_stochastic))
}

/// Every string over `letters` of length 1 to `max_len`, in order of length then alphabet
/// position.
fn strings(letters: &[&'static Letter], max_len: u32) -> Vec<Vec<&'static Letter>> {
    let mut all = Vec::new();
    let mut current: Vec<Vec<&'static Letter>> = vec![Vec::new()];
    for _ in 0..max_len {
        current = current
            .iter()
            .flat_map(|s| {
                letters.iter().map(move |&l| {
                    let mut next = s.clone();
                    next.push(l);
                    next
                })
            })
            .collect();
        all.extend(current.iter().cloned());
    }
    all
}

/// The distinct consistent orderings (the first string of each merged program), sorted by
/// invariant-measure bound (descending), then by `rank`'s error keys if any, then force and
/// pair-distance evaluations, length and spelling ([`Rank::Predicted`]: the `predictor`'s
/// critical step per force evaluation, descending).
pub fn orderings(
    letters: &[&'static Letter],
    max_len: u32,
    rank: Rank,
    predictor: Option<&Predictor>,
) -> Vec<Ordering> {
    let stochastic = letters.iter().any(|l| l.flow.is_stochastic());
    let candidates: Vec<String> = strings(letters, max_len)
        .into_iter()
        .filter(|s| can_be_consistent(&s.iter().map(|l| l.flow).collect::<Vec<_>>(), stochastic))
        .map(|s| s.iter().map(|l| l.spelling).collect())
        .collect();
    let options = Options::default();
    let analysed: Vec<Option<(String, Ordering)>> = candidates
        .par_iter()
        .map(|scheme| {
            let program = dpd::lang::compile(scheme).ok()?;
            let analysis = analyse_with(&program.unmerged_stages, &options);
            let cost = program.evaluations_per_step();
            Some((
                format!("{program:#}"),
                Ordering {
                    scheme: scheme.clone(),
                    program: program.to_string(),
                    deterministic_order: analysis.deterministic_order,
                    invariant_measure_order: analysis.invariant_measure_order,
                    invariant_measure_order_capped: analysis.invariant_measure_order_capped,
                    force_evaluations_per_step: cost.force,
                    pair_distance_evaluations_per_step: cost.pair_distance,
                    symmetric: program.is_symmetric(),
                    deterministic_error_norm: analysis.deterministic_error_norm,
                    invariant_measure_error_norm: analysis.invariant_measure_error_norm,
                    predicted_critical_dt_10: predictor
                        .map(|p| p.critical_dt(&program, 0.1).ok().and_then(Critical::dt)),
                },
            ))
        })
        .collect();
    let mut seen = HashSet::new();
    let mut list: Vec<Ordering> = analysed
        .into_iter()
        .flatten()
        .filter(|(key, _)| seen.insert(key.clone()))
        .map(|(_, o)| o)
        .collect();
    // A missing norm (nothing found up to the highest order checked) ranks first.
    let norm = |x: Option<f64>| x.unwrap_or(0.0);
    list.sort_by(|a, b| {
        let by_error = match rank {
            Rank::Cost => std::cmp::Ordering::Equal,
            Rank::Predicted => b
                .predicted_efficiency()
                .total_cmp(&a.predicted_efficiency()),
            Rank::Error => b
                .deterministic_order
                .cmp(&a.deterministic_order)
                .then(
                    norm(a.invariant_measure_error_norm)
                        .total_cmp(&norm(b.invariant_measure_error_norm)),
                )
                .then(
                    norm(a.deterministic_error_norm).total_cmp(&norm(b.deterministic_error_norm)),
                ),
        };
        b.invariant_measure_order
            .cmp(&a.invariant_measure_order)
            .then(by_error)
            .then(
                a.force_evaluations_per_step
                    .cmp(&b.force_evaluations_per_step),
            )
            .then(
                a.pair_distance_evaluations_per_step
                    .cmp(&b.pair_distance_evaluations_per_step),
            )
            .then(a.scheme.len().cmp(&b.scheme.len()))
            .then(a.scheme.cmp(&b.scheme))
    });
    list
}

#[cfg(test)]
mod tests {
    use super::*;

    fn abo() -> Vec<&'static Letter> {
        parse_alphabet("ABO").unwrap()
    }

    #[test]
    fn alphabets_split_at_uppercase_letters() {
        let l = parse_alphabet("ABOb").unwrap();
        let spelled: Vec<_> = l.iter().map(|l| l.spelling).collect();
        assert_eq!(spelled, ["A", "B", "Ob"]);
        assert!(parse_alphabet("ABX").unwrap_err().contains("\"X\""));
        assert!(parse_alphabet("AA").unwrap_err().contains("twice"));
    }

    #[test]
    fn length_three_gives_the_six_permutations() {
        let list = orderings(&abo(), 3, Rank::Cost, None);
        let mut names: Vec<_> = list.iter().map(|o| o.scheme.as_str()).collect();
        names.sort();
        assert_eq!(names, ["ABO", "AOB", "BAO", "BOA", "OAB", "OBA"]);
        // Each is consistent with a first-order invariant measure bound.
        assert!(list.iter().all(|o| o.invariant_measure_order == Some(1)));
    }

    #[test]
    fn aboba_leads_the_length_five_list_and_duplicates_are_dropped() {
        let list = orderings(&abo(), 5, Rank::Cost, None);
        let best = &list[0];
        assert_eq!(best.invariant_measure_order, Some(2));
        assert_eq!(best.force_evaluations_per_step, 1);
        let aboba = list.iter().find(|o| o.scheme == "ABOBA").unwrap();
        assert!(aboba.symmetric && aboba.invariant_measure_order == Some(2));
        let programs: HashSet<_> = list.iter().map(|o| o.program.clone()).collect();
        assert_eq!(programs.len(), list.len());
        // "AABO" merges to the same program as "ABO".
        assert!(!list.iter().any(|o| o.scheme == "AABO"));
    }

    #[test]
    fn rank_error_sorts_equal_orders_by_the_invariant_measure_norm() {
        let list = orderings(&abo(), 5, Rank::Error, None);
        let second: Vec<&Ordering> = list
            .iter()
            .filter(|o| o.invariant_measure_order == Some(2) && o.deterministic_order == 2)
            .collect();
        assert!(second.len() >= 2);
        let norms: Vec<f64> = second
            .iter()
            .map(|o| o.invariant_measure_error_norm.unwrap())
            .collect();
        assert!(norms.windows(2).all(|w| w[0] <= w[1]), "{norms:?}");
    }
}
