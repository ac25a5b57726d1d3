//! SVG plots of a sweep: relative errors against dt on log-log axes with a second-order guide
//! line, and radial distribution functions overlaid per dt; slab profiles of one run.

use super::aggregate::{worst_species, Aggregate};
use super::result::RunResult;
use super::scene::Observable;
use super::sweep::{SweepResults, THRESHOLDS};
use dpd_core::observe::ProfileRow;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

type Error = Box<dyn std::error::Error>;

const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// What a panel needs of its sweep besides a row: k_B T and the baseline row.
struct Context<'a> {
    kbt: f64,
    baseline: Option<&'a Aggregate>,
}

/// A relative error of a row, and the standard error of that relative error.
type Column = fn(&Aggregate) -> Option<f64>;
type Spread = fn(&Aggregate, &Context) -> Option<f64>;

/// One panel: its title, the signed relative error of a row and its standard error.
struct Panel {
    title: &'static str,
    error: Column,
    stderr: Spread,
}

/// The standard error of `(x - b) / |b|` for a row's mean `x` and the baseline's `b`, each with
/// its standard error (the baseline's may be absent: one run).
fn against_baseline(
    x: Option<f64>,
    s: Option<f64>,
    b: Option<f64>,
    s_b: Option<f64>,
) -> Option<f64> {
    let (_, s, b) = (x?, s?, b?);
    Some(s.hypot(s_b.unwrap_or(0.0)) / b.abs())
}

/// [`against_baseline`] for the mean and standard error `of` a row and of the baseline.
fn beside_baseline(
    r: &Aggregate,
    c: &Context,
    of: fn(&Aggregate) -> (Option<f64>, Option<f64>),
) -> Option<f64> {
    let ((x, s), (b, s_b)) = (of(r), of(c.baseline?));
    against_baseline(x, s, b, s_b)
}

const T_C: Panel = Panel {
    title: "|T_C error|",
    error: |r| r.configurational_temperature_error,
    stderr: |r, c| Some(r.configurational_temperature_stderr? / c.kbt),
};

const ETA: Panel = Panel {
    title: "|eta error| vs baseline",
    error: |r| r.shear_viscosity_relative_error,
    stderr: |r, c| {
        let b = c.baseline?.viscosity?;
        let v = r.viscosity?;
        let (s, s_b) = (v.shear_viscosity_error, b.shear_viscosity_error);
        against_baseline(v.shear_viscosity, s, b.shear_viscosity, s_b)
    },
};

/// The error panels after the observable's.
const PANELS: [Panel; 3] = [
    Panel {
        title: "|T_K error|",
        error: |r| r.kinetic_temperature_error,
        stderr: |r, c| Some(r.kinetic_temperature_stderr? / c.kbt),
    },
    Panel {
        title: "|U error| vs baseline",
        error: |r| r.potential_energy_error,
        stderr: |r, c| beside_baseline(r, c, |a| (a.potential_energy, a.potential_energy_stderr)),
    },
    Panel {
        title: "|P error| vs baseline",
        error: |r| r.pressure_error,
        stderr: |r, c| beside_baseline(r, c, |a| (a.pressure, a.pressure_stderr)),
    },
];

/// Panels drawn where some row has their error: the mean bond length (with bonds) and the
/// like-neighbour fraction (with `like_neighbours`; the species that errs most, its bar that
/// species' standard error).
const MEASURED_PANELS: [Panel; 2] = [
    Panel {
        title: "|bond length error| vs baseline",
        error: |r| r.bond_length_error,
        stderr: |r, c| beside_baseline(r, c, |a| (a.bond_length, a.bond_length_stderr)),
    },
    Panel {
        title: "|like-neighbour error| vs baseline",
        error: |r| r.like_neighbours_error,
        stderr: |r, c| {
            let b = c.baseline?;
            let (values, reference) = (r.like_neighbours.as_ref()?, b.like_neighbours.as_ref()?);
            let (name, _) = worst_species(values, reference)?;
            let spread = |m: &Option<BTreeMap<String, f64>>| m.as_ref()?.get(name).copied();
            let (s, s_b) = (
                spread(&r.like_neighbours_stderr),
                spread(&b.like_neighbours_stderr),
            );
            against_baseline(
                values.get(name).copied(),
                s,
                reference.get(name).copied(),
                s_b,
            )
        },
    },
];

/// Tick values for a log axis over `[lo, hi]`: 1, 2 and 5 (and, over less than two decades,
/// also 1.5, 3 and 7) times the powers of ten inside it.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let fine = hi / lo < 100.0;
    let mantissas: &[f64] = if fine {
        &[1.0, 1.5, 2.0, 3.0, 5.0, 7.0]
    } else {
        &[1.0, 2.0, 5.0]
    };
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    (first..=last)
        // Divided for negative exponents, so that 1.5 / 10 is the double nearest 0.15, as its
        // label prints it.
        .flat_map(|e| {
            mantissas.iter().map(move |m| match e < 0 {
                true => m / 10f64.powi(-e),
                false => m * 10f64.powi(e),
            })
        })
        .filter(|&t| t >= lo && t <= hi)
        .collect()
}

/// Write `errors.svg` (error panels: the sweep's observable, T_K, U, P, and where measured the
/// mean bond length and the like-neighbour fraction) and one `rdf-<scheme>.svg` per scheme
/// with RDF data into `dir`; returns the files written.
pub fn write_plots(results: &SweepResults, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut written = vec![dir.join("errors.svg")];
    errors(results, &written[0])?;
    let schemes = results.summary.iter().map(|s| s.scheme.as_str());
    for scheme in schemes {
        let path = dir.join(format!("rdf-{}.svg", file_name(scheme)));
        if rdf(results, scheme, &path)? {
            written.push(path);
        }
    }
    Ok(written)
}

/// A scheme string made safe for a file name.
fn file_name(scheme: &str) -> String {
    scheme
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn errors(results: &SweepResults, path: &Path) -> Result<(), Error> {
    let observable = match results.observable {
        Observable::ConfigurationalTemperature => T_C,
        Observable::Viscosity => ETA,
    };
    let measured = MEASURED_PANELS
        .into_iter()
        .filter(|p| results.rows.iter().any(|r| (p.error)(r).is_some()));
    let panels: Vec<Panel> = std::iter::once(observable)
        .chain(PANELS)
        .chain(measured)
        .collect();
    // Two rows of panels 600 x 450 each.
    let columns = panels.len().div_ceil(2);
    let root = SVGBackend::new(path, (600 * columns as u32, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    for (area, panel) in root.split_evenly((2, columns)).iter().zip(&panels) {
        error_panel(area, results, panel)?;
    }
    root.present()?;
    Ok(())
}

/// A point of an error panel: dt, the signed relative error and its standard error.
type ErrorPoint = (f64, f64, Option<f64>);

/// |error| against dt on log-log axes, one series per scheme: a filled marker where the error
/// is positive, a hollow one where it is negative, a bar of one standard error either way
/// (down to the axis where it reaches zero), the 10 % and 1 % lines and a dt^2 guide.
fn error_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    results: &SweepResults,
    panel: &Panel,
) -> Result<(), Error>
where
    DB::ErrorType: 'static,
{
    let context = Context {
        kbt: results.scene.physics.kbt,
        baseline: results.baseline.as_ref(),
    };
    let series: Vec<(&str, Vec<ErrorPoint>)> = results
        .summary
        .iter()
        .map(|s| {
            let pts = results
                .rows
                .iter()
                .filter(|r| r.scheme == s.scheme && r.stable)
                .filter_map(|r| Some((r.dt, (panel.error)(r)?, (panel.stderr)(r, &context))))
                .filter(|&(_, e, _)| e != 0.0 && e.is_finite())
                .collect();
            (s.scheme.as_str(), pts)
        })
        .collect();
    let w = results.scene.sweep_spec();
    let (x0, x1) = (w.dt_min / 1.1, w.dt_max * 1.1);
    let all = series
        .iter()
        .flat_map(|(_, p)| p.iter().map(|&(_, e, _)| e.abs()));
    let (lo, hi) = all.fold((0.005f64, 0.2f64), |(lo, hi), e| (lo.min(e), hi.max(e)));
    let (y0, y1) = (lo / 2.0, (hi * 2.0).min(1e3));
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{} (hollow: error < 0)", panel.title),
            ("sans-serif", 20),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)),
            (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
        )?;
    chart
        .configure_mesh()
        .x_desc("dt")
        .y_desc("relative error")
        .x_label_formatter(&|x| format!("{x}"))
        .y_label_formatter(&|y| format!("{y}"))
        .draw()?;
    // Second-order guide through 10 % at the geometric middle of the dt range.
    let mid = (x0 * x1).sqrt();
    let guide = |dt: f64| 0.1 * (dt / mid).powi(2);
    chart
        .draw_series(LineSeries::new(
            [x0, x1].map(|dt| (dt, guide(dt).clamp(y0, y1))),
            BLACK.mix(0.4).stroke_width(1),
        ))?
        .label("dt^2 guide")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK.mix(0.4)));
    for t in THRESHOLDS.iter().filter(|&&t| t > y0 && t < y1) {
        chart.draw_series(LineSeries::new(
            [(x0, *t), (x1, *t)],
            BLACK.mix(0.2).stroke_width(1),
        ))?;
    }
    for (k, (name, pts)) in series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let at = |&(dt, e, _): &ErrorPoint| (dt, e.abs());
        chart
            .draw_series(LineSeries::new(pts.iter().map(at), colour.stroke_width(2)))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], colour));
        chart.draw_series(pts.iter().filter_map(|&(dt, e, s)| {
            let s = s.filter(|s| s.is_finite())?;
            let (low, high) = ((e.abs() - s).max(y0), (e.abs() + s).min(y1));
            Some(PathElement::new(
                [(dt, low), (dt, high)],
                colour.stroke_width(1),
            ))
        }))?;
        chart.draw_series(pts.iter().map(|p| {
            let style = match p.1 > 0.0 {
                true => colour.filled(),
                false => WHITE.filled(),
            };
            Circle::new(at(p), 4, style)
        }))?;
        chart.draw_series(
            pts.iter()
                .filter(|p| p.1 < 0.0)
                .map(|p| Circle::new(at(p), 4, colour.stroke_width(2))),
        )?;
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    Ok(())
}

/// The legend box of `chart` at `position`.
fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Result<(), Error>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: plotters::coord::CoordTranslate,
{
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(position)
        .draw()?;
    Ok(())
}

/// g(r) of `scheme`, averaged over seeds, one curve per dt; false when no point has an RDF.
fn rdf(results: &SweepResults, scheme: &str, path: &Path) -> Result<bool, Error> {
    let curves: Vec<(f64, Vec<(f64, f64)>)> = results
        .rows
        .iter()
        .filter(|r| r.scheme == scheme)
        .filter_map(|r| {
            let runs: Vec<&RunResult> = results
                .points
                .iter()
                .filter(|p| p.scheme == scheme && (p.dt - r.dt).abs() <= 1e-9 * r.dt)
                .collect();
            Some((r.dt, mean_rdf(&runs)?))
        })
        .collect();
    if curves.is_empty() {
        return Ok(false);
    }
    let labelled: Vec<(String, Vec<(f64, f64)>)> = curves
        .into_iter()
        .map(|(dt, g)| (format!("dt = {dt:.4}"), g))
        .collect();
    rdf_plot(&labelled, &format!("g(r), {scheme}"), path)?;
    Ok(true)
}

/// Curves g(r), each with its legend label, coloured from blue (first) to red (last).
pub fn rdf_plot(
    curves: &[(String, Vec<(f64, f64)>)],
    title: &str,
    path: &Path,
) -> Result<(), Error> {
    let r_max = curves
        .iter()
        .flat_map(|c| c.1.last())
        .map(|p| p.0)
        .fold(1.0f64, f64::max);
    let g_max = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.1))
        .fold(1.5f64, f64::max);
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..r_max, 0.0..g_max * 1.05)?;
    chart.configure_mesh().x_desc("r").y_desc("g(r)").draw()?;
    let n = curves.len().max(2) as f64 - 1.0;
    for (k, (label, g)) in curves.iter().enumerate() {
        // From blue (first) to red (last).
        let t = k as f64 / n;
        let colour = RGBColor((255.0 * t) as u8, 60, (255.0 * (1.0 - t)) as u8);
        chart
            .draw_series(LineSeries::new(g.iter().copied(), colour.stroke_width(2)))?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], colour));
    }
    legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    root.present()?;
    Ok(())
}

/// Bin-wise mean of the runs' RDFs (those that have one with the same bins).
pub fn mean_rdf(runs: &[&RunResult]) -> Option<Vec<(f64, f64)>> {
    let rdfs: Vec<&Vec<[f64; 2]>> = runs.iter().filter_map(|r| r.rdf.as_ref()).collect();
    let first = rdfs.first()?;
    let same: Vec<_> = rdfs.iter().filter(|g| g.len() == first.len()).collect();
    let n = same.len() as f64;
    Some(
        (0..first.len())
            .map(|b| (first[b][0], same.iter().map(|g| g[b][1]).sum::<f64>() / n))
            .collect(),
    )
}

/// A profile quantity: panel title and value of a row.
type ProfileColumn = fn(&ProfileRow) -> f64;

const PROFILE_PANELS: [(&str, ProfileColumn); 3] = [
    ("velocity u_x", |r| r.velocity[0]),
    ("number density", |r| r.density),
    ("temperature k_B T", |r| r.temperature),
];

/// Three panels (x-velocity, density, temperature) of a slab profile across `axis`.
pub fn profile_plot(rows: &[ProfileRow], axis: usize, path: &Path) -> Result<(), Error> {
    let root = SVGBackend::new(path, (900, 1000)).into_drawing_area();
    root.fill(&WHITE)?;
    let length = rows
        .last()
        .map_or(1.0, |r| r.position * 2.0 - rows[0].position);
    let axis_name = ["x", "y", "z"][axis.min(2)];
    for (area, (title, f)) in root.split_evenly((3, 1)).iter().zip(PROFILE_PANELS) {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .map(|r| (r.position, f(r)))
            .filter(|p| p.1.is_finite())
            .collect();
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            });
        let pad = 0.05 * (hi - lo).max(1e-9);
        let (y0, y1) = if lo <= hi {
            (lo - pad, hi + pad)
        } else {
            (0.0, 1.0)
        };
        let mut chart = ChartBuilder::on(area)
            .caption(title, ("sans-serif", 20))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..length, y0..y1)?;
        chart.configure_mesh().x_desc(axis_name).draw()?;
        let colour = COLOURS[0];
        chart.draw_series(LineSeries::new(pts.iter().copied(), colour.stroke_width(2)))?;
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_label_the_range_of_the_data() {
        // The main job's dt axis: 0.02 / 1.1 to 0.2 x 1.1.
        assert_eq!(
            log_ticks(0.0182, 0.22),
            vec![0.02, 0.03, 0.05, 0.07, 0.1, 0.15, 0.2]
        );
        assert_eq!(log_ticks(0.001, 1.0).len(), 10);
    }

    /// The like-neighbour panel's bar is that of the species whose fraction errs most.
    #[test]
    fn the_like_neighbour_bar_is_the_worst_species_one() {
        let map = |a: f64, b: f64| Some(BTreeMap::from([("A".into(), a), ("B".into(), b)]));
        let row = |f, s| Aggregate {
            like_neighbours: f,
            like_neighbours_stderr: s,
            ..Aggregate::of(&[], 1.0)
        };
        let baseline = row(map(0.5, 0.8), map(0.003, 0.004));
        // A errs +2 %, B -5 %: B's bar, hypot(0.03, 0.004) / 0.8.
        let r = row(map(0.51, 0.76), map(0.01, 0.03));
        let context = Context {
            kbt: 1.0,
            baseline: Some(&baseline),
        };
        let s = (MEASURED_PANELS[1].stderr)(&r, &context).unwrap();
        assert!((s - 0.03f64.hypot(0.004) / 0.8).abs() < 1e-15, "{s}");
        assert_eq!(
            (MEASURED_PANELS[1].stderr)(
                &baseline,
                &Context {
                    kbt: 1.0,
                    baseline: None
                }
            ),
            None
        );
    }

    #[test]
    fn an_error_against_the_baseline_adds_both_standard_errors() {
        let s = against_baseline(Some(2.0), Some(0.3), Some(-4.0), Some(0.4)).unwrap();
        assert!((s - 0.125).abs() < 1e-15);
        assert_eq!(
            against_baseline(Some(2.0), None, Some(4.0), Some(0.4)),
            None
        );
        assert_eq!(
            against_baseline(Some(2.0), Some(0.3), Some(4.0), None),
            Some(0.075)
        );
    }
}
