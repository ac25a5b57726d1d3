//! Values as a paper prints them, read back with the uncertainty of their digits.

/// A printed value read back: the number with its standard uncertainty (half a unit of its
/// last printed digit), the interval a paper's reading puts the value in, or the paper's
/// statement that the scheme blew up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Printed {
    Number {
        value: f64,
        uncertainty: f64,
    },
    /// The value lies in [low, high), nothing more said (`[published_grid]` of an item).
    Interval {
        low: f64,
        high: f64,
    },
    BlowUp,
    Absent,
}

impl Printed {
    /// Read as the largest step of a grid with `factor` between steps below a threshold: the
    /// crossing lies between it and the next step, [p, factor p), widened by the printed
    /// digits (half a unit of the last one each way).
    pub fn as_grid_step_below(self, factor: f64) -> Printed {
        match self {
            Printed::Number { value, uncertainty } => Printed::Interval {
                low: value - uncertainty,
                high: factor * (value + uncertainty),
            },
            other => other,
        }
    }
}

/// Read a printed value: a decimal number, optionally with `%` (then divided by 100), `"-"`
/// (nothing printed) or `"blow-up"`.
pub fn parse_printed(text: &str) -> Result<Printed, String> {
    let t = text.trim();
    match t {
        "-" => return Ok(Printed::Absent),
        "blow-up" => return Ok(Printed::BlowUp),
        _ => {}
    }
    let (number, scale) = match t.strip_suffix('%') {
        Some(n) => (n.trim(), 0.01),
        None => (t, 1.0),
    };
    let value: f64 = number.parse().map_err(|_| {
        "not a printed number: valid are decimals like \"0.050\" or \"99.2%\", \"-\" or \
         \"blow-up\""
            .to_string()
    })?;
    let decimals = number.split_once('.').map_or(0, |(_, d)| d.len());
    Ok(Printed::Number {
        value: value * scale,
        uncertainty: 0.5 * 10f64.powi(-(decimals as i32)) * scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printed_values_keep_their_digits() {
        assert_eq!(
            parse_printed("0.050"),
            Ok(Printed::Number {
                value: 0.05,
                uncertainty: 0.0005
            })
        );
        let Ok(Printed::Number { value, uncertainty }) = parse_printed("99.2%") else {
            panic!()
        };
        assert!((value - 0.992).abs() < 1e-12 && (uncertainty - 0.0005).abs() < 1e-12);
        assert_eq!(parse_printed("-"), Ok(Printed::Absent));
        assert_eq!(parse_printed("blow-up"), Ok(Printed::BlowUp));
        assert!(parse_printed("1,5").is_err());
    }
}
