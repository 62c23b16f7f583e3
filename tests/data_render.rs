//! Every real data set in $SWEEPLAB_DATA loads and renders (small images, with
//! validation and synchronization validation on).
use crate::common;

use common::*;
use sweeplab::render::GpuScene;
use sweeplab::scene::loaders::data_dir;
use sweeplab::techniques::scene_for_volume_file;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

const FILES: [&str; 5] = ["engine.vti", "aneurism.vti", "LIDC2.mha", "smallHeart.mhd", "nucleon.nrrd"];

#[test]
fn every_shared_data_set_renders_with_every_technique() {
    let dir = data_dir();
    let ctx = validated_context();
    for file in FILES {
        let path = dir.join(file);
        assert!(path.exists(), "{} not found: data/ holds it (or SWEEPLAB_DATA names the data folder)", path.display());
        let overrides = ["render.width=20".to_string(), "render.height=16".to_string()];
        let scene = scene_for_volume_file(&path, &overrides).unwrap_or_else(|e| panic!("{file}: {e}"));
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 256).unwrap();
        for technique in [Technique::Dvr, Technique::Phong, Technique::Ipsvi] {
            let out = render(&gpu, technique, 20, 16, &mut profiler).unwrap();
            assert!(out.image.all_finite(), "{file} {technique}: non-finite pixels");
            let background = scene.render.background;
            let shows_something = out.image.pixels.iter().any(|p| (p[0] - background.x).abs() > 1e-3);
            assert!(shows_something, "{file} {technique}: the automatic transfer function shows nothing");
        }
    }
    assert_validation_clean(&ctx);
}
