//! The techniques a user can name, and one entry point that renders any of them
//! into a [`LinearImage`] with its GPU profile.

use super::tables::CATALOGUE;
use crate::linear_image::LinearImage;
use crate::render::frame_result::FrameResult;
use crate::render::session::{EachFrameAnew, FrameSession};
use crate::render::{GpuScene, RenderError, RenderTechnique};
use crate::scene::technique_settings::TableCatalogue;
use crate::scene::Scene;
use crate::vk::{ProfileReport, Profiler};
use std::fmt;
use std::ops::Deref;
use std::str::FromStr;

/// A technique by name: a copyable handle on its [`RenderTechnique`].
#[derive(Clone, Copy)]
pub struct Technique(&'static dyn RenderTechnique);

// Named like the variants of the enum this handle replaced, so that call sites
// keep reading `Technique::Ipsvi`.
#[allow(non_upper_case_globals)]
impl Technique {
    pub const Dvr: Technique = Technique(&crate::techniques::dvr::DVR);
    pub const Phong: Technique = Technique(&crate::techniques::dvr::PHONG);
    pub const Reference: Technique = Technique(&crate::reference::gpu::Reference);
    pub const Ipsvi: Technique = Technique(&crate::techniques::ipsvi::Ipsvi);
    pub const HalfAngle: Technique = Technique(&crate::techniques::half_angle::HalfAngle);
    pub const LightVolume: Technique = Technique(&crate::techniques::lightvolume::LightVolume);
    pub const Ao: Technique = Technique(&crate::techniques::ao::technique::Ao);

    /// The technique `render`, `compare` and `view` run when none is named:
    /// image plane sweep volume illumination, the technique this project studies.
    pub const DEFAULT: Technique = Technique::Ipsvi;

    /// The techniques that approximate the scene's optical model (compared
    /// with its ground truth), in the order help text lists them.
    pub const ALL: [Technique; 6] = [
        Technique::Dvr,
        Technique::Phong,
        Technique::Reference,
        Technique::Ipsvi,
        Technique::HalfAngle,
        Technique::LightVolume,
    ];

    /// The registry: every technique a user can name, [`Technique::ALL`] and
    /// ambient occlusion (its ground truth is the AO reference, src/techniques/ao/ground_truth/).
    pub const NAMED: [Technique; 7] = {
        let mut named = [Technique::Ao; 7];
        let mut i = 0;
        while i < Technique::ALL.len() {
            named[i] = Technique::ALL[i];
            i += 1;
        }
        named
    };

    /// `name: summary` of every technique, one per line (for `--technique` help).
    pub fn help() -> String {
        Technique::NAMED.map(|t| format!("{}: {}", t.name(), t.summary())).join("\n")
    }
}

impl Deref for Technique {
    type Target = dyn RenderTechnique;
    fn deref(&self) -> &Self::Target {
        self.0
    }
}

impl PartialEq for Technique {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Technique {}

impl fmt::Debug for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Technique {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Technique::NAMED.into_iter().find(|t| t.name() == s).ok_or_else(|| {
            let names = Technique::NAMED.map(|t| t.name());
            let near = crate::scene::suggest::nearest(s, names).map(|n| format!(" (did you mean {n}?)"));
            format!("unknown technique {s:?}{}; known: {}", near.unwrap_or_default(), names.join(", "))
        })
    }
}

impl Technique {
    /// The technique table this technique reads (its name, `-` as `_`), if any.
    pub fn settings_table(self) -> Option<&'static str> {
        let table = self.name().replace('-', "_");
        CATALOGUE.tables().iter().copied().find(|&t| t == table)
    }

    /// A warning for each technique table the scene gave that this technique
    /// does not read: such settings have no effect, and saying nothing would
    /// let a user believe they did.
    pub fn unused_settings(self, scene: &Scene) -> Vec<String> {
        scene
            .technique_tables
            .iter()
            .filter(|&&table| self.settings_table() != Some(table))
            .map(|&table| {
                let reader = Technique::NAMED.into_iter().find(|t| t.settings_table() == Some(table));
                let reader = reader.map_or_else(|| "another technique".to_string(), |t| format!("technique {t}"));
                format!(
                    "the [{table}] settings are read only by {reader}, not by {self}, which runs: they have no effect"
                )
            })
            .collect()
    }
}

pub struct RenderOutput {
    pub technique: Technique,
    pub image: LinearImage,
    pub profile: ProfileReport,
    /// Compute dispatches and pipeline barriers recorded for the frame.
    pub dispatches: u32,
    pub barriers: u32,
    /// A line-sweep frame's shape (IPSVI: render prints it, profile.json holds it).
    pub shape: Option<crate::render::LineShape>,
}

/// Renders one frame of `technique` at `width` x `height`.
pub fn render(
    gpu: &GpuScene,
    technique: Technique,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
) -> Result<RenderOutput, RenderError> {
    profiled_frame(gpu, technique, width, height, profiler, |p| technique.render(gpu, width, height, p))
}

/// One frame of `technique` by `frame` (its `render`, or a [`FrameSession`]'s
/// frame), with the profile of that frame: what `render` and the viewer (for a
/// technique that cannot record into the viewer's command buffer) share.
pub fn profiled_frame(
    gpu: &GpuScene,
    technique: Technique,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    frame: impl FnOnce(&mut Profiler) -> Result<FrameResult, RenderError>,
) -> Result<RenderOutput, RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::Invalid(format!("image size {width}x{height} is empty")));
    }
    technique.check(gpu.scene)?;
    let limits = crate::vk::limits::DeviceLimits::from_vk(&gpu.ctx.limits);
    crate::render::device_fit::check(&limits, &gpu.ctx.info.name, technique.0, gpu.scene, width, height)
        .map_err(crate::vk::VkError::from)?;
    gpu.ctx.memory.reset_peak();
    profiler.reset();
    let frame = frame(profiler)?;
    let bad = frame.image.pixels.iter().filter(|p| !p.iter().all(|c| c.is_finite())).count();
    if bad > 0 {
        return Err(RenderError::NonFinite { technique: technique.name(), bad, total: frame.image.pixels.len() });
    }
    let profile = profiler.resolve(gpu.ctx.memory.device_local_peak())?;
    Ok(RenderOutput {
        technique,
        image: frame.image,
        profile,
        dispatches: frame.dispatches,
        barriers: frame.barriers,
        shape: frame.shape,
    })
}

/// Frames of `technique` on `gpu` one after another: its own session where it
/// keeps state across frames, else each frame rendered anew by `render`.
pub fn session<'s>(gpu: &'s GpuScene<'s>, technique: Technique) -> Result<Box<dyn FrameSession + 's>, RenderError> {
    Ok(match technique.0.session(gpu)? {
        Some(s) => s,
        None => Box::new(EachFrameAnew { technique: technique.0, gpu }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::OpticalModel;
    use crate::techniques::scene_from_toml_str;

    #[test]
    fn every_technique_is_found_by_its_own_name_only() {
        for t in Technique::NAMED {
            assert_eq!(t.name().parse::<Technique>(), Ok(t));
            assert_eq!(Technique::NAMED.iter().filter(|u| u.name() == t.name()).count(), 1, "{t} twice");
            assert!(Technique::help().contains(&format!("{t}: {}", t.summary())));
        }
        let e = "half_angle".parse::<Technique>().unwrap_err();
        assert!(e.contains("did you mean half-angle?") && e.contains("lightvolume"), "{e}");
    }

    #[test]
    fn every_technique_table_is_read_by_exactly_one_technique() {
        for &table in CATALOGUE.tables() {
            let readers: Vec<Technique> =
                Technique::NAMED.into_iter().filter(|t| t.settings_table() == Some(table)).collect();
            assert_eq!(readers.len(), 1, "[{table}]: {readers:?}");
        }
    }

    #[test]
    fn a_table_of_a_technique_that_does_not_run_is_named_with_its_reader() {
        let text = "[volume]\nsynthetic = \"noise\"\nsize = 4\n[half_angle]\nslice_step = 0.75\n";
        let overrides = ["ipsvi.line_width=4".to_string()];
        let scene = scene_from_toml_str(text, std::path::Path::new(""), "test", &overrides).unwrap();
        let w = Technique::Dvr.unused_settings(&scene);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(w.iter().any(|m| m.contains("[ipsvi]") && m.contains("technique ipsvi") && m.contains("dvr")), "{w:?}");
        assert!(w.iter().any(|m| m.contains("[half_angle]") && m.contains("technique half-angle")), "{w:?}");
        let w = Technique::Ipsvi.unused_settings(&scene);
        assert!(w.len() == 1 && w[0].contains("[half_angle]"), "{w:?}");
        let plain =
            scene_from_toml_str("[volume]\nsynthetic = \"noise\"\nsize = 4\n", std::path::Path::new(""), "test", &[]);
        assert_eq!(Technique::Dvr.unused_settings(&plain.unwrap()), Vec::<String>::new());
    }

    #[test]
    fn each_technique_names_the_model_it_approximates() {
        let text = "[volume]\nsynthetic = \"noise\"\nsize = 4\n";
        let mut scene = scene_from_toml_str(text, std::path::Path::new(""), "test", &[]).unwrap();
        for model in [OpticalModel::SingleScattering, OpticalModel::EmissiveScattering] {
            scene.reference.model = model;
            for t in [Technique::Dvr, Technique::Phong, Technique::Reference] {
                assert_eq!(t.reference_model(&scene), model, "{t} follows the scene");
            }
            assert_eq!(Technique::Ipsvi.reference_model(&scene), OpticalModel::EmissiveScattering);
            assert_eq!(Technique::HalfAngle.reference_model(&scene), OpticalModel::SingleScattering);
            assert_eq!(Technique::LightVolume.reference_model(&scene), OpticalModel::SingleScattering);
        }
    }
}
