//! Terminal tables and CSV of sweep rows and scheme summaries.

use super::aggregate::{Aggregate, CRITICAL_OBSERVABLES};
use super::critical::Critical;
use super::sweep::SchemeSummary;

type Cell<T> = fn(&T) -> Option<f64>;

/// The numeric columns of a sweep row: header, value, decimals shown in tables
/// (percentages are relative errors times 100).
const ROW_COLUMNS: [(&str, Cell<Aggregate>, usize); 14] = [
    ("dt", |r| Some(r.dt), 4),
    ("T_K", |r| r.kinetic_temperature, 4),
    ("T_K err %", |r| percent(r.kinetic_temperature_error), 2),
    ("T_C", |r| r.configurational_temperature, 4),
    ("+-", |r| r.configurational_temperature_stderr, 4),
    (
        "T_C err %",
        |r| percent(r.configurational_temperature_error),
        2,
    ),
    ("U", |r| r.potential_energy, 4),
    ("U err %", |r| percent(r.potential_energy_error), 2),
    ("P", |r| r.pressure, 3),
    ("P err %", |r| percent(r.pressure_error), 2),
    ("eta", |r| r.shear_viscosity(), 4),
    ("eta +-", |r| r.viscosity?.shear_viscosity_error, 4),
    (
        "eta err %",
        |r| percent(r.shear_viscosity_relative_error),
        2,
    ),
    ("ms/step", |r| r.ms_per_step, 4),
];

/// Columns shown only where some row has a value: the observables of chains and mixtures.
const MEASURED_COLUMNS: [(&str, Cell<Aggregate>, usize); 3] = [
    ("bond", |r| r.bond_length, 4),
    ("bond err %", |r| percent(r.bond_length_error), 2),
    ("like err %", |r| percent(r.like_neighbours_error), 2),
];

/// The columns of `rows`: every one of [`ROW_COLUMNS`], those of [`MEASURED_COLUMNS`] that
/// some row has.
fn columns(rows: &[Aggregate]) -> Vec<&'static (&'static str, Cell<Aggregate>, usize)> {
    let measured = MEASURED_COLUMNS
        .iter()
        .filter(|(_, f, _)| rows.iter().any(|r| f(r).is_some()));
    ROW_COLUMNS.iter().chain(measured).collect()
}

fn percent(x: Option<f64>) -> Option<f64> {
    x.map(|x| 100.0 * x)
}

fn number(x: Option<f64>, decimals: usize) -> String {
    x.map_or_else(|| "-".into(), |x| format!("{x:.decimals$}"))
}

/// Columns aligned right, first column left, separated by two spaces.
fn align(header: Vec<String>, body: Vec<Vec<String>>) -> String {
    let width: Vec<usize> = (0..header.len())
        .map(|c| {
            body.iter()
                .chain([&header])
                .map(|r| r[c].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |r: &Vec<String>| {
        let cells: Vec<String> = r
            .iter()
            .zip(&width)
            .enumerate()
            .map(|(c, (s, &w))| {
                if c == 0 {
                    format!("{s:<w$}")
                } else {
                    format!("{s:>w$}")
                }
            })
            .collect();
        cells.join("  ").trim_end().to_string() + "\n"
    };
    std::iter::once(&header).chain(&body).map(line).collect()
}

/// One line per (scheme, dt): observables, relative errors, cost and stability.
pub fn rows_table(rows: &[Aggregate]) -> String {
    let columns = columns(rows);
    let mut header = vec!["scheme".to_string()];
    header.extend(columns.iter().map(|c| c.0.to_string()));
    header.push("stable".into());
    let body = rows
        .iter()
        .map(|r| {
            let mut line = vec![r.scheme.clone()];
            line.extend(columns.iter().map(|(_, f, d)| number(f(r), *d)));
            line.push(format!("{}/{}", r.stable_runs, r.runs));
            line
        })
        .collect();
    align(header, body)
}

/// The rows as CSV (full precision, empty where nothing was measured), written by the `csv`
/// crate: a scheme string with commas or quotes is quoted as RFC 4180 requires.
pub fn rows_csv(rows: &[Aggregate]) -> String {
    let columns = columns(rows);
    let mut w = csv::Writer::from_writer(Vec::new());
    let header = std::iter::once("scheme")
        .chain(columns.iter().map(|(name, _, _)| *name))
        .chain(["stable_runs", "runs"]);
    // Writing to memory fails only on a bug; an empty CSV then shows it.
    let mut write = |record: Vec<String>| w.write_record(record).is_ok();
    let mut ok = write(header.map(String::from).collect());
    for r in rows {
        let cells = std::iter::once(r.scheme.clone())
            .chain(
                columns
                    .iter()
                    .map(|(_, f, _)| f(r).map_or_else(String::new, |x| x.to_string())),
            )
            .chain([r.stable_runs.to_string(), r.runs.to_string()]);
        ok &= write(cells.collect());
    }
    match (ok, w.into_inner()) {
        (true, Ok(bytes)) => String::from_utf8(bytes).unwrap_or_default(),
        _ => String::new(),
    }
}

fn critical(c: &Option<Critical>) -> String {
    c.map_or_else(|| "-".into(), |c| c.to_string())
}

/// One line per scheme: critical dt at 10 % and 1 % relative error of the sweep's observable,
/// stability, cost, efficiency.
pub fn summary_table(summary: &[SchemeSummary], reference: &str) -> String {
    let header = [
        "scheme",
        "dt_c 10 %",
        "dt_c 1 %",
        "stable to",
        "blow-up at",
        "ms/step",
        "forces/step",
        &format!("efficiency (vs {reference})"),
    ]
    .map(String::from)
    .to_vec();
    let body = summary
        .iter()
        .map(|s| {
            vec![
                s.scheme.clone(),
                critical(&s.critical_10),
                critical(&s.critical_1),
                number(s.stability_dt, 4),
                number(s.first_blow_up_dt, 4),
                number(s.ms_per_step, 4),
                number(s.force_evaluations_per_step, 2),
                number(s.efficiency, 2),
            ]
        })
        .collect();
    align(header, body)
}

/// One line per scheme: the critical dt at 10 % and 1 % relative error of every observable
/// the sweep measured ([`SchemeSummary::critical_steps`]), in compact form
/// ([`Critical::compact`]).
pub fn critical_table(summary: &[SchemeSummary]) -> String {
    let measured: Vec<_> = CRITICAL_OBSERVABLES
        .iter()
        .filter(|(name, _, _)| summary.iter().any(|s| s.critical_steps.contains_key(name)))
        .collect();
    let mut header = vec!["scheme".to_string()];
    for (_, label, _) in &measured {
        header.extend(["10 %", "1 %"].map(|t| format!("{label} {t}")));
    }
    let body = summary
        .iter()
        .map(|s| {
            let mut line = vec![s.scheme.clone()];
            for (name, _, _) in &measured {
                let c = s.critical_steps.get(name);
                line.push(critical_compact(c.and_then(|c| c.critical_10)));
                line.push(critical_compact(c.and_then(|c| c.critical_1)));
            }
            line
        })
        .collect();
    align(header, body)
}

fn critical_compact(c: Option<Critical>) -> String {
    c.map_or_else(|| "-".into(), Critical::compact)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_align_and_csv_keeps_empty_cells() {
        let t = align(
            vec!["a".into(), "bb".into()],
            vec![vec!["xyz".into(), "1".into()]],
        );
        assert_eq!(t, "a    bb\nxyz   1\n");
        assert_eq!(number(None, 2), "-");
        assert_eq!(number(Some(0.12345), 2), "0.12");
    }

    #[test]
    fn csv_quotes_scheme_strings_with_commas() {
        let row = Aggregate {
            scheme: "prk(b = [1/2, 1/2], bh = [1, 0])".into(),
            ..Aggregate::of(&[], 1.0)
        };
        let text = rows_csv(&[row]);
        let mut lines = text.lines();
        let header = lines.next().unwrap();
        assert!(header.starts_with("scheme,"), "{header}");
        let line = lines.next().unwrap();
        assert!(
            line.starts_with("\"prk(b = [1/2, 1/2], bh = [1, 0])\","),
            "{line}"
        );
        let cells = csv::Reader::from_reader(text.as_bytes())
            .records()
            .next()
            .unwrap()
            .unwrap();
        assert_eq!(&cells[0], "prk(b = [1/2, 1/2], bh = [1, 0])");
        assert_eq!(cells.len(), header.split(',').count());
    }
}
