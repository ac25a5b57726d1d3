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

/// Characters of context shown on each side of a marked range, and the longest range
/// underlined in full, so that an excerpt stays one short line whatever the input.
const CONTEXT: usize = 30;
const LONGEST_MARK: usize = 40;

impl Diagnostic {
    pub fn new(message: impl Into<String>, span: Range<usize>) -> Self {
        Diagnostic {
            message: message.into(),
            span,
        }
    }

    /// The message followed by the line of `src` holding the span, with carets under the span:
    /// `"unexpected character '?'\n  AB?\n    ^"`. The line is cut to a few dozen characters
    /// around the span (`...` marks a cut) and control characters are shown escaped. No excerpt
    /// when the span covers the whole scheme or does not fall on character boundaries of `src`.
    pub fn render(&self, src: &str) -> String {
        format!("{}{}", escape(&self.message), excerpt(src, &self.span))
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (bytes {}..{})",
            escape(&self.message),
            self.span.start,
            self.span.end
        )
    }
}

impl std::error::Error for Diagnostic {}

/// A 1-based character position of byte offset `at` in `src`, for messages.
pub fn position(src: &str, at: usize) -> usize {
    src.char_indices().take_while(|&(i, _)| i < at).count() + 1
}

/// `text` with control characters escaped (`\u{7}`, `\n`), tabs shown as blanks: safe to print
/// on one line of a terminal or a header.
pub fn escape(text: &str) -> String {
    text.chars().map(shown).collect()
}

fn shown(c: char) -> String {
    match c {
        '\t' => " ".to_string(),
        c if c.is_control() => c.escape_default().to_string(),
        c => c.to_string(),
    }
}

/// "\n  line\n  ^^^" for `range` of `src`; empty for the whole scheme or a bad range.
fn excerpt(src: &str, range: &Range<usize>) -> String {
    if src.trim().is_empty() || (range.start == 0 && range.end >= src.len()) {
        return String::new();
    }
    marked_line(src, range).unwrap_or_default()
}

/// `None` if `range` is not on character boundaries of `src`.
fn marked_line(src: &str, range: &Range<usize>) -> Option<String> {
    let start = range.start;
    let line_start = src.get(..start)?.rfind('\n').map_or(0, |i| i + 1);
    let line_end = src
        .get(start..)?
        .find('\n')
        .map_or(src.len(), |i| start + i);
    let end = range.end.clamp(start, line_end);
    let before: Vec<char> = src.get(line_start..start)?.chars().collect();
    let marked: Vec<char> = src.get(start..end)?.chars().collect();
    let after: Vec<char> = src.get(end..line_end)?.chars().collect();
    let cut_before = before.len() > CONTEXT;
    let before = &before[before.len().saturating_sub(CONTEXT)..];
    let cut_mark = marked.len() > LONGEST_MARK;
    let marked = &marked[..marked.len().min(LONGEST_MARK)];
    let cut_after = cut_mark || after.len() > CONTEXT;
    let after = if cut_mark {
        &[][..]
    } else {
        &after[..after.len().min(CONTEXT)]
    };
    let text = |chars: &[char]| chars.iter().map(|&c| shown(c)).collect::<String>();
    let (lead, trail) = (
        if cut_before { "..." } else { "" },
        if cut_after { "..." } else { "" },
    );
    let (before, marked) = (format!("{lead}{}", text(before)), text(marked));
    Some(format!(
        "\n  {before}{marked}{}{trail}\n  {}{}",
        text(after),
        " ".repeat(before.chars().count()),
        "^".repeat(marked.chars().count().max(1))
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn excerpt_of(src: &str, range: Range<usize>) -> String {
        excerpt(src, &range)
    }

    #[test]
    fn excerpt_marks_the_range_on_its_line() {
        assert_eq!(excerpt_of("ABQ", 2..3), "\n  ABQ\n    ^");
        assert_eq!(
            excerpt_of("let x = 1;\nA(y) B", 13..14),
            "\n  A(y) B\n    ^"
        );
        assert_eq!(excerpt_of("AB(1/0", 6..6), "\n  AB(1/0\n        ^");
    }

    #[test]
    fn no_excerpt_for_the_whole_scheme_or_a_bad_range() {
        assert_eq!(excerpt_of("BOB", 0..3), "");
        assert_eq!(excerpt_of("  ", 0..0), "");
        assert_eq!(excerpt_of("A\u{e9}B", 2..3), "");
        assert_eq!(excerpt_of("AB", 5..6), "");
    }

    #[test]
    fn long_lines_are_cut_around_the_range() {
        let src = format!("{}Q{}", "A".repeat(100_000), "B".repeat(100_000));
        let e = excerpt_of(&src, 100_000..100_001);
        let want = format!(
            "\n  ...{}Q{}...\n  {}^",
            "A".repeat(CONTEXT),
            "B".repeat(CONTEXT),
            " ".repeat(CONTEXT + 3)
        );
        assert_eq!(e, want);
        let long = excerpt_of(&format!("A({})", "1".repeat(500)), 2..502);
        assert_eq!(long.lines().nth(2).unwrap().trim().len(), LONGEST_MARK);
    }

    #[test]
    fn control_characters_are_escaped() {
        let e = excerpt_of("A\u{1b}[31mB\u{7}", 1..2);
        assert_eq!(e, "\n  A\\u{1b}[31mB\\u{7}\n   ^^^^^^");
        assert_eq!(escape("a\nb\tc"), "a\\nb c");
    }
}
