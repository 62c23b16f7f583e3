//! Parsing of header field values shared by the text-header formats (MetaImage,
//! NRRD, our raw header): number lists, booleans, and line splitting.

use std::str::FromStr;

use super::error::FormatProblem;

/// Exactly `N` whitespace-separated values of `T`; `expected` describes them.
pub fn parse_array<T: FromStr + Copy + Default, const N: usize>(
    field: &str,
    value: &str,
    expected: &str,
) -> Result<[T; N], FormatProblem> {
    let mut out = [T::default(); N];
    let mut tokens = value.split_ascii_whitespace();
    for slot in out.iter_mut() {
        *slot = tokens
            .next()
            .and_then(|t| t.parse().ok())
            .ok_or_else(|| FormatProblem::bad_field(field, value, expected))?;
    }
    if tokens.next().is_some() {
        return Err(FormatProblem::bad_field(field, value, expected));
    }
    Ok(out)
}

pub fn parse_one<T: FromStr>(field: &str, value: &str, expected: &str) -> Result<T, FormatProblem> {
    value.trim().parse().map_err(|_| FormatProblem::bad_field(field, value, expected))
}

/// `True`/`False` (any case) or `1`/`0`.
pub fn parse_bool(field: &str, value: &str) -> Result<bool, FormatProblem> {
    match value.trim().to_ascii_lowercase().as_str() {
        "true" | "1" => Ok(true),
        "false" | "0" => Ok(false),
        _ => Err(FormatProblem::bad_field(field, value, "True or False")),
    }
}

/// One header line: its 1-based number, its text (without `\n` or `\r\n`), and the
/// byte offset just past its end, where binary data may begin.
pub struct Line<'a> {
    pub number: usize,
    pub text: &'a str,
    pub end: usize,
}

/// Iterates text lines from the start of `bytes` until a line that is not UTF-8,
/// which is reported as an error (binary data where a header line was expected).
pub struct Lines<'a> {
    bytes: &'a [u8],
    position: usize,
    number: usize,
}

pub fn lines(bytes: &[u8]) -> Lines<'_> {
    Lines { bytes, position: 0, number: 0 }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Result<Line<'a>, FormatProblem>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.position >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.position..];
        let (raw, end) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], self.position + i + 1),
            None => (rest, self.bytes.len()),
        };
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        self.position = end;
        self.number += 1;
        let number = self.number;
        Some(match std::str::from_utf8(raw) {
            Ok(text) => Ok(Line { number, text, end }),
            Err(_) => {
                self.position = self.bytes.len();
                Err(FormatProblem::syntax(format!("header line {number} is not text")))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_need_exactly_n_values() {
        let dims: [i64; 3] = parse_array("DimSize", " 1 2\t3 ", "3 integers").unwrap();
        assert_eq!(dims, [1, 2, 3]);
        assert!(parse_array::<i64, 3>("DimSize", "1 2", "3 integers").is_err());
        assert!(parse_array::<i64, 3>("DimSize", "1 2 3 4", "3 integers").is_err());
        assert!(parse_array::<f64, 3>("Spacing", "1 a 3", "3 numbers").is_err());
    }

    #[test]
    fn lines_report_offsets_and_strip_carriage_returns() {
        let bytes = b"a = 1\r\nb = 2\n\xff\xfe";
        let mut it = lines(bytes);
        let first = it.next().unwrap().unwrap();
        assert_eq!((first.number, first.text, first.end), (1, "a = 1", 7));
        let second = it.next().unwrap().unwrap();
        assert_eq!((second.text, second.end), ("b = 2", 13));
        assert!(it.next().unwrap().is_err());
        assert!(it.next().is_none());
    }
}
