//! `dpd design FAMILY`: solve a family's order conditions for its highest orders, then
//! minimise the error norm with the freedom left (see `dpd_ir::design`); with `--measure`,
//! sweep the best members and ABOBA on a scene and set the predicted order against the
//! measured one.

use super::predict::{spectrum_of, SpectrumArgs};
use super::scene_flags::{SceneFlags, SchemeList, SweepFlags};
use super::{bad_input, print_json, sweep};
use dpd::design::{design, Design, Member, Objective};
use dpd::lang::compile_family;
use dpd_measure::SchemeSummary;
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::ExitCode;

/// The scheme the measured candidates are compared with (efficiency 1).
const REFERENCE: &str = "aboba";

#[derive(Debug, clap::Args)]
pub struct Args {
    /// A scheme with free parameters, e.g. "param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O"
    family: String,
    /// Further points to report, one value per parameter separated by commas; repeatable,
    /// e.g. --at 0.1932
    #[arg(long, allow_negative_numbers = true)]
    at: Vec<String>,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
    /// Sweep the best members (see --top) and ABOBA on the scene (--scene and the scene
    /// flags; the dt grid from its [sweep] table) and compare predicted with measured ranks
    #[arg(long)]
    measure: bool,
    /// How many members --measure sweeps: those of the highest orders with the smallest
    /// error norm, solutions and notable points alike
    #[arg(long, default_value_t = 3)]
    top: usize,
    /// Directory of --measure's sweep (design.json, resumable; CSV; SVG plots)
    #[arg(long, value_name = "DIR", default_value = "results/design")]
    out: PathBuf,
    #[command(flatten)]
    scene: SceneFlags,
    /// What chooses the free parameters: `norm` (the order conditions, then the smallest
    /// error norm) or `predicted` (the longest predicted critical step of 10 % T_C error per
    /// force evaluation over the family's box, on the modes of --scene and --gamma, as `dpd
    /// predict`; printed after the norm's design)
    #[arg(long, value_enum, default_value_t = DesignObjective::Norm)]
    objective: DesignObjective,
}

/// How `dpd design` chooses the free parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DesignObjective {
    Norm,
    Predicted,
}

pub fn main(args: Args) -> ExitCode {
    let family = match compile_family(args.family.trim()) {
        Ok(f) => f,
        Err(e) => {
            let why: Vec<String> = e.iter().map(ToString::to_string).collect();
            return bad_input(format!(
                "invalid family = {:?}: {}",
                args.family,
                why.join("; ")
            ));
        }
    };
    let mut extra = Vec::new();
    for text in &args.at {
        let values: Result<Vec<f64>, _> = text.split(',').map(|v| v.trim().parse()).collect();
        match values {
            Ok(v) if v.len() == family.parameters.len() && v.iter().all(|x| x.is_finite()) => {
                extra.push(v)
            }
            _ => {
                return bad_input(format!(
                    "invalid --at = {text:?}: expected {} finite numbers separated by commas ({})",
                    family.parameters.len(),
                    family.names().join(", ")
                ))
            }
        }
    }
    let Some(d) = design(&family, &extra) else {
        return bad_input(format!(
            "invalid family = {:?}: it cannot be built at a generic point of its box",
            args.family
        ));
    };
    let predicted = match args.objective {
        DesignObjective::Norm => None,
        DesignObjective::Predicted => {
            let spectrum = SpectrumArgs {
                scene: args.scene.scene.clone(),
                gamma: args.scene.gamma,
                ..SpectrumArgs::default()
            };
            let predictor = match spectrum_of(&spectrum) {
                Ok((s, _, _)) => dpd_predict::Predictor::new(&s),
                Err(e) => return bad_input(e),
            };
            let points: Vec<Vec<f64>> = d
                .solutions
                .iter()
                .chain(&d.notable)
                .map(|m| m.parameters.iter().map(|(_, v)| *v).collect())
                .collect();
            match dpd_predict::design::best_member(&family, &predictor, &points) {
                Some(best) => Some(best),
                None => return bad_input("no point of the family's box can be predicted"),
            }
        }
    };
    if args.json && !args.measure {
        return match &predicted {
            Some(best) => print_json(&json!({ "design": d, "predicted": best })),
            None => print_json(&d),
        };
    }
    if !args.json {
        let inv = |p: Option<u32>| p.map_or("-".to_string(), |p| p.to_string());
        outln!(
            "family: {}\ngeneric orders: deterministic {}, invariant measure {}; minimising the {:?} norm",
            d.family,
            d.generic_orders.0,
            inv(d.generic_orders.1),
            d.objective
        );
        outln!("solutions (highest orders, best first):");
        print_members(&d.solutions);
        outln!("notable points:");
        print_members(&d.notable);
        if let Some(best) = &predicted {
            outln!(
                "predicted best ({} members): {}: dt_c 10 % {} per {} force evaluation(s), {}",
                best.evaluated,
                point(&best.parameters),
                best.critical_dt_10
                    .dt()
                    .map_or("> 2".to_string(), |dt| format!("{dt:.4}")),
                best.force_evaluations_per_step,
                best.program
            );
        }
    }
    if args.measure {
        return measure(&d, &args);
    }
    ExitCode::SUCCESS
}

/// Parameter values as `l = 0.2000000000, c = ...`.
fn point(parameters: &[(String, f64)]) -> String {
    let point: Vec<String> = parameters
        .iter()
        .map(|(n, v)| format!("{n} = {v:.10}"))
        .collect();
    point.join(", ")
}

fn print_members(members: &[Member]) {
    let norm = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.6}"));
    for m in members {
        outln!(
            "  {}: det {} (norm {}), inv {} (norm {}), freedom {}, {} force / {} pair-distance evaluations",
            point(&m.parameters),
            m.deterministic_order,
            norm(m.deterministic_error_norm),
            m.invariant_measure_order.map_or("-".to_string(), |p| p.to_string()),
            norm(m.invariant_measure_error_norm),
            m.freedom,
            m.force_evaluations_per_step,
            m.pair_distance_evaluations_per_step
        );
        if let Some(limit) = &m.limit {
            outln!("    (the infimum as {limit}, where the scheme cannot be built; this point is next to it)");
        }
    }
}

/// The `top` members of the highest orders with the smallest norms, one per program.
fn candidates(d: &Design, top: usize) -> Vec<&Member> {
    let Some(best) = d
        .solutions
        .iter()
        .chain(&d.notable)
        .map(Member::orders)
        .max()
    else {
        return Vec::new();
    };
    let mut members: Vec<&Member> = d
        .solutions
        .iter()
        .chain(&d.notable)
        .filter(|m| m.orders() == best)
        .collect();
    members.sort_by(|a, b| a.norm(d.objective).total_cmp(&b.norm(d.objective)));
    let mut seen = std::collections::HashSet::new();
    members.retain(|m| seen.insert(m.program.clone()));
    members.truncate(top);
    members
}

/// Ranks (1 = best) of `values`, largest first; `None` values rank last, unranked.
fn ranks_descending(values: &[Option<f64>]) -> Vec<Option<usize>> {
    values
        .iter()
        .map(|v| v.map(|x| 1 + values.iter().flatten().filter(|&&y| y > x).count()))
        .collect()
}

fn measure(d: &Design, args: &Args) -> ExitCode {
    if args.top == 0 {
        return bad_input("invalid --top = 0: at least one member must be measured");
    }
    let chosen = candidates(d, args.top);
    let mut schemes: Vec<String> = chosen.iter().map(|m| m.program.clone()).collect();
    schemes.push(REFERENCE.to_string());
    let sweep_keys = SweepFlags {
        schemes: Some(SchemeList(schemes.clone())),
        reference: Some(REFERENCE.to_string()),
        ..Default::default()
    };
    let scene = match sweep_keys.keys().and_then(|k| args.scene.scene_with(&k)) {
        Ok(scene) => scene,
        Err(e) => return bad_input(e),
    };
    let json_path = args.out.join("design.json");
    let (results, written) = match sweep::measure(&scene, &json_path, &args.out, false) {
        Ok(done) => done,
        Err(code) => return code,
    };
    let summary = |scheme: &str| results.summary.iter().find(|s| s.scheme == scheme);
    // Predicted: the norm of each candidate and of the reference.
    let reference_norm = dpd::schemes::lookup(REFERENCE)
        .ok()
        .and_then(|e| e.scheme().program().map(|p| p.analysis()))
        .and_then(|a| d.objective.norm_of(&a));
    let mut norms: Vec<Option<f64>> = chosen.iter().map(|m| Some(m.norm(d.objective))).collect();
    norms.push(reference_norm);
    let predicted = ranks_descending(&norms.iter().map(|n| n.map(|x| -x)).collect::<Vec<_>>());
    let efficiency: Vec<Option<f64>> = schemes
        .iter()
        .map(|s| summary(s).and_then(|s| s.efficiency))
        .collect();
    let measured = ranks_descending(&efficiency);
    let rows: Vec<Value> = schemes
        .iter()
        .enumerate()
        .map(|(k, scheme)| {
            let s: Option<&SchemeSummary> = summary(scheme);
            json!({
                "scheme": scheme,
                "error_norm": norms[k],
                "predicted_rank": predicted[k],
                "critical_dt_10": s.and_then(|s| s.critical_dt_10),
                "critical_dt_1": s.and_then(|s| s.critical_dt_1),
                "efficiency": efficiency[k],
                "measured_rank": measured[k],
            })
        })
        .collect();
    if args.json {
        let mut value = match serde_json::to_value(d) {
            Ok(v) => v,
            Err(e) => return bad_input(format!("cannot serialise the design: {e}")),
        };
        for list in ["solutions", "notable"] {
            for m in value[list].as_array_mut().into_iter().flatten() {
                if let Some(row) = rows.iter().find(|r| r["scheme"] == m["program"]) {
                    for key in ["critical_dt_10", "critical_dt_1", "efficiency"] {
                        m[key] = row[key].clone();
                    }
                }
            }
        }
        value["measured"] = Value::Array(rows);
        value["sweep"] = json!(json_path.display().to_string());
        let code = print_json(&value);
        if let Err(e) = written {
            errln!("dpd: error: {e}");
            return ExitCode::FAILURE;
        }
        return code;
    }
    outln!(
        "measured on the scene ({} norm predicts: smaller is better; efficiency relative to {REFERENCE}, T_C or the scene's observable):",
        match d.objective {
            Objective::Deterministic => "deterministic",
            Objective::InvariantMeasure => "invariant-measure",
        }
    );
    let num = |v: &Value, digits: usize| {
        v.as_f64()
            .map_or("-".to_string(), |x| format!("{x:.digits$}"))
    };
    let rank = |v: &Value| v.as_u64().map_or("-".to_string(), |x| x.to_string());
    outln!(
        "  {:>9} {:>9} {:>10} {:>10} {:>10} {:>8}  scheme",
        "norm",
        "predicted",
        "dt_c 10 %",
        "dt_c 1 %",
        "efficiency",
        "measured"
    );
    for r in &rows {
        outln!(
            "  {:>9} {:>9} {:>10} {:>10} {:>10} {:>8}  {}",
            num(&r["error_norm"], 6),
            rank(&r["predicted_rank"]),
            num(&r["critical_dt_10"], 4),
            num(&r["critical_dt_1"], 4),
            num(&r["efficiency"], 3),
            rank(&r["measured_rank"]),
            r["scheme"].as_str().unwrap_or_default()
        );
    }
    sweep::finish(&results, written, &scene)
}
