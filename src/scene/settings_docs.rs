//! The key reference of a technique's table, written from its declared keys
//! ([`super::settings_controls`]): one TOML line per key, set to its default
//! (the value in `S::default()`), with what it does and its range. `sweeplab
//! keys` prints it, and `tests/scenes/all-keys.toml` holds it (a test keeps
//! the file equal to it), so a key's doc and range are written only beside
//! its settings type.

use super::settings_controls::{or_list, Current, DeclaredSettings, Key, Kind};

/// The comment column of a key's line, as in the hand-written tables.
const COMMENT_COLUMN: usize = 29;

/// `[table]` and every declared key of `S`: `key = default  # doc; range`.
/// A key without a default (unset, empty text) is shown commented out.
pub fn documented_table<S: DeclaredSettings>() -> String {
    let defaults = S::default();
    let mut text = format!("[{}]\n", S::TABLE);
    for Key { key, doc, kind, value } in S::keys() {
        let comment = match range_text(&kind) {
            Some(range) => format!("{doc}; {range}"),
            None => doc.to_string(),
        };
        let line = match toml_value(&value(&defaults), &kind) {
            Some(v) => format!("{key} = {v}"),
            None => format!("# {key} = ..."),
        };
        let pad = COMMENT_COLUMN.saturating_sub(line.len()).max(1);
        text += &format!("{line}{:pad$}# {comment}\n", "");
    }
    text
}

/// The value as a TOML file writes it (a real key's whole value as `15.0`);
/// `None` where there is no default to show.
fn toml_value(current: &Current, kind: &Kind) -> Option<String> {
    match current {
        Current::Bool(b) => Some(b.to_string()),
        Current::Number(n) if matches!(kind, Kind::Real { .. }) && n.fract() == 0.0 => Some(format!("{n:.1}")),
        Current::Number(n) => Some(number_text(*n)),
        Current::Name(name) => Some(format!("{name:?}")),
        Current::Text(t) if t.is_empty() => None,
        Current::Text(t) => Some(t.clone()),
        Current::Unset => None,
    }
}

/// The shortest text that reads back as the value: an f32 key's value (held
/// as f64) as the f32, so 0.1 reads "0.1" and not "0.10000000149011612";
/// a whole value without a fraction.
fn number_text(n: f64) -> String {
    if n.fract() == 0.0 && n.abs() < 1e15 {
        return format!("{n:.0}");
    }
    let single = n as f32;
    if f64::from(single) == n {
        format!("{single:?}")
    } else {
        format!("{n:?}")
    }
}

/// What a key accepts, in words; `None` where the doc says it (toggles, text).
fn range_text(kind: &Kind) -> Option<String> {
    match kind {
        Kind::Toggle | Kind::Text => None,
        Kind::Whole { lo, hi } => Some(format!("{lo}..={hi}")),
        Kind::WholeOrAuto { lo, hi } => Some(format!("0 (auto) or {lo}..={hi}")),
        Kind::Real { lo, hi } if hi.is_finite() => Some(format!("{}..={}", number_text(*lo), number_text(*hi))),
        Kind::Real { lo, .. } if *lo == f64::MIN_POSITIVE => Some("> 0".into()),
        Kind::Real { lo, .. } => Some(format!(">= {}", number_text(*lo))),
        Kind::Choice(names) => Some(or_list(&names.iter().map(|n| format!("{n:?}")).collect::<Vec<_>>())),
        Kind::Numbers(numbers) => Some(or_list(numbers)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_as_their_value_and_f32_values_without_their_f64_tail() {
        assert_eq!(number_text(256.0), "256");
        assert_eq!(number_text(f64::from(0.1f32)), "0.1");
        assert_eq!(number_text(1e-6), "1e-6");
        // An f64 value reads back exactly; an f32 value held as f64, as the f32.
        for n in [0.25, 1e-6, 0.001, 256.0, 0.999_999] {
            assert_eq!(number_text(n).parse::<f64>().unwrap(), n);
        }
        for x in [0.1f32, 0.01, 0.05, 15.5] {
            assert_eq!(number_text(f64::from(x)).parse::<f32>().unwrap(), x);
        }
    }

    #[test]
    fn ranges_in_words() {
        assert_eq!(range_text(&Kind::Whole { lo: 1, hi: 32 }).unwrap(), "1..=32");
        assert_eq!(range_text(&Kind::Real { lo: 0.01, hi: 16.0 }).unwrap(), "0.01..=16");
        assert_eq!(range_text(&Kind::Real { lo: f64::MIN_POSITIVE, hi: f64::INFINITY }).unwrap(), "> 0");
        assert_eq!(range_text(&Kind::Numbers(&[1, 2, 4])).unwrap(), "1, 2 or 4");
        assert_eq!(range_text(&Kind::WholeOrAuto { lo: 16, hi: 4096 }).unwrap(), "0 (auto) or 16..=4096");
        assert_eq!(range_text(&Kind::Choice(vec!["a", "b"])).unwrap(), "\"a\" or \"b\"");
        assert_eq!(range_text(&Kind::Toggle), None);
    }
}
