//! Splits a scheme into tokens. White space separates nothing: `ABOBA` is five names.

use super::diagnostic::Diagnostic;
use std::ops::Range;

/// Longest number literal accepted, in bytes (keeps exact arithmetic cheap).
const MAX_NUMBER_LEN: usize = 400;
/// Longest name accepted, in bytes (keeps messages that quote a name short).
const MAX_NAME_LEN: usize = 64;

#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// A sub-flow or sub-scheme name: an uppercase letter followed by lowercase letters,
    /// digits and underscores (`A`, `Ob`, `S`, `Ham2`).
    Upper(String),
    /// A constant, parameter, function or keyword: a lowercase letter or `_` followed by
    /// lowercase letters, digits and underscores (`x1`, `sqrt`, `let`, `prk`).
    Lower(String),
    /// A number literal as written (`12`, `0.25`, `1e-3`).
    Number(String),
    /// One of `( ) [ ] { } , ; = + - * / ^ < >`.
    Punct(char),
    /// `..`, the range of a `param` declaration.
    DotDot,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    pub tok: Tok,
    pub span: Range<usize>,
}

const PUNCT: &str = "()[]{},;=+-*/^<>";

/// Tokens of `src`; unexpected characters are reported and skipped.
pub fn lex(src: &str) -> (Vec<Token>, Vec<Diagnostic>) {
    let mut tokens = Vec::new();
    let mut errors = Vec::new();
    let bytes = src.as_bytes();
    let mut chars = src.char_indices().peekable();
    while let Some((start, c)) = chars.next() {
        let word_end = |from: usize| {
            from + src[from..]
                .find(|ch: char| !(ch.is_ascii_lowercase() || ch.is_ascii_digit() || ch == '_'))
                .unwrap_or(src.len() - from)
        };
        let (tok, end) = if c.is_whitespace() {
            continue;
        } else if (c.is_ascii_alphabetic() || c == '_')
            && word_end(start + 1) - start > MAX_NAME_LEN
        {
            let end = word_end(start + 1);
            errors.push(Diagnostic::new(
                format!("name longer than {MAX_NAME_LEN} characters"),
                start..end,
            ));
            while chars.peek().is_some_and(|&(i, _)| i < end) {
                chars.next();
            }
            continue;
        } else if c.is_ascii_uppercase() {
            let end = word_end(start + 1);
            (Tok::Upper(src[start..end].to_string()), end)
        } else if c.is_ascii_lowercase() || c == '_' {
            let end = word_end(start + 1);
            (Tok::Lower(src[start..end].to_string()), end)
        } else if c.is_ascii_digit()
            || (c == '.' && bytes.get(start + 1).is_some_and(u8::is_ascii_digit))
        {
            let end = number_end(bytes, start);
            if end - start > MAX_NUMBER_LEN {
                errors.push(Diagnostic::new(
                    format!("number literal longer than {MAX_NUMBER_LEN} characters"),
                    start..end,
                ));
            }
            (Tok::Number(src[start..end].to_string()), end)
        } else if src[start..].starts_with("..") {
            (Tok::DotDot, start + 2)
        } else if PUNCT.contains(c) {
            (Tok::Punct(c), start + 1)
        } else {
            errors.push(Diagnostic::new(
                format!("unexpected character '{c}'"),
                start..start + c.len_utf8(),
            ));
            continue;
        };
        while chars.peek().is_some_and(|&(i, _)| i < end) {
            chars.next();
        }
        tokens.push(Token {
            tok,
            span: start..end,
        });
    }
    (tokens, errors)
}

/// End of the number literal starting at `start`: digits, an optional fraction, and an
/// optional exponent `e`/`E` with optional sign, taken only when digits follow it.
fn number_end(bytes: &[u8], start: usize) -> usize {
    let digits = |mut i: usize| {
        while bytes.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i
    };
    let mut end = digits(start);
    if bytes.get(end) == Some(&b'.') && bytes.get(end + 1) != Some(&b'.') {
        end = digits(end + 1);
    }
    if matches!(bytes.get(end), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(bytes.get(end + 1), Some(b'+' | b'-')));
        if bytes.get(end + 1 + sign).is_some_and(u8::is_ascii_digit) {
            end = digits(end + 1 + sign);
        }
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(src: &str) -> Vec<Tok> {
        lex(src).0.into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn letters_split_at_uppercase() {
        let up = |s: &str| Tok::Upper(s.to_string());
        assert_eq!(toks("ObBAB"), vec![up("Ob"), up("B"), up("A"), up("B")]);
        assert_eq!(toks("A B\nO"), vec![up("A"), up("B"), up("O")]);
    }

    #[test]
    fn numbers_and_implicit_products() {
        assert_eq!(
            toks("1-2x1"),
            vec![
                Tok::Number("1".into()),
                Tok::Punct('-'),
                Tok::Number("2".into()),
                Tok::Lower("x1".into())
            ]
        );
        assert_eq!(toks("1.5e-3"), vec![Tok::Number("1.5e-3".into())]);
        assert_eq!(
            toks("2e"),
            vec![Tok::Number("2".into()), Tok::Lower("e".into())]
        );
    }

    #[test]
    fn ranges_split_numbers() {
        let n = |s: &str| Tok::Number(s.to_string());
        assert_eq!(toks("0..1"), vec![n("0"), Tok::DotDot, n("1")]);
        assert_eq!(toks("0.5..2."), vec![n("0.5"), Tok::DotDot, n("2.")]);
    }

    #[test]
    fn long_names_are_refused_without_a_token() {
        let (tokens, errors) = lex(&format!("A{} B", "b".repeat(100)));
        assert_eq!(
            tokens,
            vec![Token {
                tok: Tok::Upper("B".into()),
                span: 102..103
            }]
        );
        assert_eq!(
            errors,
            vec![Diagnostic::new("name longer than 64 characters", 0..101)]
        );
    }

    #[test]
    fn unexpected_characters_are_reported_with_spans() {
        let (tokens, errors) = lex("Aé!B");
        assert_eq!(tokens.len(), 2);
        assert_eq!(errors.len(), 2);
        assert_eq!(errors[0].span, 1..3);
        assert_eq!(errors[1].span, 3..4);
    }
}
