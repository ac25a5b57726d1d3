//! Published against measured, number by number, with a verdict.

use super::item::Item;
use super::measure::{Measured, Measurements, Value};
use super::printed::{parse_printed, Printed};
use serde::Serialize;

/// A measured number whose 95 % error bar is wider than this fraction of the published
/// value cannot tell agreement from a real difference: its verdict is "unresolved".
pub const RESOLUTION: f64 = 0.2;

/// The two-sided 95 % quantile of Student's t with `dof` degrees of freedom (`None`: the
/// normal 1.96): agreement is |measured - published| within this many combined standard
/// uncertainties (the measured standard error and half a unit of the published last digit,
/// in quadrature). Tabulated to 10, then 1.96 + 2.5 / dof (within 0.01 of the exact value).
pub fn t95(dof: Option<usize>) -> f64 {
    const TABLE: [f64; 10] = [12.71, 4.30, 3.18, 2.78, 2.57, 2.45, 2.36, 2.31, 2.26, 2.23];
    match dof {
        None => 1.96,
        Some(0) => f64::INFINITY,
        Some(d) if d <= 10 => TABLE[d - 1],
        Some(d) => 1.96 + 2.5 / d as f64,
    }
}

/// The verdict on one published number.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", rename_all = "snake_case")]
pub enum Verdict {
    /// Within [`t95`] combined uncertainties (`sigmas` of them apart), or both blow up.
    Agrees { sigmas: Option<f64> },
    /// Further apart, or only one of paper and run blows up.
    Differs { sigmas: Option<f64> },
    /// The measurement cannot decide, and why.
    Unresolved { reason: String },
    /// Published but not comparable (see the item's notes).
    NotCompared,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let apart = |s: &Option<f64>| s.map_or_else(String::new, |s| format!(" ({s:.1} sigma)"));
        match self {
            Verdict::Agrees { sigmas } => write!(f, "agrees{}", apart(sigmas)),
            Verdict::Differs { sigmas } => write!(f, "DIFFERS{}", apart(sigmas)),
            Verdict::Unresolved { reason } => write!(f, "unresolved: {reason}"),
            Verdict::NotCompared => write!(f, "not compared"),
        }
    }
}

/// One published number against its measurement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// The paper's name of the method.
    pub method: String,
    pub scheme: String,
    pub dt: Option<f64>,
    pub quantity: String,
    /// As printed.
    pub published: String,
    pub measured: Measured,
    #[serde(flatten)]
    pub verdict: Verdict,
}

/// Every published number of `item` against `m` (in the order of the rows); published
/// `"-"` cells are left out.
pub fn compare(item: &Item, m: &Measurements) -> Vec<Comparison> {
    let mut out = Vec::new();
    for row in &item.published {
        for (quantity, text) in &row.values {
            let Ok(mut printed) = parse_printed(text) else {
                continue;
            };
            let mut published = text.clone();
            let grid = item.published_grid.get(quantity);
            if let (Some(&factor), Printed::Number { value, .. }) = (grid, printed) {
                let next = factor * value;
                published = format!("{text} (next step {next:.*})", decimals(next));
                printed = printed.as_grid_step_below(factor);
            }
            if printed == Printed::Absent {
                continue;
            }
            let compared = !item.not_compared.contains(quantity);
            let measured = if compared {
                m.get(quantity, &row.scheme, row.dt)
            } else {
                Measured::Missing {
                    reason: "not compared".into(),
                }
            };
            let verdict = if compared {
                verdict(printed, &measured)
            } else {
                Verdict::NotCompared
            };
            out.push(Comparison {
                method: row.method.clone().unwrap_or_else(|| row.scheme.clone()),
                scheme: row.scheme.clone(),
                dt: row.dt,
                quantity: quantity.clone(),
                published,
                measured,
                verdict,
            });
        }
    }
    out
}

/// The verdict on `printed` given `measured`.
pub fn verdict(printed: Printed, measured: &Measured) -> Verdict {
    let unresolved = |reason: &str| Verdict::Unresolved {
        reason: reason.into(),
    };
    match (printed, measured) {
        (_, Measured::Missing { reason }) => unresolved(reason),
        (Printed::Absent, _) => unresolved("nothing published"),
        (Printed::BlowUp, Measured::BlowUp) => Verdict::Agrees { sigmas: None },
        (Printed::BlowUp, Measured::Value(_))
        | (Printed::Number { .. } | Printed::Interval { .. }, Measured::BlowUp) => {
            Verdict::Differs { sigmas: None }
        }
        (Printed::Number { value, uncertainty }, Measured::Value(v)) => {
            let distance = |m: f64, sigma: f64| (m - value).abs() / sigma.hypot(uncertainty);
            against(value, distance, *v)
        }
        (Printed::Interval { low, high }, Measured::Value(v)) => {
            let distance = |m: f64, sigma: f64| (low - m).max(m - high).max(0.0) / sigma;
            against(0.5 * (low + high), distance, *v)
        }
    }
}

/// The verdict on `m` against a published value near `published`, `distance(value, sigma)`
/// apart in combined standard uncertainties.
fn against(published: f64, distance: impl Fn(f64, f64) -> f64, m: Value) -> Verdict {
    let Some(sigma) = m.sigma else {
        return Verdict::Unresolved {
            reason: "no error bar (a single run)".into(),
        };
    };
    let t = t95(m.dof);
    if t * sigma > RESOLUTION * published.abs() {
        return Verdict::Unresolved {
            reason: format!(
                "95 % error bar {:.0} % of the published value",
                100.0 * t * sigma / published.abs()
            ),
        };
    }
    let sigmas = distance(m.value, sigma);
    if sigmas <= t {
        Verdict::Agrees {
            sigmas: Some(sigmas),
        }
    } else {
        Verdict::Differs {
            sigmas: Some(sigmas),
        }
    }
}

/// A measured value as text: 4 significant digits and its error.
pub fn measured_text(m: &Measured) -> String {
    match m {
        Measured::Value(Value { value, sigma, .. }) => {
            let digits = |x: f64| format!("{x:.*}", decimals(x));
            match sigma {
                Some(s) => format!("{} ± {}", digits(*value), digits(*s)),
                None => digits(*value),
            }
        }
        Measured::BlowUp => "blow-up".into(),
        Measured::Missing { .. } => "-".into(),
    }
}

/// Decimals that show 3 significant digits of `x` (at most 6).
fn decimals(x: f64) -> usize {
    if x == 0.0 || !x.is_finite() {
        return 4;
    }
    (2 - x.abs().log10().floor() as i64).clamp(0, 6) as usize
}

/// The comparisons as an aligned table.
pub fn table(rows: &[Comparison]) -> String {
    let header = [
        "method",
        "dt",
        "quantity",
        "published",
        "measured",
        "verdict",
    ];
    let body: Vec<[String; 6]> = rows
        .iter()
        .map(|c| {
            [
                c.method.clone(),
                c.dt.map_or_else(|| "-".into(), |dt| format!("{dt}")),
                c.quantity.clone(),
                c.published.clone(),
                measured_text(&c.measured),
                c.verdict.to_string(),
            ]
        })
        .collect();
    let width: Vec<usize> = (0..6)
        .map(|k| {
            body.iter()
                .map(|r| r[k].chars().count())
                .chain([header[k].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: Vec<&str>| {
        let padded: Vec<String> = cells
            .iter()
            .zip(&width)
            .map(|(c, &w)| format!("{c:<w$}"))
            .collect();
        padded.join("  ").trim_end().to_string() + "\n"
    };
    let mut out = line(header.to_vec());
    for r in &body {
        out += &line(r.iter().map(String::as_str).collect());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(value: f64, sigma: Option<f64>) -> Measured {
        Measured::Value(Value {
            value,
            sigma,
            dof: None,
        })
    }

    #[test]
    fn verdicts_follow_the_combined_uncertainty() {
        let p = parse_printed("0.050").unwrap();
        // 0.002 away with sigma 0.001 (and 0.0005 printed): 1.8 combined sigma, within the
        // normal 1.96, not with 2 runs (t = 12.7 there, and the bar is then too wide).
        assert!(matches!(
            verdict(p, &value(0.052, Some(0.001))),
            Verdict::Agrees { .. }
        ));
        assert!(matches!(
            verdict(p, &value(0.056, Some(0.001))),
            Verdict::Differs { .. }
        ));
        let two_runs = Measured::Value(Value {
            value: 0.052,
            sigma: Some(0.001),
            dof: Some(1),
        });
        assert!(matches!(verdict(p, &two_runs), Verdict::Unresolved { .. }));
        assert_eq!(t95(Some(4)), 2.78);
        assert!((t95(Some(30)) - 2.04).abs() < 0.01);
        // A 2-sigma bar of 40 % of the value cannot decide; a single run has no bar.
        assert!(matches!(
            verdict(p, &value(0.05, Some(0.01))),
            Verdict::Unresolved { .. }
        ));
        assert!(matches!(
            verdict(p, &value(0.05, None)),
            Verdict::Unresolved { .. }
        ));
        let blow_up = parse_printed("blow-up").unwrap();
        assert!(matches!(
            verdict(blow_up, &Measured::BlowUp),
            Verdict::Agrees { .. }
        ));
        assert!(matches!(
            verdict(blow_up, &value(1.0, Some(0.01))),
            Verdict::Differs { .. }
        ));
        assert!(matches!(
            verdict(p, &Measured::BlowUp),
            Verdict::Differs { .. }
        ));
    }

    /// 003 Table 1's ABOBA: published 0.116, measured 0.1214 +- 0.0003 with ten runs. Beyond
    /// the printed digits it differs; read as the largest step of the paper's 15 % grid below
    /// 10 % (the crossing in [0.1155, 0.1340)) it agrees, as 0.1313 at gamma = 40.5 does, and
    /// DPD-S1 at gamma = 450 (0.0511 against 0.044: [0.0435, 0.0512)) is inside too.
    #[test]
    fn a_grid_step_below_is_read_as_the_interval_to_the_next_step() {
        let ten_runs = |v: f64| {
            Measured::Value(Value {
                value: v,
                sigma: Some(0.0003),
                dof: Some(9),
            })
        };
        let p = parse_printed("0.116").unwrap();
        assert!(matches!(
            verdict(p, &ten_runs(0.1214)),
            Verdict::Differs { .. }
        ));
        let read = p.as_grid_step_below(1.15);
        let Printed::Interval { low, high } = read else {
            panic!("{read:?}")
        };
        assert!((low - 0.1155).abs() < 1e-12 && (high - 1.15 * 0.1165).abs() < 1e-12);
        for crossing in [0.1214, 0.1313] {
            assert_eq!(
                verdict(read, &ten_runs(crossing)),
                Verdict::Agrees { sigmas: Some(0.0) }
            );
        }
        // 0.0015 beyond the next step: 5 sigma, beyond t = 2.26; 0.0003 beyond: 1 sigma.
        let Verdict::Differs { sigmas: Some(s) } = verdict(read, &ten_runs(high + 0.0015)) else {
            panic!("0.0015 beyond the interval agrees")
        };
        assert!((s - 5.0).abs() < 1e-9);
        assert!(matches!(
            verdict(read, &ten_runs(low - 0.0003)),
            Verdict::Agrees { .. }
        ));
        assert!(matches!(
            verdict(read, &Measured::BlowUp),
            Verdict::Differs { .. }
        ));
        let s1 = parse_printed("0.044").unwrap().as_grid_step_below(1.15);
        assert!(matches!(
            verdict(s1, &ten_runs(0.0511)),
            Verdict::Agrees { .. }
        ));
        assert_eq!(
            parse_printed("blow-up").unwrap().as_grid_step_below(1.15),
            Printed::BlowUp
        );
    }
}
