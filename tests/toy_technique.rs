//! Adding a technique is its folder and one registration line: a toy technique
//! (unshaded DVR times a gain, with a `[toy]` table of its own) registered
//! beside the library's techniques, in a catalogue of this test's own, with
//! nothing else written for it. The catalogue then names it (with a
//! did-you-mean), reads its table from a scene file and checks `--set` edits
//! of it against the range it declares, builds its viewer controls from that
//! declaration, warns when another
//! technique runs with its table set, and the library's render entry point
//! runs it on the GPU like any other technique.

use serde::Deserialize;
use std::path::Path;
use std::sync::LazyLock;
use sweeplab::render::{FrameResult, GpuScene, RenderError, RenderTechnique, ResourceNeed};
use sweeplab::scene::scene_file::scene_from_toml_str;
use sweeplab::scene::settings_controls::{check_declared_ranges, Current, DeclaredSettings, Key, Kind};
use sweeplab::scene::settings_table::{SettingsError, SettingsTable};
use sweeplab::scene::technique_settings::TableCatalogue;
use sweeplab::scene::{OpticalModel, Scene};
use sweeplab::techniques::{dvr, Catalogue, Registration, TableEntry, Technique, CATALOGUE, REGISTERED};
use sweeplab::vk::Profiler;

use crate::common::{assert_validation_clean, validated_context};

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct ToySettings {
    gain: f32,
}

impl Default for ToySettings {
    fn default() -> Self {
        ToySettings { gain: 1.0 }
    }
}

/// Its range is written once, in the declaration: the check comes from there.
impl SettingsTable for ToySettings {
    const TABLE: &'static str = "toy";
    fn validate(&self) -> Result<(), SettingsError> {
        check_declared_ranges(self)
    }
}

impl DeclaredSettings for ToySettings {
    fn keys() -> Vec<Key<Self>> {
        vec![Key::new("gain", "the toy's brightness over DVR's", Kind::Real { lo: 0.0, hi: 2.0 }, |s| {
            Current::Number(s.gain as f64)
        })]
    }
}

struct Toy;

impl RenderTechnique for Toy {
    fn name(&self) -> &'static str {
        "toy"
    }
    fn summary(&self) -> &'static str {
        "unshaded DVR times toy.gain"
    }
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        dvr::DVR.resources(scene, width, height)
    }
    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        let gain = gpu.scene.settings.get::<ToySettings>().gain;
        let mut frame = dvr::DVR.render(gpu, width, height, profiler)?;
        frame.image.pixels.iter_mut().flatten().for_each(|c| *c *= gain);
        Ok(frame)
    }
}

/// The one line a technique adds, here beside the library's own.
static REGISTRY: LazyLock<Vec<Registration>> = LazyLock::new(|| {
    let toy = Registration::compared(&Toy).with_table(TableEntry::of::<ToySettings>());
    REGISTERED.iter().copied().chain([toy]).collect()
});

fn catalogue() -> Catalogue<'static> {
    Catalogue::new(&REGISTRY)
}

const SCENE: &str = "[volume]\nsynthetic = \"three-spheres\"\nsize = 16\n[toy]\ngain = 0.5\n";

fn scene(catalogue: &dyn TableCatalogue, overrides: &[&str]) -> Result<Scene, String> {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    scene_from_toml_str(catalogue, SCENE, Path::new(""), "toy.toml", &overrides).map_err(|e| e.to_string())
}

#[test]
fn a_registered_toy_is_named_read_checked_and_declared_like_the_others() {
    let catalogue = catalogue();
    let toy = catalogue.technique("toy").unwrap();
    assert_eq!(toy.name(), "toy");
    let e = catalogue.technique("toys").unwrap_err();
    assert!(e.contains("did you mean toy?") && e.contains("ipsvi"), "{e}");
    assert_eq!(catalogue.table_of(toy), Some("toy"));
    assert!(catalogue.tables().contains(&"toy") && catalogue.tables().contains(&"ipsvi"));

    // Its table is read from the file, and `--set` edits are checked by its own check.
    let read = scene(&catalogue, &[]).unwrap();
    assert_eq!(read.settings.get::<ToySettings>().gain, 0.5);
    let set = scene(&catalogue, &["toy.gain=1.5"]).unwrap();
    assert_eq!(set.settings.get::<ToySettings>().gain, 1.5);
    let e = scene(&catalogue, &["toy.gain=3"]).unwrap_err();
    assert!(e.contains("toy.gain = 3: must be in 0..=2"), "{e}");
    let e = scene(&catalogue, &["toy.gian=1"]).unwrap_err();
    assert!(e.contains("unknown key toy.gian") && e.contains("did you mean `gain`"), "{e}");

    // The viewer's controls come from its declaration, after the library's.
    let controls = catalogue.controls();
    let last = controls.last().unwrap();
    assert_eq!((last.path(), &last.kind), ("toy.gain".to_string(), &Kind::Real { lo: 0.0, hi: 2.0 }));
    assert_eq!((last.get)(&read), Current::Number(0.5));
    assert_eq!(controls.len(), CATALOGUE.controls().len() + 1);
    assert_eq!(last.doc, "the toy's brightness over DVR's");

    // Its key reference (`sweeplab keys`) comes from the same declaration.
    let doc = catalogue.documented_table("toy").unwrap();
    assert_eq!(doc, "[toy]\ngain = 1.0                   # the toy's brightness over DVR's; 0..=2\n");
    assert!(catalogue.documented_tables().ends_with(&doc));

    // Another technique run with the toy's table set is told it has no effect.
    let warnings = catalogue.unused_settings(Technique::Dvr, &read);
    assert!(
        warnings.len() == 1 && warnings[0].contains("[toy]") && warnings[0].contains("technique toy"),
        "{warnings:?}"
    );

    // The library's own catalogue never heard of it.
    let e = scene(&CATALOGUE, &[]).unwrap_err();
    assert!(e.contains("toy"), "{e}");
    assert!(CATALOGUE.technique("toy").is_err());
}

#[test]
fn the_library_renders_a_registered_toy_like_any_technique() {
    let catalogue = catalogue();
    let scene = scene(&catalogue, &[]).unwrap();
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let toy = catalogue.technique("toy").unwrap();
    let dimmed = sweeplab::techniques::render(&gpu, toy, 16, 16, &mut profiler).unwrap();
    let plain = sweeplab::techniques::render(&gpu, Technique::Dvr, 16, 16, &mut profiler).unwrap();
    let lit = plain.image.pixels.iter().filter(|p| p.iter().any(|&c| c > 0.05)).count();
    assert!(lit > 16, "the spheres cover pixels: {lit}");
    for (d, p) in dimmed.image.pixels.iter().zip(&plain.image.pixels) {
        for c in 0..3 {
            assert_eq!(d[c], p[c] * 0.5, "the toy's gain of its own table");
        }
    }
    assert_eq!(dimmed.dispatches, plain.dispatches);
    assert_validation_clean(&ctx);
}
