//! Mutations of parser inputs for the property tests that fuzz the volume
//! loaders and the scene files (tests/loaders/fuzz.rs, tests/scene_fuzz.rs):
//! byte edits like a fuzzer's, plus the edit that finds most header bugs, a
//! number replaced by an extreme one.
#![allow(dead_code)]

use proptest::prelude::*;

/// Replacements for a number in a header: zero, negatives, overflow of u32,
/// i64 and u64, and what floats can hold but sizes cannot.
pub const EXTREME_NUMBERS: [&str; 14] = [
    "0",
    "-1",
    "-0",
    "1e308",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "2147483648",
    "4294967297",
    "65536",
    "9223372036854775808",
    "18446744073709551616",
    "99999999999",
];

#[derive(Clone, Debug)]
pub enum Mutation {
    /// Sets the byte at (position mod length).
    Set {
        at: usize,
        value: u8,
    },
    Insert {
        at: usize,
        bytes: Vec<u8>,
    },
    Remove {
        at: usize,
        len: usize,
    },
    Truncate {
        at: usize,
    },
    /// Replaces the n-th (mod count) run of ASCII digits by an extreme number.
    Number {
        nth: usize,
        value: &'static str,
    },
    /// Repeats a slice (duplicated keys, lines or blocks).
    Repeat {
        at: usize,
        len: usize,
    },
    /// Overwrites 4 bytes with a non-finite f32 (NaN, +inf, -inf, either byte
    /// order): voxels no writer produces.
    NonFinite {
        at: usize,
        bits: [u8; 4],
    },
}

const NON_FINITE_F32: [[u8; 4]; 6] = [
    [0x7f, 0xc0, 0x00, 0x00],
    [0x00, 0x00, 0xc0, 0x7f],
    [0x7f, 0x80, 0x00, 0x00],
    [0x00, 0x00, 0x80, 0x7f],
    [0xff, 0x80, 0x00, 0x00],
    [0x00, 0x00, 0x80, 0xff],
];

pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(at, value)| Mutation::Set { at, value }),
        (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
        (any::<usize>(), 1..32usize).prop_map(|(at, len)| Mutation::Remove { at, len }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        // Twice as likely: header fields are where sizes come from.
        (any::<usize>(), proptest::sample::select(&EXTREME_NUMBERS[..]))
            .prop_map(|(nth, value)| Mutation::Number { nth, value }),
        (any::<usize>(), proptest::sample::select(&EXTREME_NUMBERS[..]))
            .prop_map(|(nth, value)| Mutation::Number { nth, value }),
        (any::<usize>(), 1..64usize).prop_map(|(at, len)| Mutation::Repeat { at, len }),
        (any::<usize>(), proptest::sample::select(&NON_FINITE_F32[..]))
            .prop_map(|(at, bits)| Mutation::NonFinite { at, bits }),
    ]
}

pub fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    proptest::collection::vec(mutation(), 1..4)
}

/// Digit runs of `bytes` as (start, end).
fn numbers(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let start = i;
            while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
                i += 1;
            }
            runs.push((start, i));
        } else {
            i += 1;
        }
    }
    runs
}

pub fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    let pos = |at: usize| if len == 0 { 0 } else { at % (len + 1) };
    match m {
        Mutation::Set { at, value } => {
            if len > 0 {
                bytes[at % len] = *value;
            }
        }
        Mutation::Insert { at, bytes: b } => {
            let at = pos(*at);
            bytes.splice(at..at, b.iter().copied());
        }
        Mutation::Remove { at, len: n } => {
            let at = pos(*at);
            let end = (at + n).min(len);
            bytes.drain(at..end);
        }
        Mutation::Truncate { at } => bytes.truncate(pos(*at)),
        Mutation::Number { nth, value } => {
            let runs = numbers(bytes);
            if !runs.is_empty() {
                let (start, end) = runs[nth % runs.len()];
                bytes.splice(start..end, value.bytes());
            }
        }
        Mutation::Repeat { at, len: n } => {
            let at = pos(*at);
            let end = (at + n).min(len);
            let copy = bytes[at..end].to_vec();
            bytes.splice(end..end, copy);
        }
        Mutation::NonFinite { at, bits } => {
            if len >= 4 {
                // Aligned to 4 bytes from the end, where a detached data file's voxels are.
                let at = (len - 4) - ((at % (len - 3)) / 4 * 4).min(len - 4);
                bytes[at..at + 4].copy_from_slice(bits);
            }
        }
    }
}

pub fn mutated(original: &[u8], ms: &[Mutation]) -> Vec<u8> {
    let mut bytes = original.to_vec();
    for m in ms {
        apply(&mut bytes, m);
    }
    bytes
}
