//! What to say about a volume file that is not there: its path once, and the
//! files it was probably meant to be (similar names in the same folder), or
//! where data sets usually live when the folder itself is missing.

use std::path::Path;

use super::suggest::edit_distance;

/// At most this many edits between file names make a likely typo.
const MAX_NAME_EDITS: usize = 3;

/// " (did you mean data/engine.vti?)", or a note on the folder; empty
/// when nothing useful can be said.
pub fn missing_file_hint(path: &Path) -> String {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Some(name) = path.file_name().map(|n| n.to_string_lossy().to_lowercase()) else { return String::new() };
    let Ok(entries) = std::fs::read_dir(folder) else {
        return format!(
            "; the folder {} does not exist (data sets are read from $SWEEPLAB_DATA, default {})",
            folder.display(),
            super::loaders::DEFAULT_DATA_DIR
        );
    };
    let mut near: Vec<(usize, String)> = entries
        .filter_map(|e| e.ok())
        .filter(|e| e.file_type().map(|t| t.is_file()).unwrap_or(false))
        .filter_map(|e| {
            let candidate = e.file_name().to_string_lossy().into_owned();
            let d = edit_distance(&name, &candidate.to_lowercase());
            (d <= MAX_NAME_EDITS).then_some((d, candidate))
        })
        .collect();
    near.sort();
    match near.first() {
        Some((_, file)) => format!(" (did you mean {}?)", folder.join(file).display()),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_a_similar_name_in_the_same_folder_or_says_the_folder_is_missing() {
        let folder = std::env::temp_dir().join(format!("sweeplab-missing-file-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("engine.vti"), "x").unwrap();
        let hint = missing_file_hint(&folder.join("engin.vti"));
        assert_eq!(hint, format!(" (did you mean {}?)", folder.join("engine.vti").display()));
        assert_eq!(missing_file_hint(&folder.join("walnut.raw")), "");
        let hint = missing_file_hint(&folder.join("nowhere").join("engine.vti"));
        assert!(hint.contains("does not exist") && hint.contains("SWEEPLAB_DATA"), "{hint}");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
