//! A warning for lavapipe runs at another SIMD width that share Mesa's default
//! shader cache. Mesa 22.3's cache does not key lavapipe's compiled shaders on
//! `LP_NATIVE_VECTOR_WIDTH`: a shader compiled at 512 bits and loaded by a
//! 256-bit process runs, validation-clean, and renders a wrong image (CT
//! engine 256: RMSE 6.59e-3 against 2.86e-3; docs/testing.md, "Tests in a
//! wider lavapipe"). Nothing in the driver tells; the `device:` line does.

/// The warning for a device named `device_name`, given the process's
/// `LP_NATIVE_VECTOR_WIDTH`, `MESA_SHADER_CACHE_DIR` and
/// `MESA_SHADER_CACHE_DISABLE`: a width is set while the cache is Mesa's
/// default and enabled.
pub fn shared_cache_warning(
    device_name: &str,
    vector_width: Option<&str>,
    cache_dir: Option<&str>,
    cache_disabled: Option<&str>,
) -> Option<String> {
    let width = vector_width.filter(|w| !w.trim().is_empty())?;
    let own_cache = cache_dir.is_some_and(|d| !d.trim().is_empty());
    let disabled = cache_disabled.is_some_and(|v| matches!(v.trim(), "1" | "true" | "yes"));
    if !device_name.contains("llvmpipe") || own_cache || disabled {
        return None;
    }
    Some(format!(
        "warning: LP_NATIVE_VECTOR_WIDTH={width} with Mesa's default shader cache, which does not tell vector \
         widths apart (a shader compiled at one width renders wrong at another): set MESA_SHADER_CACHE_DIR to \
         a folder for this width"
    ))
}

/// [`shared_cache_warning`] for this process's environment.
pub fn shared_cache_warning_here(device_name: &str) -> Option<String> {
    let var = |name| std::env::var(name).ok();
    shared_cache_warning(
        device_name,
        var("LP_NATIVE_VECTOR_WIDTH").as_deref(),
        var("MESA_SHADER_CACHE_DIR").as_deref(),
        var("MESA_SHADER_CACHE_DISABLE").as_deref(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAVAPIPE: &str = "llvmpipe (LLVM 15.0.6, 512 bits)";

    #[test]
    fn warns_only_for_lavapipe_at_a_set_width_on_the_default_cache() {
        let w = shared_cache_warning(LAVAPIPE, Some("512"), None, None).expect("a width on the default cache");
        assert!(w.contains("LP_NATIVE_VECTOR_WIDTH=512") && w.contains("MESA_SHADER_CACHE_DIR"), "{w}");
        assert_eq!(shared_cache_warning(LAVAPIPE, None, None, None), None, "the default width");
        assert_eq!(shared_cache_warning(LAVAPIPE, Some("512"), Some("/tmp/lp512"), None), None, "its own cache");
        assert_eq!(shared_cache_warning(LAVAPIPE, Some("512"), None, Some("true")), None, "no cache");
        assert!(shared_cache_warning(LAVAPIPE, Some("512"), Some(""), Some("false")).is_some(), "empty, not off");
        assert_eq!(shared_cache_warning("NVIDIA H200", Some("512"), None, None), None, "not lavapipe");
    }
}
