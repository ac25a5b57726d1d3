//! The named schemes, looked up by case-insensitive name or alias, with what each costs and
//! what its orders are: the one place these claims are written (the scheme docs do not repeat
//! them).

use std::fmt;
use std::sync::OnceLock;

use dpd_core::{DynScheme, Scheme};
use dpd_ir::lang::{Diagnostic, Options};
use serde::Serialize;
use thiserror::Error;

use crate::{
    adaptive, adjusted, composition, exponential, langevin, lowe, peters, prk, shardlow, trotter,
    verlet,
};

/// What the catalogue claims about a scheme, written once here.
///
/// Splitting schemes are listed with what the analysis of their program computes, and a test
/// checks that it equals these claims. Hand-written schemes are listed with their claims, and
/// tests check them by measurement: evaluation counters, the order of convergence at
/// `gamma = 0`, momentum conservation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Claims {
    /// Force evaluations per step in the steady state (evaluations reused across steps).
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
    /// Order of the Hamiltonian part (0 for an inconsistent scheme).
    pub deterministic_order: u32,
    /// Left-ideal bound on the order of the invariant measure; `None` where the criterion does
    /// not apply (F stages, hand-written schemes).
    pub invariant_measure_order: Option<u32>,
    /// The step reads the same backwards (mirrored sweeps in opposite orders).
    pub symmetric: bool,
    /// Coefficients of each generator sum to one.
    pub consistent: bool,
    /// Every update is pairwise and antisymmetric: total momentum is conserved to rounding error.
    pub momentum_conserving: bool,
}

/// A named scheme of the catalogue.
pub struct Entry {
    /// Registry name, lowercase.
    pub name: &'static str,
    /// Other names it is found under, lowercase.
    pub aliases: &'static [&'static str],
    /// One line on what the scheme is.
    pub summary: &'static str,
    /// Citation.
    pub source: &'static str,
    build: fn() -> Box<dyn Scheme + Send + Sync>,
    /// The step in words, for hand-written schemes (splitting schemes print their program).
    hand_written: Option<&'static str>,
    claims: Claims,
    row: OnceLock<Row>,
}

/// One line of the listing (`dpd schemes`, `dpd schemes --json`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    pub name: &'static str,
    pub aliases: &'static [&'static str],
    pub summary: &'static str,
    /// The merged stages of a splitting scheme, or the step in words for a hand-written one.
    pub sequence: String,
    pub hand_written: bool,
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
    pub deterministic_order: u32,
    pub invariant_measure_order: Option<u32>,
    pub symmetric: bool,
    pub consistent: bool,
    pub momentum_conserving: bool,
    pub source: &'static str,
}

impl Entry {
    /// A fresh instance of the scheme.
    pub fn scheme(&self) -> Box<dyn Scheme + Send + Sync> {
        (self.build)()
    }

    /// The stages of one step: the program of a splitting scheme, the step in words otherwise.
    pub fn sequence(&self) -> String {
        self.row().sequence.clone()
    }

    /// Whether the scheme is hand-written on the core sub-flows rather than a splitting
    /// string.
    pub fn is_hand_written(&self) -> bool {
        self.hand_written.is_some()
    }

    /// What the catalogue claims about the scheme (checked by `tests/claims.rs`).
    pub fn claims(&self) -> &Claims {
        &self.claims
    }

    /// The order analysis of a splitting scheme's program; `None` for hand-written schemes.
    pub fn analysis(&self) -> Option<dpd_ir::Analysis> {
        self.scheme().program().map(|p| p.analysis())
    }

    /// Force evaluations per step (computed from the program where there is one).
    pub fn force_evaluations_per_step(&self) -> usize {
        self.row().force_evaluations_per_step
    }

    pub fn pair_distance_evaluations_per_step(&self) -> usize {
        self.row().pair_distance_evaluations_per_step
    }

    pub fn deterministic_order(&self) -> u32 {
        self.row().deterministic_order
    }

    pub fn invariant_measure_order(&self) -> Option<u32> {
        self.row().invariant_measure_order
    }

    /// The listing row: analysed for splitting schemes, claimed for hand-written ones.
    pub fn row(&self) -> &Row {
        self.row.get_or_init(|| {
            let claims = &self.claims;
            let mut row = Row {
                name: self.name,
                aliases: self.aliases,
                summary: self.summary,
                sequence: self.hand_written.unwrap_or_default().to_string(),
                hand_written: self.hand_written.is_some(),
                force_evaluations_per_step: claims.force_evaluations_per_step,
                pair_distance_evaluations_per_step: claims.pair_distance_evaluations_per_step,
                deterministic_order: claims.deterministic_order,
                invariant_measure_order: claims.invariant_measure_order,
                symmetric: claims.symmetric,
                consistent: claims.consistent,
                momentum_conserving: claims.momentum_conserving,
                source: self.source,
            };
            if let Some(program) = self.scheme().program() {
                let analysis = program.analysis();
                let cost = program.evaluations_per_step();
                row.sequence = program.to_string();
                row.force_evaluations_per_step = cost.force;
                row.pair_distance_evaluations_per_step = cost.pair_distance;
                row.deterministic_order = analysis.deterministic_order;
                row.invariant_measure_order = analysis.invariant_measure_order;
                row.symmetric = program.is_symmetric();
                row.consistent = analysis.consistent;
                // Every sub-flow of the language is pairwise and antisymmetric.
                row.momentum_conserving = true;
            }
            row
        })
    }
}

impl fmt::Debug for Entry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Entry")
            .field("name", &self.name)
            .field("aliases", &self.aliases)
            .field("claims", &self.claims)
            .finish_non_exhaustive()
    }
}

/// The claims of a splitting scheme (pairwise and, unless said otherwise, consistent).
const fn splitting(
    force: usize,
    pair_distance: usize,
    deterministic_order: u32,
    invariant_measure_order: Option<u32>,
    symmetric: bool,
) -> Claims {
    Claims {
        force_evaluations_per_step: force,
        pair_distance_evaluations_per_step: pair_distance,
        deterministic_order,
        invariant_measure_order,
        symmetric,
        consistent: true,
        momentum_conserving: true,
    }
}

/// The claims of a hand-written scheme: one force and one pair-distance evaluation per step,
/// not symmetric, consistent, no invariant-measure criterion.
const fn by_hand(deterministic_order: u32, momentum_conserving: bool) -> Claims {
    Claims {
        force_evaluations_per_step: 1,
        pair_distance_evaluations_per_step: 1,
        deterministic_order,
        invariant_measure_order: None,
        symmetric: false,
        consistent: true,
        momentum_conserving,
    }
}

/// An entry; `hand_written` is the step in words for schemes that are not splitting strings.
const fn entry(
    name: &'static str,
    aliases: &'static [&'static str],
    summary: &'static str,
    source: &'static str,
    build: fn() -> Box<dyn Scheme + Send + Sync>,
    hand_written: Option<&'static str>,
    claims: Claims,
) -> Entry {
    Entry {
        name,
        aliases,
        summary,
        source,
        build,
        hand_written,
        claims,
        row: OnceLock::new(),
    }
}

const GROOT_WARREN: &str = "R. D. Groot and P. B. Warren, J. Chem. Phys. 107, 4423 (1997)";
const SHARDLOW: &str = "T. Shardlow, SIAM J. Sci. Comput. 24, 1267 (2003)";
const YAMADA: &str = "Yamada et al., as quoted in algorithms.md section 3";
const PRK_DPD: &str = "Fluids 4, 156 (2019), doi:10.3390/fluids4030156";
const ETD: &str =
    "N. Phan-Thien, N. Mai-Duy, D. Pan and B. C. Khoo, Comput. Phys. Commun. 185, 229 (2014)";

static ENTRIES: [Entry; 28] = [
    entry(
        "vv",
        &["velocity-verlet", "groot-warren", "gw"],
        "velocity Verlet / Groot-Warren, lambda = 1/2; end-of-step forces reused",
        GROOT_WARREN,
        || Box::new(verlet::vv()),
        None,
        splitting(1, 1, 2, None, true),
    ),
    entry(
        "gw-0.65",
        &["groot-warren-0.65"],
        "Groot-Warren modified velocity Verlet, lambda = 0.65 (their recommendation)",
        GROOT_WARREN,
        || Box::new(verlet::GrootWarren::new(0.65).expect("0.65 is in [0, 1]")),
        Some("F(1/2) A(1) F~(1/2), F~ the full force at v + 0.65 dt a"),
        by_hand(2, true),
    ),
    entry(
        "dpd-s1",
        &["s1", "shardlow-s1"],
        "Shardlow's DPD-S1: BBK pair sweep, then velocity Verlet (OBAB)",
        SHARDLOW,
        || Box::new(shardlow::dpd_s1()),
        None,
        splitting(1, 1, 2, Some(2), false),
    ),
    entry(
        "dpd-s2",
        &["s2", "shardlow-s2"],
        "Shardlow's DPD-S2: half BBK sweeps around velocity Verlet (OBABO)",
        SHARDLOW,
        || Box::new(shardlow::dpd_s2()),
        None,
        splitting(1, 1, 2, Some(2), true),
    ),
    entry(
        "aboba",
        &[],
        "ABOBA with exact pairwise O; kicks and sweep share the half-step forces",
        "X. Shang, SIAM J. Sci. Comput. 43, A1929 (2021)",
        || Box::new(langevin::aboba()),
        None,
        splitting(1, 1, 2, Some(2), true),
    ),
    entry(
        "baoab",
        &[],
        "BAOAB with exact pairwise O",
        "B. Leimkuhler and C. Matthews, AMRX 2013, 34 (2013)",
        || Box::new(langevin::baoab()),
        None,
        splitting(1, 2, 2, Some(2), true),
    ),
    entry(
        "baooab",
        &[],
        "BAOAB with the sweep in two mirrored halves",
        "algorithms.md section 3; Leimkuhler and Matthews (2013)",
        || Box::new(langevin::baooab()),
        None,
        splitting(1, 2, 2, Some(2), true),
    ),
    entry(
        "obabo",
        &[],
        "velocity Verlet between two exact half sweeps",
        "G. Bussi and M. Parrinello, Phys. Rev. E 75, 056707 (2007)",
        || Box::new(langevin::obabo()),
        None,
        splitting(1, 1, 2, Some(2), true),
    ),
    entry(
        "lowe-andersen",
        &["lowe", "vv-la"],
        "Lowe's scheme: velocity Verlet, then a Lowe-Andersen collision sweep (needs collision_rate)",
        "C. P. Lowe, Europhys. Lett. 47, 145 (1999)",
        || Box::new(lowe::lowe_andersen()),
        None,
        splitting(1, 1, 2, Some(2), false),
    ),
    entry(
        "ablba",
        &["aboba-la"],
        "ABOBA with Lowe-Andersen collisions in place of O (needs collision_rate)",
        "this crate (issue 49), after Lowe (1999) and Shang (2021)",
        || Box::new(lowe::ablba()),
        None,
        splitting(1, 1, 2, Some(2), true),
    ),
    entry(
        "peters",
        &["vv-peters"],
        "Peters' scheme: velocity Verlet, then Peters' pair thermostat, which is the exact O sweep",
        "E. A. J. F. Peters, Europhys. Lett. 66, 311 (2004)",
        || Box::new(peters::peters()),
        None,
        splitting(1, 1, 2, Some(2), false),
    ),
    entry(
        "padl",
        &[],
        "pairwise adaptive Langevin: BAOAB with the friction factor xi updated around the sweep (needs thermostat_mass)",
        "B. Leimkuhler and X. Shang, J. Comput. Phys. 324, 174 (2016); ordering: this crate",
        || Box::new(adaptive::padl()),
        None,
        splitting(1, 2, 2, None, true),
    ),
    entry(
        "padl-aboba",
        &[],
        "pairwise adaptive Langevin in the ABOBA ordering (needs thermostat_mass)",
        "this crate (issue 49), after Leimkuhler and Shang (2016) and Shang (2021)",
        || Box::new(adaptive::padl_aboba()),
        None,
        splitting(1, 1, 2, None, true),
    ),
    entry(
        "pnhl",
        &[],
        "pairwise Nose-Hoover-Langevin: PAdL's ordering with the noiseless sweep On, the noise on xi alone (needs thermostat_mass and thermostat_friction)",
        "B. Leimkuhler and X. Shang, J. Comput. Phys. 280, 72 (2015); ordering: padl's (this crate)",
        || Box::new(adaptive::pnhl()),
        None,
        splitting(1, 2, 2, None, true),
    ),
    entry(
        "ghmc",
        &["aboba-mh"],
        "Metropolis-adjusted: velocity Verlet in braces, accepted on exp(-Delta H / kT), then O; the Gibbs measure exactly at any dt, acceptance falling with N dt^6",
        "A. M. Horowitz, Phys. Lett. B 268, 247 (1991) (generalised HMC); pairwise O: this crate (issue 49)",
        || Box::new(adjusted::ghmc()),
        None,
        Claims {
            momentum_conserving: false,
            ..splitting(1, 1, 2, Some(2), false)
        },
    ),
    entry(
        "sas",
        &["dpd-trotter", "tat"],
        "DPD-Trotter: exact pair conservative + OU half sweeps around a drift (TAT)",
        "T. Serrano, G. De Fabritiis, P. Espanol and P. V. Coveney, Math. Comput. Simul. 72, 190 (2006)",
        || Box::new(trotter::sas()),
        None,
        splitting(2, 1, 2, Some(2), true),
    ),
    entry(
        "asa",
        &["ata"],
        "half drifts around one exact pair conservative + OU sweep (ATA)",
        "ordering variant of Serrano et al. (2006)",
        || Box::new(trotter::asa()),
        None,
        splitting(1, 1, 2, Some(1), true),
    ),
    entry(
        "m-shardlow-1",
        &["mshardlow-1"],
        "Yoshida triple jump with the published (wrong) sign, then BBK; INCONSISTENT",
        YAMADA,
        || Box::new(shardlow::m_shardlow_1()),
        None,
        Claims {
            consistent: false,
            ..splitting(3, 3, 0, Some(2), false)
        },
    ),
    entry(
        "m-shardlow-2",
        &["mshardlow-2"],
        "Yoshida fourth-order triple jump, then BBK",
        YAMADA,
        || Box::new(shardlow::m_shardlow_2()),
        None,
        splitting(3, 3, 4, Some(4), false),
    ),
    entry(
        "prk3-ruth",
        &["ruth"],
        "third-order PRK, Ruth's table, full-force kicks with noise frozen in the step",
        PRK_DPD,
        || Box::new(prk::prk3_ruth()),
        None,
        splitting(3, 3, 3, None, false),
    ),
    entry(
        "prk3-iwatsu-a",
        &["iwatsu-a"],
        "third-order PRK, Iwatsu's solution A, full-force kicks with frozen noise",
        PRK_DPD,
        || Box::new(prk::prk3_iwatsu_a()),
        None,
        splitting(3, 3, 3, None, false),
    ),
    entry(
        "prk3-iwatsu-b",
        &["iwatsu-b"],
        "third-order PRK, Iwatsu's solution B, full-force kicks with frozen noise",
        PRK_DPD,
        || Box::new(prk::prk3_iwatsu_b()),
        None,
        splitting(3, 3, 3, None, false),
    ),
    entry(
        "prk3-ruth-o",
        &[],
        "Ruth's sequence with exact kicks, then one exact O sweep",
        "this crate, from R. D. Ruth, IEEE Trans. Nucl. Sci. 30, 2669 (1983)",
        || Box::new(prk::prk3_ruth_o()),
        None,
        splitting(3, 3, 3, Some(3), false),
    ),
    entry(
        "prk3-ruth-sym",
        &[],
        "Ruth's sequence, exact O, Ruth's adjoint: symmetric, fourth order",
        "this crate, from R. D. Ruth, IEEE Trans. Nucl. Sci. 30, 2669 (1983)",
        || Box::new(prk::prk3_ruth_sym()),
        None,
        splitting(5, 6, 4, Some(4), true),
    ),
    entry(
        "aboba-y4",
        &["aboba4"],
        "half Yoshida triple jump, exact O, half triple jump: ABOBA-like, fourth order",
        "this crate, from H. Yoshida, Phys. Lett. A 150, 262 (1990)",
        || Box::new(composition::aboba_y4()),
        None,
        splitting(6, 6, 4, Some(4), true),
    ),
    entry(
        "obabo-y4",
        &["obabo4"],
        "Yoshida triple jump between exact half sweeps: OBABO-like, fourth order",
        "this crate, from H. Yoshida, Phys. Lett. A 150, 262 (1990)",
        || Box::new(composition::obabo_y4()),
        None,
        splitting(3, 3, 4, Some(4), true),
    ),
    entry(
        "setd",
        &[],
        "exponential time differencing per particle, exact OU noise variance; small masses",
        ETD,
        || Box::new(exponential::Setd),
        Some("E(1) A(1), E: u += dt phi1(c dt) g + sqrt(dt phi1(2 c dt)) b xi"),
        by_hand(1, false),
    ),
    entry(
        "msetd",
        &[],
        "exponential time differencing per particle, noise frozen over the step; small masses",
        ETD,
        || Box::new(exponential::Msetd),
        Some("E'(1) A(1), E': u += dt phi1(c dt) (g + b xi / sqrt(dt))"),
        by_hand(1, false),
    ),
];

/// Every registered scheme, in catalogue order.
pub fn entries() -> &'static [Entry] {
    &ENTRIES
}

/// The form names are compared in: lowercase, `_` read as `-`, surrounding blanks dropped.
fn normalise(name: &str) -> String {
    name.trim().to_lowercase().replace('_', "-")
}

/// The entry named `name` or one of its aliases, ignoring case.
pub fn lookup(name: &str) -> Result<&'static Entry, UnknownScheme> {
    let key = normalise(name);
    ENTRIES
        .iter()
        .find(|e| e.name == key || e.aliases.contains(&key.as_str()))
        .ok_or_else(|| UnknownScheme {
            name: name.to_string(),
            close_matches: close_matches(&key),
        })
}

/// A name that is neither a registered name nor an alias.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub struct UnknownScheme {
    /// The name as given.
    pub name: String,
    /// Registered names within a small edit distance (or containing it), closest first.
    pub close_matches: Vec<&'static str>,
}

impl fmt::Display for UnknownScheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown scheme '{}'", self.name)?;
        if self.close_matches.is_empty() {
            let all: Vec<&str> = ENTRIES.iter().map(|e| e.name).collect();
            write!(f, "; registered schemes: {}", all.join(", "))
        } else {
            write!(f, "; did you mean {}?", self.close_matches.join(", "))
        }
    }
}

/// Registry names whose name or an alias is within edit distance `max(2, len/3)` of `key` or
/// contains it, closest first, each name once.
fn close_matches(key: &str) -> Vec<&'static str> {
    let limit = (key.chars().count() / 3).max(2);
    let mut found: Vec<(usize, &'static str)> = ENTRIES
        .iter()
        .filter_map(|e| {
            std::iter::once(e.name)
                .chain(e.aliases.iter().copied())
                .map(|n| {
                    let contains = !key.is_empty() && n.contains(key);
                    if contains {
                        0
                    } else {
                        edit_distance(key, n)
                    }
                })
                .min()
                .filter(|&d| d <= limit)
                .map(|d| (d, e.name))
        })
        .collect();
    found.sort();
    found.into_iter().map(|(_, n)| n).collect()
}

/// Levenshtein distance over characters (insertions, deletions, substitutions).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// A text that is neither a registered scheme nor a valid scheme string.
#[derive(Clone, Debug, PartialEq, Error)]
pub struct ResolveError {
    pub unknown: UnknownScheme,
    /// The text compiled as a scheme string (trimmed); the diagnostics' spans point into it.
    pub text: String,
    /// Why the text does not compile in the scheme language.
    pub diagnostics: Vec<Diagnostic>,
}

/// Diagnostics shown in full by [`ResolveError`]'s message; the rest are counted.
const SHOWN_DIAGNOSTICS: usize = 3;

impl ResolveError {
    /// The error of `source` (trimmed), given the name lookup that failed and the diagnostics
    /// of compiling it.
    pub fn new(unknown: UnknownScheme, source: &str, diagnostics: Vec<Diagnostic>) -> Self {
        ResolveError {
            unknown,
            text: source.to_string(),
            diagnostics,
        }
    }

    /// Whether the text reads like a registry name rather than a scheme string: at most 40
    /// letters, digits, `-` or `_`, with a lowercase letter, `-` or `_` (the letters of scheme
    /// strings are uppercase; a registry name written in uppercase was already found).
    pub fn looks_like_a_name(&self) -> bool {
        let name = self.unknown.name.trim();
        name.len() <= 40
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
            && name
                .chars()
                .any(|c| c.is_ascii_lowercase() || c == '-' || c == '_')
    }
}

impl fmt::Display for ResolveError {
    /// The language errors first, each with the line of the scheme it is about, then a
    /// registry suggestion when the text looks like a name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("not a valid scheme string: ")?;
        for (i, d) in self.diagnostics.iter().take(SHOWN_DIAGNOSTICS).enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            f.write_str(&d.render(&self.text))?;
        }
        let more = self.diagnostics.len().saturating_sub(SHOWN_DIAGNOSTICS);
        if more > 0 {
            write!(f, "\n({more} more errors)")?;
        }
        if self.looks_like_a_name() {
            let u = &self.unknown;
            write!(
                f,
                "\nnot a registered scheme name either: '{}'",
                u.name.trim()
            )?;
            if u.close_matches.is_empty() {
                f.write_str(" (`dpd schemes` lists them)")?;
            } else {
                write!(f, "; did you mean {}?", u.close_matches.join(", "))?;
            }
        }
        Ok(())
    }
}

/// The registered scheme named `name_or_source`, else the text compiled as a scheme string
/// (run by the stage interpreter, named by its text).
pub fn resolve(name_or_source: &str) -> Result<Box<dyn Scheme + Send + Sync>, ResolveError> {
    resolve_with(name_or_source, &Default::default())
}

/// [`resolve`], compiling a scheme string with `options` (`allow_inconsistent`).
pub fn resolve_with(
    name_or_source: &str,
    options: &Options,
) -> Result<Box<dyn Scheme + Send + Sync>, ResolveError> {
    let unknown = match lookup(name_or_source) {
        Ok(entry) => return Ok(entry.scheme()),
        Err(unknown) => unknown,
    };
    let source = name_or_source.trim();
    DynScheme::compile(source, source, options)
        .map(|s| Box::new(s) as Box<dyn Scheme + Send + Sync>)
        .map_err(|diagnostics| ResolveError::new(unknown, source, diagnostics))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("", ""), 0);
        assert_eq!(edit_distance("aboba", "aboba"), 0);
        assert_eq!(edit_distance("abobaa", "aboba"), 1);
        assert_eq!(edit_distance("baoab", "aboba"), 4);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "sas"), 3);
    }

    fn resolve_error(text: &str) -> String {
        match resolve(text) {
            Ok(_) => panic!("{text:?} resolved"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_bad_string_gets_its_language_error_with_a_caret_once() {
        let e = resolve_error("ABQ");
        assert!(e.starts_with("not a valid scheme string: unknown"), "{e}");
        assert!(e.contains("\n  ABQ\n    ^"), "{e}");
        assert!(!e.contains("registered"), "{e}");
        let long = resolve_error(&format!("{}Q", "A".repeat(100_000)));
        assert!(long.len() < 400, "{} bytes", long.len());
    }

    #[test]
    fn a_name_like_text_also_gets_a_registry_suggestion() {
        let e = resolve_error("abobaa");
        assert!(e.starts_with("not a valid scheme string: "), "{e}");
        assert!(
            e.contains("\nnot a registered scheme name either: 'abobaa'; did you mean aboba"),
            "{e}"
        );
        let e = resolve_error("zzz-yyy");
        assert!(e.ends_with("(`dpd schemes` lists them)"), "{e}");
    }

    #[test]
    fn names_and_aliases_are_unique_lowercase() {
        let mut seen = std::collections::HashSet::new();
        for e in entries() {
            for n in std::iter::once(e.name).chain(e.aliases.iter().copied()) {
                assert_eq!(n, normalise(n), "{n} is not in normal form");
                assert!(seen.insert(n), "{n} registered twice");
            }
        }
    }
}
