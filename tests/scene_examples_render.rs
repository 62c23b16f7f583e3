//! Every example scene of tests/scenes renders, validation clean, with the
//! unshaded baseline and with every technique whose settings table it carries
//! (a scene file written for a technique must work with it).

use crate::common;

use std::path::{Path, PathBuf};

use common::*;
use sweeplab::render::GpuScene;
use sweeplab::techniques::load_scene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

const SIZE: u32 = 16;

fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
}

/// The techniques a scene file names by its settings tables (`[half_angle]`
/// is technique `half-angle`); a table that names none fails the test.
fn named_techniques(path: &Path) -> Vec<Technique> {
    const SCENE_SECTIONS: [&str; 7] = ["volume", "transfer", "camera", "lights", "render", "reference", "phong"];
    // Settings whose technique does not render yet: AO's preprocessing.
    const NOT_RENDERED_YET: [&str; 1] = ["ao"];
    let doc: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    doc.keys()
        .filter(|k| !SCENE_SECTIONS.contains(&k.as_str()) && !NOT_RENDERED_YET.contains(&k.as_str()))
        .map(|k| {
            k.replace('_', "-")
                .parse()
                .unwrap_or_else(|e| panic!("{}: table [{k}] names no technique: {e}", path.display()))
        })
        .collect()
}

#[test]
fn every_example_scene_renders_with_every_technique_it_names() {
    let ctx = validated_context();
    let mut rendered = 0;
    for path in examples() {
        let scene = load_scene(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 8192).unwrap();
        // all-keys.toml documents every key (three lights of every kind), so a
        // technique may refuse it for a documented limit; a scene written for a
        // technique may not be refused at all.
        let reference_of_keys = path.ends_with("all-keys.toml");
        for technique in std::iter::once(Technique::Dvr).chain(named_techniques(&path)) {
            let out = match render(&gpu, technique, SIZE, SIZE, &mut profiler) {
                Ok(out) => out,
                // Only the refusal a technique documents for it: half-angle
                // slicing carries one light, all-keys.toml has several.
                Err(e) if reference_of_keys && technique == Technique::HalfAngle && scene.lights.len() > 1 => {
                    println!("{} with {technique}: refused: {e}", path.display());
                    assert!(e.to_string().contains("one light"), "{e}");
                    continue;
                }
                Err(e) => panic!("{} with {technique}: {e}", path.display()),
            };
            assert!(out.image.all_finite(), "{} with {technique}: non-finite pixels", path.display());
            assert!(out.dispatches >= 1, "{} with {technique}: nothing dispatched", path.display());
            println!("{} with {technique}: {} dispatches", path.display(), out.dispatches);
            rendered += 1;
        }
        assert_validation_clean(&ctx);
    }
    assert!(rendered >= examples().len() + 3, "the examples name ipsvi and lightvolume: {rendered} renders");
}
