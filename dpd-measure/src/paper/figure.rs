//! Figures of paper items redrawn as SVG from our runs.

use super::item::{PlotKind, PlotSpec};
use super::measure::Measurements;
use crate::plot::{mean_rdf, profile_plot, rdf_plot, write_plots};
use std::path::{Path, PathBuf};

type Error = Box<dyn std::error::Error>;

/// Draw `spec` for each of `panels` (named) into `dir`; the files written.
pub fn draw(
    spec: &PlotSpec,
    panels: &[(&str, &Measurements)],
    dir: &Path,
) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for (name, m) in panels {
        match spec.kind {
            PlotKind::Errors => {
                let Some(sweep) = &m.sweep else {
                    return Err(format!("{name}: an errors figure needs a sweep").into());
                };
                let sub = dir.join(name);
                std::fs::create_dir_all(&sub)?;
                written.extend(write_plots(sweep, &sub)?);
            }
            PlotKind::Rdf => {
                let mut curves = Vec::new();
                for (scheme, dt) in distinct_points(m) {
                    if let Some(g) = mean_rdf(&m.runs_at(&scheme, dt)) {
                        curves.push((format!("{scheme}, dt = {dt}"), g));
                    }
                }
                let path = dir.join(format!("{name}-rdf.svg"));
                rdf_plot(&curves, &format!("g(r), {name}"), &path)?;
                written.push(path);
            }
            PlotKind::Profile => {
                for (scheme, dt) in distinct_points(m) {
                    let runs = m.runs_at(&scheme, dt);
                    let Some(rows) = runs.first().and_then(|r| r.profile.as_ref()) else {
                        continue;
                    };
                    let axis = m.scene.observe.profile.as_ref().map_or(2, |p| p.axis);
                    let path = dir.join(format!("{name}-profile-{scheme}-dt{dt}.svg"));
                    profile_plot(rows, axis, &path)?;
                    written.push(path);
                }
            }
        }
    }
    Ok(written)
}

/// The (scheme, dt) of the runs, in the order first met.
fn distinct_points(m: &Measurements) -> Vec<(String, f64)> {
    let mut out: Vec<(String, f64)> = Vec::new();
    for p in &m.points {
        if !out.iter().any(|(s, dt)| s == &p.scheme && *dt == p.dt) {
            out.push((p.scheme.clone(), p.dt));
        }
    }
    out
}
