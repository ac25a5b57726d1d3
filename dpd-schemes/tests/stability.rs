//! The reduced stability matrix: every registered scheme at the corners of the matrix
//! and at the standard point. Nothing may panic or report NaN.
use dpd_schemes::registry::entries;
use dpd_schemes::stability::{run, Matrix, Outcome};

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
    let json = serde_json::to_string(&records).unwrap();
    assert!(!json.contains("NaN") && !json.contains("null,\"reason\":\"\""));
}
