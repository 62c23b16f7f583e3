//! Counts with their noun in the right number: "1 dispatch", "258 dispatches".
//! Standalone (imports nothing of ours), so every layer may use it.

/// `n` and `one` when `n` is 1, else `n` and `many`.
pub fn count(n: impl Into<u64>, one: &str, many: &str) -> String {
    let n = n.into();
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::count;

    #[test]
    fn one_is_singular_and_every_other_count_plural() {
        assert_eq!(count(1u32, "dispatch", "dispatches"), "1 dispatch");
        assert_eq!(count(0u32, "dispatch", "dispatches"), "0 dispatches");
        assert_eq!(count(258usize as u64, "entry", "entries"), "258 entries");
    }
}
