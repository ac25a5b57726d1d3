//! Errors of the scheme language, each pointing into the source.

use std::fmt;
use std::ops::Range;

/// An error in a scheme, with the byte range of the source it is about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub message: String,
    /// Byte offsets into the scheme source.
    pub span: Range<usize>,
}

impl Diagnostic {
    pub fn new(message: impl Into<String>, span: Range<usize>) -> Self {
        Diagnostic {
            message: message.into(),
            span,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (bytes {}..{})",
            self.message, self.span.start, self.span.end
        )
    }
}

impl std::error::Error for Diagnostic {}

/// A 1-based character position of byte offset `at` in `src`, for messages.
pub fn position(src: &str, at: usize) -> usize {
    src.char_indices().take_while(|&(i, _)| i < at).count() + 1
}
