//! Turns --scene / --volume / --set / --size into a `Scene`.

use super::args::SceneArgs;
use anyhow::{bail, Context as _};
use sweeplab::scene::warnings::scene_warnings;
use sweeplab::scene::Scene;
use sweeplab::techniques;

/// The `--set` edits, and `--size` as `render.width`/`render.height`; both
/// ways of giving the size at once is an error, not a silent choice.
pub fn overrides(args: &SceneArgs) -> anyhow::Result<Vec<String>> {
    let mut overrides = args.set.clone();
    if let Some(size) = &args.size {
        let sets_size = args
            .set
            .iter()
            .find(|s| ["render.width", "render.height"].contains(&s.split('=').next().unwrap_or("").trim()));
        if let Some(set) = sets_size {
            bail!("--size {size} and --set {set} both give the image size: give one");
        }
        let (w, h) = parse_size(size)?;
        overrides.push(format!("render.width={w}"));
        overrides.push(format!("render.height={h}"));
    }
    Ok(overrides)
}

pub fn load(args: &SceneArgs) -> anyhow::Result<Scene> {
    let overrides = overrides(args)?;
    let scene = if let Some(path) = &args.scene {
        techniques::load_scene(path, &overrides)?
    } else if let Some(path) = &args.volume {
        techniques::scene_for_volume_file(path, &overrides)?
    } else {
        techniques::default_scene(&overrides)?
    };
    for warning in scene_warnings(&scene) {
        eprintln!("warning: {warning}");
    }
    Ok(scene)
}

pub fn parse_size(text: &str) -> anyhow::Result<(u32, u32)> {
    let Some((w, h)) = text.to_lowercase().split_once('x').map(|(a, b)| (a.trim().to_string(), b.trim().to_string()))
    else {
        bail!("--size {text:?}: expected WIDTHxHEIGHT, e.g. 512x512");
    };
    if w.starts_with('-') || h.starts_with('-') {
        bail!("--size {text:?}: width and height are whole numbers in 1..=16384, e.g. 512x512");
    }
    let w: u32 = w.parse().with_context(|| format!("--size {text:?}: width {w:?} is not a whole number"))?;
    let h: u32 = h.parse().with_context(|| format!("--size {text:?}: height {h:?} is not a whole number"))?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        bail!("--size {text:?}: width and height must be between 1 and 16384");
    }
    Ok((w, h))
}
