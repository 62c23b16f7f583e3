//! serde's type errors in the words of a scene file's reader: "expected u32"
//! names a Rust type, which says nothing to someone editing a TOML file, so
//! it becomes "expected a whole number (0 or more)".

/// Rust type names in serde messages, with what they mean in a scene file.
const TERMS: [(&str, &str); 12] = [
    ("u8", "a whole number (0 or more)"),
    ("u16", "a whole number (0 or more)"),
    ("u32", "a whole number (0 or more)"),
    ("u64", "a whole number (0 or more)"),
    ("usize", "a whole number (0 or more)"),
    ("i8", "a whole number"),
    ("i16", "a whole number"),
    ("i32", "a whole number"),
    ("i64", "a whole number"),
    ("f32", "a number"),
    ("f64", "a number"),
    ("a boolean", "true or false"),
];

/// `message` with serde's "expected <type>" rewritten in user terms; other
/// messages are returned unchanged.
pub fn in_user_terms(message: &str) -> String {
    let Some((head, expected)) = message.rsplit_once("expected ") else { return message.to_string() };
    match TERMS.iter().find(|(rust, _)| expected.trim_end() == *rust) {
        Some((_, words)) => format!("{head}expected {words}"),
        None => message.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rust_types_become_words() {
        assert_eq!(
            in_user_terms("invalid type: string \"four\", expected u32"),
            "invalid type: string \"four\", expected a whole number (0 or more)"
        );
        assert_eq!(
            in_user_terms("invalid type: string \"abc\", expected f32"),
            "invalid type: string \"abc\", expected a number"
        );
        assert_eq!(
            in_user_terms("invalid type: integer `1`, expected a boolean"),
            "invalid type: integer `1`, expected true or false"
        );
        // Anything else is left alone, including a type name inside other words.
        let other = "unknown variant `fast`, expected `racy` or `farthest`";
        assert_eq!(in_user_terms(other), other);
    }
}
