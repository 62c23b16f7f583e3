//! Base64 decoding (RFC 4648, standard alphabet) for VTK XML binary data.
//!
//! VTK writes a block header and the data as separately padded base64 runs, one
//! after the other, so padding may appear at any 4-character boundary; each
//! quantum is decoded on its own. Whitespace is skipped.

use super::error::FormatProblem;

fn sextet(c: u8) -> Option<u8> {
    match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    }
}

/// Decodes `text`; `what` names the data in errors.
pub fn decode(text: &[u8], what: &str) -> Result<Vec<u8>, FormatProblem> {
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 3);
    let mut quantum = [0u8; 4];
    let mut filled = 0;
    let mut padding = 0;
    for (position, &c) in text.iter().enumerate() {
        if c.is_ascii_whitespace() {
            continue;
        }
        if c == b'=' {
            // Only the last one or two characters of a quantum may be padding.
            if filled < 2 {
                return Err(bad(what, position, "misplaced `=`"));
            }
            padding += 1;
            quantum[filled] = 0;
        } else {
            if padding > 0 {
                return Err(bad(what, position, "data inside padding"));
            }
            quantum[filled] =
                sextet(c).ok_or_else(|| bad(what, position, &format!("invalid character {:?}", c as char)))?;
        }
        filled += 1;
        if filled == 4 {
            push_quantum(&mut out, &quantum, 3 - padding);
            filled = 0;
            padding = 0;
        }
    }
    match (filled, padding) {
        (0, _) => {}
        // Unpadded tail: 2 characters carry 1 byte, 3 carry 2.
        (2, 0) | (3, 0) => push_quantum(&mut out, &quantum, filled - 1),
        _ => return Err(bad(what, text.len(), "incomplete final group")),
    }
    Ok(out)
}

fn push_quantum(out: &mut Vec<u8>, q: &[u8; 4], bytes: usize) {
    let bits = (q[0] as u32) << 18 | (q[1] as u32) << 12 | (q[2] as u32) << 6 | q[3] as u32;
    let all = [(bits >> 16) as u8, (bits >> 8) as u8, bits as u8];
    out.extend_from_slice(&all[..bytes]);
}

fn bad(what: &str, position: usize, problem: &str) -> FormatProblem {
    FormatProblem::syntax(format!("{what} is not valid base64: {problem} at character {position}"))
}

#[cfg(test)]
mod tests {
    use super::decode;

    #[test]
    fn rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("Zg==", "f"),
            ("Zm8=", "fo"),
            ("Zm9v", "foo"),
            ("Zm9vYg==", "foob"),
            ("Zm9vYmE=", "fooba"),
            ("Zm9vYmFy", "foobar"),
        ];
        for (text, plain) in cases {
            assert_eq!(decode(text.as_bytes(), "t").unwrap(), plain.as_bytes(), "{text}");
        }
    }

    #[test]
    fn separately_padded_runs_and_whitespace() {
        // "f" and "oo" encoded separately, then concatenated, with line breaks.
        assert_eq!(decode(b"Zg==\n  b28=", "t").unwrap(), b"foo");
        assert_eq!(decode(b"Zm9\nvYg", "t").unwrap(), b"foob");
    }

    #[test]
    fn rejects_garbage() {
        assert!(decode(b"Zm9v!A==", "t").is_err());
        assert!(decode(b"Z===", "t").is_err());
        assert!(decode(b"Zg=a", "t").is_err());
        assert!(decode(b"Zm9vY", "t").is_err());
    }
}
