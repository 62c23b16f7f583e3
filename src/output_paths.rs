//! Output paths checked before any GPU work by every front end: images are PNG (the only format the
//! image writer is built with), and every file goes into a folder that exists,
//! so a typo costs nothing but the message.

use std::path::Path;

/// A file a command was asked to write that it cannot write; the message
/// names the flag and says what to give instead.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct OutputPathError(String);

macro_rules! bail {
    ($($t:tt)*) => { return Err(OutputPathError(format!($($t)*))) };
}

/// A PNG image to write for `flag`.
pub fn check_png(flag: &str, path: &Path) -> Result<(), OutputPathError> {
    // A folder (or a path ending in a separator) first: "name the file *.png"
    // would not tell that a folder was given.
    let text = path.to_string_lossy();
    if path.is_dir() || text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR) {
        bail!(
            "{flag} {}: expects a file, got a directory (e.g. {flag} {})",
            path.display(),
            path.join("image.png").display()
        );
    }
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    if extension.as_deref() != Some("png") {
        bail!("{flag} {}: images are written as PNG; name the file *.png", path.display());
    }
    check_file(flag, path)
}

/// A file to write for `flag`: its folder must exist and it must not be a folder.
pub fn check_file(flag: &str, path: &Path) -> Result<(), OutputPathError> {
    if path.is_dir() {
        bail!("{flag} {}: expects a file, got a directory", path.display());
    }
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !folder.is_dir() {
        bail!("{flag} {}: the folder {} does not exist", path.display(), folder.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_must_be_png_in_an_existing_folder() {
        let dir = std::env::temp_dir();
        assert!(check_png("--out", &dir.join("a.png")).is_ok());
        assert!(check_png("--out", &dir.join("a.PNG")).is_ok());
        assert!(check_png("--out", Path::new("a.png")).is_ok());
        let jpg = check_png("--out", &dir.join("a.jpg")).unwrap_err().to_string();
        assert!(jpg.contains("--out") && jpg.contains("PNG"), "{jpg}");
        let missing = check_png("--out", &dir.join("no-such-folder-sweeplab/a.png")).unwrap_err().to_string();
        assert!(missing.contains("does not exist"), "{missing}");
        assert!(check_file("--json", &dir).unwrap_err().to_string().contains("expects a file, got a directory"));
        let slash = format!("{}/", dir.display());
        let e = check_png("--out", Path::new(&slash)).unwrap_err().to_string();
        assert!(e.contains("expects a file, got a directory"), "{e}");
    }
}
