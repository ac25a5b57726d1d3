//! `dpd_scheme!` against the hand-written reference steps and against `DynScheme`: bitwise
//! equal trajectories, evaluation counts as the program states, and the program exposed.

// The core's test set-up (the standard box, bitwise comparison) names the core `dpd_core`;
// `dpd` re-exports everything it uses.
extern crate dpd as dpd_core;
#[path = "../dpd-core/tests/common/mod.rs"]
mod common;

use dpd::lang::Options;
use dpd::{dpd_scheme, reference, AdvanceError, DynScheme, Scheme, System};

const DT: f64 = 0.01;
const SEED: u64 = 7;

/// The standard box of algorithms.md section 8 (N = 500, density 3, a = 25, gamma = 4.5).
fn standard_box() -> System {
    common::standard_box(4.5, DT, SEED)
}

/// Runs both schemes from the same standard box and asserts bitwise equal states after every
/// step.
fn assert_same_trajectory(a: &impl Scheme, b: &impl Scheme, steps: u64) {
    assert_same_trajectory_from(standard_box, a, b, steps);
}

/// [`assert_same_trajectory`] from the state `start` makes.
fn assert_same_trajectory_from(
    start: fn() -> System,
    a: &impl Scheme,
    b: &impl Scheme,
    steps: u64,
) {
    let (mut sa, mut sb) = (start(), start());
    for step in 0..steps {
        sa.advance(a, 1).unwrap();
        sb.advance(b, 1).unwrap();
        assert!(
            common::same_bits(&sa, &sb),
            "{} and {} differ after step {}",
            a.name(),
            b.name(),
            step + 1
        );
    }
}

fn dynamic(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Options::default()).unwrap()
}

#[test]
fn aboba_matches_the_reference_bitwise() {
    assert_same_trajectory(&dpd_scheme!("ABOBA"), &reference::Aboba, 1000);
}

#[test]
fn dpd_s1_matches_the_reference_bitwise() {
    assert_same_trajectory(&dpd_scheme!("ObBAB"), &reference::DpdS1, 1000);
}

#[test]
fn velocity_verlet_matches_the_reference_bitwise() {
    assert_same_trajectory(
        &dpd_scheme!("F(1/2) A F(1/2)"),
        &reference::VelocityVerlet,
        1000,
    );
}

/// The standard box with Lowe-Andersen collisions at rate 2 (for schemes with L).
fn colliding_box() -> System {
    let params = dpd::Params::builder().collision_rate(2.0);
    common::system(500, 3.0, params, DT, SEED)
}

#[test]
fn lowe_andersen_schemes_match_dyn_scheme_bitwise() {
    for (generated, source) in [
        (
            &dpd_scheme!("A(1/2) B(1/2) L B(1/2) A(1/2)") as &dyn Scheme,
            "A(1/2) B(1/2) L B(1/2) A(1/2)",
        ),
        (&dpd_scheme!("B(1/2) A B(1/2) L"), "B(1/2) A B(1/2) L"),
        (&dpd_scheme!("BA L< L> AB"), "BA L< L> AB"),
    ] {
        same_steps(colliding_box, generated, source);
    }
}

/// `generated` and `DynScheme` of `source` from two `start()` systems: the same bits (with xi)
/// after each of 200 steps; returns the first system.
fn same_steps(start: impl Fn() -> System, generated: &dyn Scheme, source: &str) -> System {
    let (mut sa, mut sb) = (start(), start());
    let dynamic = dynamic(source);
    for step in 0..200 {
        sa.advance(generated, 1).unwrap();
        sb.advance(&dynamic, 1).unwrap();
        assert!(common::same_bits(&sa, &sb), "{source}: step {}", step + 1);
    }
    sa
}

/// PAdL (Oa and Xi) and PNHL (On and Xi) at a thermostat mass of 50, where xi moves by
/// several per cent: the same bits for positions, momenta and xi.
#[test]
fn adaptive_schemes_match_dyn_scheme_bitwise() {
    let adaptive_box = || {
        let params = dpd::Params::builder().thermostat_mass(50.0);
        common::system(500, 3.0, params, DT, SEED)
    };
    for (generated, source) in [
        (
            &dpd_scheme!("B A Xi(1/2) Oa Xi(1/2) A B") as &dyn Scheme,
            "B A Xi(1/2) Oa Xi(1/2) A B",
        ),
        (
            &dpd_scheme!("A(1/2) B(1/2) Xi(1/2) Oa Xi(1/2) B(1/2) A(1/2)"),
            "A(1/2) B(1/2) Xi(1/2) Oa Xi(1/2) B(1/2) A(1/2)",
        ),
    ] {
        let sa = same_steps(adaptive_box, generated, source);
        assert!((sa.xi() - 1.0).abs() > 1e-3, "{source}: xi = {}", sa.xi());
    }
    // PNHL (On, and Xi with its own noise): xi leaves its start, 0.
    let pnhl_box = || {
        let params = dpd::Params::builder().thermostat_mass(50.0);
        common::system(500, 3.0, params.thermostat_friction(1.0), DT, SEED)
    };
    let source = "B A Xi(1/2) On Xi(1/2) A B";
    let sa = same_steps(pnhl_box, &dpd_scheme!("B A Xi(1/2) On Xi(1/2) A B"), source);
    assert!(sa.xi().abs() > 1e-3, "{source}: xi = {}", sa.xi());
}

/// Metropolis-adjusted schemes at dt = 0.05 on the relaxed standard box, where some proposals
/// are rejected: the same bits after every step, and the same acceptance.
#[test]
fn adjusted_schemes_match_dyn_scheme_bitwise() {
    let relaxed = || {
        let mut sys = common::standard_box(4.5, 0.02, SEED);
        sys.advance(&dynamic("ABOBA"), 300).unwrap();
        sys.set_dt(0.05).unwrap();
        sys
    };
    for (generated, source) in [
        (
            &dpd_scheme!("{B(1/2) A B(1/2)} O") as &dyn Scheme,
            "{B(1/2) A B(1/2)} O",
        ),
        (
            &dpd_scheme!("{A(1/4) B(1/2) A(1/4)} Ob(1/2) {A(1/4) B(1/2) A(1/4)} O(1/2)"),
            "{A(1/4) B(1/2) A(1/4)} Ob(1/2) {A(1/4) B(1/2) A(1/4)} O(1/2)",
        ),
    ] {
        let sa = same_steps(relaxed, generated, source);
        let a = sa.acceptance();
        assert!(0 < a.accepted && a.accepted < a.proposed, "{source}: {a:?}");
    }
}

#[test]
fn obab_with_exact_o_matches_dyn_scheme_bitwise() {
    assert_same_trajectory(&dpd_scheme!("OBAB"), &dynamic("OBAB"), 1000);
}

/// One macro invocation per string, each against `DynScheme` of the same string.
macro_rules! against_dyn_scheme {
    ($($source:literal),* $(,)?) => {
        $(assert_same_trajectory(&dpd_scheme!($source), &dynamic($source), 200);)*
    };
}

#[test]
fn generated_schemes_match_dyn_scheme_bitwise() {
    against_dyn_scheme!(
        "BAOOAB",
        "OBABO",
        "TAT",
        "ATA",
        "BAOAB",
        "S(x1)S(x0)S(x1) O",
        "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = F)",
        "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O",
        "A(1/4) B(1/3) A(1/2) O(1/2) B(2/3) Ob(1/2) A(1/4)",
        "A(sqrt(2)/4) B A(1/2 - sqrt(2)/4) O A(1/2) B",
        "BA O< O> AB",
        "A T< T> A",
        "B[pair](1/4) (A(1/8) B[pair](1/8) A(1/8))^4 O B[pair](1/4)",
        "F[pair](1/2) A F[pair](1/2)",
    );
}

/// On a fluid (no bonds) a scheme that names only the pair group kicks with the same forces
/// as its ungrouped form, and runs bit for bit as it does, repetitions included.
#[test]
fn pair_groups_run_bitwise_as_the_ungrouped_scheme() {
    assert_same_trajectory(
        &dpd_scheme!("B[pair](1/2) A O A B[pair](1/2)"),
        &dpd_scheme!("BAOAB"),
        200,
    );
    assert_same_trajectory(
        &dpd_scheme!("(B[pair](1/4) A(1/2) B[pair](1/4))^2 O"),
        &dynamic("B(1/4) A(1/2) B(1/4) B(1/4) A(1/2) B(1/4) O"),
        200,
    );
    assert_same_trajectory(
        &dpd_scheme!("F[pair](1/2) A F[pair](1/2)"),
        &reference::VelocityVerlet,
        200,
    );
}

/// A melt of 50 bonded chains of 6 beads (harmonic and FENE bonds, both angle styles), its
/// bonded pairs excluded from the pair forces or not.
fn melt(exclude: bool) -> System {
    common::melt(50, 6, dpd::Params::builder(), SEED)
        .exclude_bonded(exclude)
        .dt(DT)
        .build()
        .unwrap()
}

/// r-RESPA with the bonds on the inner step runs bit for bit the same from `dpd_scheme!` and
/// from the run-time compiler from `start`, and so do ABOBA and velocity Verlet, which apply
/// all forces together, against the reference steps.
fn bonded_schemes_agree(start: fn() -> System) {
    const RESPA: &str = "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)";
    assert_same_trajectory_from(
        start,
        &dpd_scheme!("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)"),
        &dynamic(RESPA),
        200,
    );
    assert_same_trajectory_from(start, &dpd_scheme!("ABOBA"), &reference::Aboba, 200);
    assert_same_trajectory_from(
        start,
        &dpd_scheme!("F(1/2) A F(1/2)"),
        &reference::VelocityVerlet,
        200,
    );
}

/// [`bonded_schemes_agree`] on the melt.
#[test]
fn bonded_melt_runs_the_same_from_the_macro_and_the_compiler() {
    bonded_schemes_agree(|| melt(false));
}

/// [`bonded_schemes_agree`] on the melt with its bonded pairs excluded, and SAS with the bonds
/// on B[bond] (its T sweeps read the table the exclusion filtered).
#[test]
fn excluded_melt_runs_the_same_from_the_macro_and_the_compiler() {
    bonded_schemes_agree(|| melt(true));
    const SAS: &str = "T(1/2) B[bond](1/2) A B[bond](1/2) T(1/2)";
    assert_same_trajectory_from(
        || melt(true),
        &dpd_scheme!("T(1/2) B[bond](1/2) A B[bond](1/2) T(1/2)"),
        &dynamic(SAS),
        200,
    );
}

/// `B[bond]` on a fluid without bonds: refused before the first step, naming the group, with
/// the system untouched; the macro and the run-time compiler alike.
#[test]
fn a_bonded_kick_on_a_fluid_is_refused_before_the_first_step() {
    const RESPA: &str = "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)";
    let generated = dpd_scheme!("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)");
    let compiled = dynamic(RESPA);
    for scheme in [&generated as &dyn Scheme, &compiled] {
        let mut sys = standard_box();
        let before = sys.clone();
        match sys.advance(scheme, 10) {
            Err(AdvanceError::Scheme(e)) => {
                let message = e.to_string();
                assert!(
                    message.contains("B[bond]") && message.contains("bonded forces"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(sys.step(), 0);
        assert!(common::same_bits(&before, &sys));
        assert_eq!(sys.counters(), before.counters());
    }
}

#[test]
fn evaluation_counts_match_the_program() {
    fn check(scheme: impl Scheme, force: u64, distance: u64) {
        let program = scheme.program().unwrap();
        assert_eq!(program.force_evaluations_per_step() as u64, force);
        assert_eq!(
            program.pair_distance_evaluations_per_step() as u64,
            distance
        );
        let mut sys = standard_box();
        // The first step fills the caches; count over the steady state after it.
        sys.advance(&scheme, 1).unwrap();
        let before = sys.counters();
        let steps = 20;
        sys.advance(&scheme, steps).unwrap();
        let after = sys.counters();
        assert_eq!(after.bonded_force_evaluations, 0, "a fluid has no bonds");
        let per_step = |a: u64, b: u64| (a - b) as f64 / steps as f64;
        assert_eq!(
            (
                per_step(after.force_evaluations, before.force_evaluations),
                per_step(
                    after.pair_distance_evaluations,
                    before.pair_distance_evaluations
                ),
            ),
            (force as f64, distance as f64),
            "{}",
            scheme.name()
        );
    }
    check(dpd_scheme!("ABOBA"), 1, 1);
    check(dpd_scheme!("OBAB"), 1, 1);
    check(dpd_scheme!("F(1/2) A F(1/2)"), 1, 1);
    check(dpd_scheme!("BAOAB"), 1, 2);
    // Each inner drift is followed by a pair kick: five pair evaluations; none bonded.
    check(
        dpd_scheme!("B[pair](1/4) (A(1/8) B[pair](1/8) A(1/8))^4 O B[pair](1/4)"),
        5,
        5,
    );
}

#[test]
fn program_exposes_stages_symmetry_and_analysis() {
    let aboba = dpd_scheme!("ABOBA", name = "aboba", invariant_order >= 2);
    assert_eq!(aboba.name(), "aboba");
    let program = aboba.program().unwrap();
    assert_eq!(program.source, "ABOBA");
    assert_eq!(program.to_string(), "A(1/2) B(1/2) O(1) B(1/2) A(1/2)");
    assert_eq!(program.stages.len(), 5);
    assert!(program.is_symmetric());
    let analysis = program.analysis();
    assert!(analysis.consistent);
    assert_eq!(analysis.deterministic_order, 2);
    assert!(analysis.invariant_measure_order.unwrap() >= 2);
    // The same program instance on every call.
    assert!(std::ptr::eq(program, aboba.program().unwrap()));

    let abo = dpd_scheme!("ABO");
    assert!(!abo.program().unwrap().is_symmetric());
    assert_eq!(
        abo.program().unwrap().analysis().invariant_measure_order,
        Some(1)
    );
}

/// The program a generated scheme carries is the one the scheme compiler makes of its source:
/// the same stages, coefficients (bits and exact values), streams and sweep orders.
#[test]
fn generated_program_is_the_compiled_program() {
    let cases: [(&dyn Scheme, &str, bool); 7] = [
        (
            &dpd_scheme!("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)"),
            "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)",
            false,
        ),
        (&dpd_scheme!("ABOBA"), "ABOBA", false),
        (&dpd_scheme!("BAOOAB"), "BAOOAB", false),
        (&dpd_scheme!("ObBAB"), "ObBAB", false),
        (
            &dpd_scheme!("F(7/24) A(2/3) F(3/4) A(-2/3) F(-1/24) A(1)"),
            "F(7/24) A(2/3) F(3/4) A(-2/3) F(-1/24) A(1)",
            false,
        ),
        (
            &dpd_scheme!("S(x1) S(x0) S(x1) O"),
            "S(x1) S(x0) S(x1) O",
            false,
        ),
        (
            &dpd_scheme!("S(x1) S(-x0) S(x1) Ob", allow_inconsistent),
            "S(x1) S(-x0) S(x1) Ob",
            true,
        ),
    ];
    for (scheme, source, allow_inconsistent) in cases {
        let compiled = dpd::lang::compile_with(source, &Options { allow_inconsistent }).unwrap();
        let carried = scheme.program().unwrap();
        assert_eq!(*carried, compiled, "{source}");
        let bits = |p: &dpd::Program| -> Vec<u64> {
            p.stages
                .iter()
                .chain(&p.unmerged_stages)
                .map(|s| s.coeff.value.to_bits())
                .collect()
        };
        assert_eq!(bits(carried), bits(&compiled), "{source}");
    }
}

#[test]
fn allow_inconsistent_reproduces_m_shardlow_1() {
    let m1 = dpd_scheme!("S(x1) S(-x0) S(x1) Ob", allow_inconsistent);
    let analysis = m1.program().unwrap().analysis();
    assert!(!analysis.consistent);
    assert!((analysis.coefficient_sums.a - 4.405).abs() < 1e-3);
    assert_same_trajectory(
        &m1,
        &DynScheme::compile(
            "m1",
            "S(x1) S(-x0) S(x1) Ob",
            &Options {
                allow_inconsistent: true,
            },
        )
        .unwrap(),
        20,
    );
}
