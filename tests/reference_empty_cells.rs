//! The ground truth's shadow rays step over the volume's empty cells
//! (src/render/empty_cells.rs, glsl/empty_cells.glsl): the image is bit for
//! bit that of the march over every sample, on the examples with air around
//! their medium (a spot light inside the Cornell box, a directional light, two
//! point lights, the emissive model, a half-transparent medium), with both
//! volume formats; and the cells matter: marked all empty, the shadow rays see
//! no medium and the image changes.
use crate::common;

use common::*;
use std::path::Path;
use sweeplab::linear_image::LinearImage;
use sweeplab::reference::gpu::render_with_cells;
use sweeplab::render::empty_cells::EmptyCells;
use sweeplab::render::view_chunks::ChunkSync;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::techniques::load_scene;
use sweeplab::vk::{Context, Profiler};

const SIZE: u32 = 16;
/// Clear air, then a faint grey that every value above 0.05 makes half transparent.
const HALF_TRANSPARENT: &str =
    "transfer={points=[[0.0, 0.8, 0.8, 0.8, 0.0], [0.05, 0.8, 0.8, 0.8, 0.0], [1.0, 0.8, 0.8, 0.8, 0.2]]}";

fn render(ctx: &Context, gpu: &GpuScene, cells: &EmptyCells) -> LinearImage {
    let mut profiler = Profiler::new(ctx, 256).unwrap();
    render_with_cells(gpu, (SIZE, SIZE), &mut profiler, ChunkSync::Barrier, cells).unwrap().image
}

#[test]
fn stepping_over_empty_cells_gives_the_image_of_every_sample_bit_for_bit() {
    let ctx = validated_context();
    let (small, gap) = ("volume.size=24", "volume.size=48");
    let cases = [
        ("cornell-box.toml", &[small][..], VolumeTexels::Native),
        ("cornell-box.toml", &[small][..], VolumeTexels::Float32),
        ("slab-under-sphere.toml", &[small][..], VolumeTexels::Native),
        ("three-spheres.toml", &[small][..], VolumeTexels::Native),
        ("slab-under-sphere.toml", &[small, "reference.model=\"emissive-scattering\""][..], VolumeTexels::Native),
        // Half-transparent, with air between the slab and the sphere (at 24
        // voxels the dilated cells of the two touch): shadow rays from the slab
        // cross empty cells, then the sphere. Skipping 4 voxels past an empty
        // cell's exit changes this image (3.4e-4 of a peak of 0.6); 2 voxels,
        // the cells' guaranteed margin, does not.
        ("slab-under-sphere.toml", &[gap, HALF_TRANSPARENT][..], VolumeTexels::Native),
    ];
    for (file, extra, texels) in cases {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes").join(file);
        // Coarse: the sums, not their convergence, are compared.
        let mut overrides: Vec<String> =
            ["reference.step=0.5", "reference.shadow_step=0.25"].iter().chain(extra).map(|s| s.to_string()).collect();
        overrides.extend([format!("render.width={SIZE}"), format!("render.height={SIZE}")]);
        let scene = load_scene(&path, &overrides).unwrap();
        let gpu = GpuScene::upload_with(&ctx, &scene, texels).unwrap();
        let cells = EmptyCells::of_scene(&gpu);
        let what = format!("{file} {extra:?} {texels:?}");
        assert!(
            cells.empty_count() > 0 && cells.empty_count() < cells.occupied.len(),
            "{what}: {} of {} cells empty",
            cells.empty_count(),
            cells.occupied.len()
        );
        let every_sample = render(&ctx, &gpu, &EmptyCells::none_empty(&scene.volume));
        assert!(render(&ctx, &gpu, cells) == every_sample, "{what}: skipping empty cells changed the image");
        let all_empty = EmptyCells { cells: cells.cells, occupied: vec![0; cells.occupied.len()] };
        assert!(render(&ctx, &gpu, &all_empty) != every_sample, "{what}: the cells do not reach the shadow rays");
    }
    assert_validation_clean(&ctx);
}
