//! Typed errors of the core: invalid input, detected blow-ups and unreadable checkpoints.

use thiserror::Error;

/// An input value that is not allowed. Names the field, the value and what would be valid.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("invalid {field} = {value}: {allowed}")]
pub struct ParamError {
    /// The parameter, e.g. `gamma` or `a[0][1]` or `mass[17]`.
    pub field: String,
    /// The offending value as given.
    pub value: String,
    /// What would be valid.
    pub allowed: String,
}

impl ParamError {
    /// The error for `field`, with `value` as [`shown`] prints it.
    pub fn new(field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) -> Self {
        ParamError {
            field: field.into(),
            value: shown(&value.to_string()),
            allowed: allowed.into(),
        }
    }
}

/// Longest value a [`ParamError`] prints, in characters.
const LONGEST_VALUE: usize = 80;

/// `value` as printed in a message: a number written with more than 20 characters in
/// scientific notation (`1e300`, not 301 digits), control characters escaped, and a text
/// longer than 80 characters cut, with `...`.
pub fn shown(value: &str) -> String {
    let value = match value.parse::<f64>() {
        Ok(x) if value.len() > 20 && x.is_finite() => format!("{x:e}"),
        _ => value.to_string(),
    };
    let escaped: String = value
        .chars()
        .map(|c| match c {
            c if c.is_control() => c.escape_default().to_string(),
            c => c.to_string(),
        })
        .collect();
    match escaped.char_indices().nth(LONGEST_VALUE - 3) {
        Some((cut, _)) if escaped.chars().count() > LONGEST_VALUE => {
            format!("{}...", &escaped[..cut])
        }
        _ => escaped,
    }
}

/// Require `value` to be finite and `> 0`.
pub(crate) fn positive(field: &str, value: f64) -> Result<f64, ParamError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ParamError::new(field, value, "must be finite and > 0"))
    }
}

/// Require `value` to be finite and `>= 0`.
pub(crate) fn non_negative(field: &str, value: f64) -> Result<f64, ParamError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ParamError::new(field, value, "must be finite and >= 0"))
    }
}

/// Require every component of every vector in `values` to be finite; the error names
/// `field[i]`.
pub(crate) fn finite_vectors(field: &str, values: &[crate::Vec3]) -> Result<(), ParamError> {
    match values.iter().position(|x| !x.iter().all(|v| v.is_finite())) {
        None => Ok(()),
        Some(i) => Err(ParamError::new(
            format!("{field}[{i}]"),
            format!("{:?}", values[i]),
            "must be finite",
        )),
    }
}

/// A step that produced a non-finite value or moved a particle too far. The system was left
/// in the state before the failing step.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("blow-up at step {step} of scheme {scheme}: {reason}")]
pub struct BlowUp {
    /// Number of the step that failed (steps count from 0).
    pub step: u64,
    pub scheme: String,
    pub reason: String,
}

/// Why [`crate::System::advance`] stopped.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AdvanceError {
    /// The scheme cannot run on the system (it names a force group the system lacks, or
    /// leaves out one it has); no step was taken.
    #[error(transparent)]
    Scheme(#[from] ParamError),
    /// A step blew up and was undone.
    #[error(transparent)]
    BlowUp(#[from] BlowUp),
}

/// A checkpoint that cannot be written or read back.
#[derive(Debug, Error)]
pub enum CheckpointError {
    #[error("checkpoint {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("checkpoint {path} is not a dpd checkpoint (bad magic bytes)")]
    NotACheckpoint { path: String },
    #[error("checkpoint {path} has format version {found}; this build reads versions {oldest} to {newest}")]
    Version {
        path: String,
        found: u32,
        oldest: u32,
        newest: u32,
    },
    #[error("checkpoint {path} is truncated: header announces {expected} bytes of data, file holds {found}")]
    Truncated {
        path: String,
        expected: u64,
        found: u64,
    },
    #[error("checkpoint {path} is corrupt: checksum mismatch")]
    Corrupt { path: String },
    #[error("checkpoint {path} cannot be decoded: {message}")]
    Decode { path: String, message: String },
    #[error("checkpoint {path} holds invalid data: {source}")]
    Invalid {
        path: String,
        #[source]
        source: ParamError,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_shown_compactly() {
        assert_eq!(ParamError::new("dt", 1e300, "x").value, "1e300");
        assert_eq!(ParamError::new("dt", 1e-300, "x").value, "1e-300");
        assert_eq!(ParamError::new("dt", 0.05, "x").value, "0.05");
        assert_eq!(ParamError::new("n", 500, "x").value, "500");
        assert_eq!(shown("A\u{1b}B"), "A\\u{1b}B");
        let long = shown(&"A".repeat(1000));
        assert_eq!((long.len(), &long[77..]), (80, "..."));
    }
}
