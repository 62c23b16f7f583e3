//! The registry: every technique a user can name, registered once in
//! [`REGISTERED`] (its [`RenderTechnique`], whether it is compared with the
//! scene's ground truth, its settings table), and one entry point that renders
//! any of them into a [`LinearImage`] with its GPU profile. Adding a technique
//! is its folder, its `pub mod` line in `techniques/mod.rs` and its line here.

use super::tables::CATALOGUE;
use crate::linear_image::LinearImage;
use crate::render::frame_result::FrameResult;
use crate::render::session::{EachFrameAnew, FrameSession};
use crate::render::{GpuScene, RenderError, RenderTechnique};
use crate::scene::settings_controls::{controls_of, Control, DeclaredSettings};
use crate::scene::settings_docs::documented_table;
use crate::scene::settings_table::{read_table, SettingsError};
use crate::scene::technique_settings::TechniqueTable;
use crate::scene::Scene;
use crate::techniques::{ao, dvr, half_angle, ipsvi, lightvolume};
use crate::vk::{ProfileReport, Profiler};
use std::fmt;
use std::ops::Deref;
use std::str::FromStr;

/// Every technique, in the order help text and the viewer list them.
pub const REGISTERED: &[Registration] = &[
    Registration::compared(&dvr::DVR),
    Registration::compared(&dvr::PHONG),
    Registration::compared(&crate::reference::gpu::Reference),
    Registration::compared(&ipsvi::Ipsvi).with_table(TableEntry::of::<ipsvi::IpsviSettings>()),
    Registration::compared(&half_angle::HalfAngle).with_table(TableEntry::of::<half_angle::HalfAngleSettings>()),
    Registration::compared(&lightvolume::LightVolume).with_table(TableEntry::of::<lightvolume::LightVolumeSettings>()),
    // Its ground truth is its own (src/techniques/ao/ground_truth/), not the scene's.
    Registration::own_truth(&ao::technique::Ao).with_table(TableEntry::of::<ao::AoSettings>()),
];

/// One technique as the front ends know it.
#[derive(Clone, Copy)]
pub struct Registration {
    pub technique: Technique,
    /// It approximates the scene's optical model, so it is among
    /// [`Technique::all`] (the stability table, the viewer's list); false for a
    /// technique with a ground truth of its own (AO).
    pub approximates_scene_model: bool,
    /// The scene-file table it reads, if any.
    pub table: Option<TableEntry>,
}

impl Registration {
    pub const fn compared(technique: &'static dyn RenderTechnique) -> Registration {
        Registration { technique: Technique(technique), approximates_scene_model: true, table: None }
    }

    pub const fn own_truth(technique: &'static dyn RenderTechnique) -> Registration {
        Registration { technique: Technique(technique), approximates_scene_model: false, table: None }
    }

    pub const fn with_table(self, table: TableEntry) -> Registration {
        Registration { table: Some(table), ..self }
    }
}

/// A settings table: its name, its reader and its declared keys.
#[derive(Clone, Copy)]
pub struct TableEntry {
    pub name: &'static str,
    pub read: fn(toml::Value) -> Result<Box<dyn TechniqueTable>, SettingsError>,
    pub controls: fn() -> Vec<Control>,
    /// The key reference (`sweeplab keys`, all-keys.toml).
    pub documented: fn() -> String,
}

impl TableEntry {
    pub const fn of<T: DeclaredSettings>() -> TableEntry {
        TableEntry {
            name: T::TABLE,
            read: read_boxed::<T>,
            controls: controls_of::<T>,
            documented: documented_table::<T>,
        }
    }
}

fn read_boxed<T: DeclaredSettings>(value: toml::Value) -> Result<Box<dyn TechniqueTable>, SettingsError> {
    Ok(Box::new(read_table::<T>(value)?))
}

/// A technique by name: a copyable handle on its [`RenderTechnique`].
#[derive(Clone, Copy)]
pub struct Technique(&'static dyn RenderTechnique);

// Named like the variants of the enum this handle replaced, so that call sites
// keep reading `Technique::Ipsvi`. Conveniences only: the registry is
// [`REGISTERED`].
#[allow(non_upper_case_globals)]
impl Technique {
    pub const Dvr: Technique = Technique(&dvr::DVR);
    pub const Phong: Technique = Technique(&dvr::PHONG);
    pub const Reference: Technique = Technique(&crate::reference::gpu::Reference);
    pub const Ipsvi: Technique = Technique(&ipsvi::Ipsvi);
    pub const HalfAngle: Technique = Technique(&half_angle::HalfAngle);
    pub const LightVolume: Technique = Technique(&lightvolume::LightVolume);
    pub const Ao: Technique = Technique(&ao::technique::Ao);

    /// The technique `render`, `compare` and `view` run when none is named:
    /// image plane sweep volume illumination, the technique this project studies.
    pub const DEFAULT: Technique = Technique::Ipsvi;

    /// The techniques that approximate the scene's optical model (compared
    /// with its ground truth), in the order help text lists them.
    pub fn all() -> impl Iterator<Item = Technique> {
        CATALOGUE.registrations().iter().filter(|r| r.approximates_scene_model).map(|r| r.technique)
    }

    /// Every technique a user can name.
    pub fn named() -> impl Iterator<Item = Technique> {
        CATALOGUE.registrations().iter().map(|r| r.technique)
    }

    /// `name: summary` of every technique, one per line (for `--technique` help).
    pub fn help() -> String {
        Technique::named().map(|t| format!("{}: {}", t.name(), t.summary())).collect::<Vec<_>>().join("\n")
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
        CATALOGUE.technique(s)
    }
}

impl Technique {
    /// The technique table this technique reads, if any.
    pub fn settings_table(self) -> Option<&'static str> {
        CATALOGUE.table_of(self)
    }

    /// A warning for each technique table the scene gave that this technique
    /// does not read: such settings have no effect, and saying nothing would
    /// let a user believe they did.
    pub fn unused_settings(self, scene: &Scene) -> Vec<String> {
        CATALOGUE.unused_settings(self, scene)
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
    use crate::scene::technique_settings::TableCatalogue;
    use crate::scene::OpticalModel;
    use crate::techniques::scene_from_toml_str;

    #[test]
    fn every_technique_is_found_by_its_own_name_only() {
        for t in Technique::named() {
            assert_eq!(t.name().parse::<Technique>(), Ok(t));
            assert_eq!(Technique::named().filter(|u| u.name() == t.name()).count(), 1, "{t} twice");
            assert!(Technique::help().contains(&format!("{t}: {}", t.summary())));
        }
        let e = "half_angle".parse::<Technique>().unwrap_err();
        assert!(e.contains("did you mean half-angle?") && e.contains("lightvolume"), "{e}");
    }

    #[test]
    fn every_technique_table_is_read_by_exactly_one_technique() {
        for &table in CATALOGUE.tables() {
            let readers: Vec<Technique> = Technique::named().filter(|t| t.settings_table() == Some(table)).collect();
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
