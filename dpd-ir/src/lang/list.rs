//! Lists of schemes in one string, as command lines take them: `"vv, prk(b = [1/2, 1/2], bh =
//! [1, 0])"` is two schemes. A comma inside parentheses or brackets belongs to the scheme (the
//! coefficients of `prk(...)`, a letter's `(1/2, ...)`); a comma at the top level separates.

/// The schemes of `text`, split at its top-level commas and trimmed. An empty entry (two
/// commas in a row, a leading or trailing comma, or an empty text) is an error saying so.
pub fn split_schemes(text: &str) -> Result<Vec<String>, String> {
    let mut schemes = Vec::new();
    let (mut depth, mut start) = (0i64, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                schemes.push(text[start..i].trim().to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    schemes.push(text[start..].trim().to_string());
    if schemes.iter().any(String::is_empty) {
        return Err("empty scheme in the list (two commas in a row?)".into());
    }
    Ok(schemes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_split_at_top_level_commas_only() {
        let list = split_schemes(
            "vv, prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O,A(1/2) B A(1/2)",
        )
        .unwrap();
        assert_eq!(
            list,
            vec![
                "vv",
                "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O",
                "A(1/2) B A(1/2)"
            ]
        );
        for empty in ["vv,,aboba", "vv,", "", " , vv"] {
            assert!(split_schemes(empty).is_err(), "{empty:?}");
        }
    }
}
