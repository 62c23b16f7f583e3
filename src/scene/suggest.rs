//! "Did you mean ...?": the nearest known name to a misspelt one.

/// At most this many single-character edits make a name a likely misspelling.
const MAX_EDITS: usize = 2;

/// The known name closest to `name`, if it is within [`MAX_EDITS`] edits.
/// Case does not count: `IPSVI` is `ipsvi` typed with caps lock on.
pub fn nearest<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let name = name.to_lowercase();
    known
        .into_iter()
        .map(|k| (edit_distance(&name, &k.to_lowercase()), k))
        .filter(|&(d, _)| d <= MAX_EDITS)
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
}

/// Levenshtein distance.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_character_edits() {
        assert_eq!(edit_distance("camera", "camera"), 0);
        assert_eq!(edit_distance("camera", "camra"), 1);
        assert_eq!(edit_distance("lights", "light"), 1);
        assert_eq!(edit_distance("render", "rendre"), 2);
        assert_eq!(edit_distance("ipsvi", "phong"), 5);
        assert_eq!(edit_distance("", "ao"), 2);
    }

    #[test]
    fn case_does_not_count() {
        assert_eq!(nearest("IPSVI", ["dvr", "ipsvi", "ao"]), Some("ipsvi"));
        assert_eq!(nearest("Half-Angel", ["half-angle", "phong"]), Some("half-angle"));
    }

    #[test]
    fn nearest_takes_the_closest_name_within_two_edits() {
        assert_eq!(nearest("ipsvvi", ["phong", "ipsvi", "lightvolume"]), Some("ipsvi"));
        assert_eq!(nearest("cone_angel", ["cone_angle", "zone_blend"]), Some("cone_angle"));
        assert_eq!(nearest("ao", ["ipsvi", "lightvolume"]), None);
    }
}
