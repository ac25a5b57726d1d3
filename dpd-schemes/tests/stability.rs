//! The reduced stability matrix: every registered scheme at the corners of the matrix
//! and at the standard point. Nothing may panic or report a non-finite value, in memory or in
//! the JSON it writes.
use dpd_schemes::registry::entries;
use dpd_schemes::stability::{run, Matrix, Outcome};
use serde_json::Value;

#[test]
fn reduced_matrix_completes_or_reports_for_every_scheme() {
    let matrix = Matrix::reduced();
    let schemes: Vec<_> = entries().iter().collect();
    let records = run(&matrix, &schemes).unwrap();
    assert_eq!(records.len(), schemes.len() * matrix.cases().len());
    let (mut completed, mut blow_ups, mut insane) = (0, 0, 0);
    for r in &records {
        match &r.outcome {
            Outcome::Completed {
                kinetic_temperature,
                configurational_temperature,
                kinetic_error,
                configurational_error,
            } => {
                completed += 1;
                for x in [
                    kinetic_temperature,
                    configurational_temperature,
                    kinetic_error,
                    configurational_error,
                ] {
                    assert!(x.is_finite(), "{r:?}");
                }
            }
            Outcome::BlowUp { step, reason } => {
                blow_ups += 1;
                assert!(*step < matrix.steps && !reason.is_empty(), "{r:?}");
            }
            Outcome::Insane {
                kinetic_temperature,
                configurational_temperature,
                reason,
            } => {
                insane += 1;
                for t in [kinetic_temperature, configurational_temperature]
                    .into_iter()
                    .flatten()
                {
                    assert!(t.is_finite(), "{r:?}");
                }
                assert!(!reason.is_empty());
            }
        }
        // The standard point must complete for every scheme.
        if r.gamma == 4.5 && r.mass == 1.0 && r.dt == 1e-2 {
            assert!(matches!(r.outcome, Outcome::Completed { .. }), "{r:?}");
        }
    }
    println!("completed {completed}, blow-ups {blow_ups}, insane {insane}");
    // serde_json writes a non-finite f64 as `null`, so the written records are checked too:
    // a null may stand only for a temperature an insane run reports as non-finite, and every
    // reason must say something.
    let json = serde_json::to_value(&records).unwrap();
    // The walk finds what a wrong implementation would write: a NaN error (null) and an empty
    // reason, each with the record it is in.
    let mut planted = Vec::new();
    nulls_and_empty_strings(
        &serde_json::json!([{"outcome": {"kinetic_error": f64::NAN}}, {"reason": ""}]),
        String::new(),
        &mut planted,
    );
    assert_eq!(
        planted,
        [
            ("/0/outcome/kinetic_error".to_string(), 0),
            ("/1/reason".to_string(), 1)
        ]
    );
    let mut found = Vec::new();
    nulls_and_empty_strings(&json, String::new(), &mut found);
    let allowed = |path: &str| {
        path.ends_with("/kinetic_temperature") || path.ends_with("/configurational_temperature")
    };
    for (path, record) in &found {
        let status = &json[record]["outcome"]["status"];
        assert!(
            allowed(path) && status == "insane",
            "{path} is null or empty in {}",
            json[record]
        );
    }
}

/// Every `null` and empty string in `value`, as (JSON pointer, index of the top-level record).
fn nulls_and_empty_strings(value: &Value, path: String, found: &mut Vec<(String, usize)>) {
    let record = || {
        path.split('/')
            .nth(1)
            .and_then(|i| i.parse().ok())
            .unwrap_or(0)
    };
    match value {
        Value::Null => found.push((path.clone(), record())),
        Value::String(s) if s.is_empty() => found.push((path.clone(), record())),
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                nulls_and_empty_strings(v, format!("{path}/{i}"), found);
            }
        }
        Value::Object(fields) => {
            for (k, v) in fields {
                nulls_and_empty_strings(v, format!("{path}/{k}"), found);
            }
        }
        _ => {}
    }
}
