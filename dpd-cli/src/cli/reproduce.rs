//! `dpd reproduce`: the tables and figures of the papers in `scenes/papers/`, run and printed
//! published against measured with a verdict per number.

use super::{bad_input, progress, INTERRUPTED};
use dpd_measure::paper::compare::{compare, table, Comparison, Verdict};
use dpd_measure::paper::figure::draw;
use dpd_measure::paper::measure::{run_item, Measurements};
use dpd_measure::paper::{load_all, Item, Kind};
use dpd_measure::Control;
use serde::Serialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// An item id (see --list), a paper's prefix (e.g. 003) or `all`
    #[arg(default_value = "all")]
    item: String,
    /// Run each item's reduced protocol (its [quick] keys): seconds, for CI
    #[arg(long)]
    quick: bool,
    /// List the items and exit
    #[arg(long)]
    list: bool,
    /// Directory of the results (JSON per item, resumable sweep files, SVG figures)
    #[arg(long, value_name = "DIR", default_value = "results/papers")]
    out: PathBuf,
    /// Directory of the items (one subdirectory per paper)
    #[arg(long, value_name = "DIR", default_value = "scenes/papers")]
    items: PathBuf,
}

/// What is written to `<out>/<id>[.quick].json`.
#[derive(Serialize)]
struct Report<'a> {
    id: &'a str,
    quick: bool,
    wall_seconds: f64,
    comparisons: &'a [Comparison],
    figures: Vec<String>,
}

pub fn main(args: Args) -> ExitCode {
    let items = match load_all(&args.items) {
        Ok(items) => items,
        Err(e) => return bad_input(e),
    };
    if args.list {
        for item in &items {
            let what = if item.runs() { "" } else { " [not run]" };
            outln!("{:<16} {}{what}: {}", item.id, item.citation, item.title);
        }
        return ExitCode::SUCCESS;
    }
    let chosen: Vec<&Item> = items
        .iter()
        .filter(|i| {
            args.item == "all" || i.id == args.item || i.id.starts_with(&format!("{}-", args.item))
        })
        .collect();
    if chosen.is_empty() {
        let ids: Vec<&str> = items.iter().map(|i| i.id.as_str()).collect();
        return bad_input(format!(
            "no item {:?}; valid: all, a paper prefix, or one of {}",
            args.item,
            ids.join(", ")
        ));
    }
    if let Err(e) = std::fs::create_dir_all(&args.out) {
        return bad_input(format!("cannot create {}: {e}", args.out.display()));
    }
    let mut done: HashMap<String, (Measurements, f64)> = HashMap::new();
    let mut tally: HashMap<&str, usize> = HashMap::new();
    let start = Instant::now();
    for item in &chosen {
        outln!("== {} ({:?}): {}", item.id, item.kind, item.title);
        outln!("   {}, {}", item.reference, item.citation);
        if !item.notes.is_empty() {
            outln!("   {}", item.notes.trim().replace('\n', "\n   "));
        }
        if !item.runs() {
            outln!("   not a simulation: nothing to run\n");
            continue;
        }
        let needed: Vec<&Item> = std::iter::once(*item)
            .chain(
                item.panels
                    .iter()
                    .filter_map(|p| items.iter().find(|i| &i.id == p)),
            )
            .filter(|i| i.scene(args.quick).ok().flatten().is_some())
            .collect();
        for need in needed {
            if done.contains_key(&need.id) {
                continue;
            }
            match measure(need, args.quick, &args.out) {
                Ok(Some(m)) => {
                    done.insert(need.id.clone(), m);
                }
                Ok(None) => {}
                Err(code) => return code,
            }
        }
        let own = done.get(&item.id);
        let comparisons = own.map(|(m, _)| compare(item, m)).unwrap_or_default();
        for c in &comparisons {
            *tally.entry(verdict_name(&c.verdict)).or_default() += 1;
        }
        if !comparisons.is_empty() {
            out!("{}", table(&comparisons));
        }
        let figures = match (&item.plot, item.kind) {
            (Some(spec), Kind::Figure) => {
                let names: Vec<&String> = if item.panels.is_empty() {
                    vec![&item.id]
                } else {
                    item.panels.iter().collect()
                };
                let panels: Vec<(&str, &Measurements)> = names
                    .iter()
                    .filter_map(|n| Some((n.as_str(), &done.get(*n)?.0)))
                    .collect();
                let dir = args.out.join(figure_dir(&item.id, args.quick));
                match draw(spec, &panels, &dir) {
                    Ok(files) => files.iter().map(|f| f.display().to_string()).collect(),
                    Err(e) => {
                        errln!("dpd: error: {}: cannot draw: {e}", item.id);
                        return ExitCode::FAILURE;
                    }
                }
            }
            _ => Vec::new(),
        };
        if !figures.is_empty() {
            outln!("   drew {}", figures.join(", "));
        }
        let wall = own.map_or(0.0, |(_, s)| *s);
        outln!("   wall time of its runs: {wall:.1} s\n");
        let report = Report {
            id: &item.id,
            quick: args.quick,
            wall_seconds: wall,
            comparisons: &comparisons,
            figures,
        };
        let path = args
            .out
            .join(format!("{}{}.json", item.id, suffix(args.quick)));
        let text = serde_json::to_string_pretty(&report).unwrap_or_default();
        if let Err(e) = std::fs::write(&path, text) {
            errln!("dpd: error: cannot write {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
        if progress::stop_flag().load(Ordering::Relaxed) {
            outln!("interrupted: run the same command again to resume");
            return ExitCode::from(INTERRUPTED);
        }
    }
    let mut counts: Vec<_> = tally.into_iter().collect();
    counts.sort();
    let counts: Vec<String> = counts.iter().map(|(k, n)| format!("{n} {k}")).collect();
    outln!(
        "{} items in {:.1} s; numbers: {}",
        chosen.len(),
        start.elapsed().as_secs_f64(),
        if counts.is_empty() {
            "none".into()
        } else {
            counts.join(", ")
        }
    );
    ExitCode::SUCCESS
}

fn suffix(quick: bool) -> &'static str {
    if quick {
        ".quick"
    } else {
        ""
    }
}

fn figure_dir(id: &str, quick: bool) -> String {
    format!("{id}{}", suffix(quick))
}

fn verdict_name(v: &Verdict) -> &'static str {
    match v {
        Verdict::Agrees { .. } => "agree",
        Verdict::Differs { .. } => "differ",
        Verdict::Unresolved { .. } => "unresolved",
        Verdict::NotCompared => "not compared",
    }
}

/// Run one item with a progress bar; its measurements and wall time, or the exit code of a
/// failure.
fn measure(item: &Item, quick: bool, out: &Path) -> Result<Option<(Measurements, f64)>, ExitCode> {
    let bar = progress::bar(0, item.id.clone());
    let control = Control {
        stop: progress::stop_flag(),
        progress: &|n| bar.inc(n),
    };
    let start = Instant::now();
    let result = run_item(item, quick, out, control);
    bar.finish_and_clear();
    match result {
        Ok(m) => Ok(m.map(|m| (m, start.elapsed().as_secs_f64()))),
        Err(e) => Err(bad_input(format!("{}: {e}", item.id))),
    }
}
