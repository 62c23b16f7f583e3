//! The image sizes a bench is given: square side lengths, checked before any
//! GPU work with the flag named.

use super::ExperimentError;
use crate::scene::scene_schema::MAX_IMAGE_SIZE;

/// Square image sizes: at least one, each 1..=MAX_IMAGE_SIZE.
pub fn check_sizes(flag: &str, sizes: &[u32]) -> Result<(), ExperimentError> {
    let invalid = |m: String| Err(ExperimentError::Invalid(format!("{flag}: {m}")));
    if sizes.is_empty() {
        return invalid("give at least one size (comma-separated, e.g. 256,512)".into());
    }
    if sizes.contains(&0) {
        return invalid(format!("a 0x0 image is empty (sizes are 1..={MAX_IMAGE_SIZE})"));
    }
    match sizes.iter().find(|&&s| s > MAX_IMAGE_SIZE) {
        Some(bad) => invalid(format!("{bad} is not an image size (1..={MAX_IMAGE_SIZE})")),
        None => Ok(()),
    }
}

/// One `--sizes` value: the side length of a square image. `64x64` is
/// answered with what to write instead (`64`).
pub fn side_length(text: &str) -> Result<u32, String> {
    let text = text.trim();
    if let Some((w, h)) = text.to_lowercase().split_once('x') {
        let hint = if w == h { format!("`{w}` for {w}x{h}") } else { "e.g. `64` for 64x64".to_string() };
        return Err(format!("sizes are side lengths of square images: {hint}"));
    }
    text.parse::<u32>()
        .map_err(|_| format!("{text:?} is not a side length: a whole number in 1..={MAX_IMAGE_SIZE}, e.g. 256"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_side_lengths() {
        assert_eq!(side_length("64"), Ok(64));
        let e = side_length("64x64").unwrap_err();
        assert!(e.contains("side lengths") && e.contains("`64` for 64x64"), "{e}");
        assert!(side_length("64x32").unwrap_err().contains("side lengths"));
        assert!(side_length("big").unwrap_err().contains("whole number"));
    }

    #[test]
    fn bad_values_name_the_flag() {
        assert!(check_sizes("--sizes", &[64, 512]).is_ok());
        for bad in [&[][..], &[0], &[64, 20000]] {
            let e = check_sizes("--sizes", bad).unwrap_err().to_string();
            assert!(e.starts_with("--sizes"), "{e}");
        }
    }
}
