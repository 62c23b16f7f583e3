//! AO preprocessing on the CPU (docs/ao.md): local histograms against hand
//! computations, the streamed preprocessing against a recomputation, VQ
//! behaviour on real histograms, the disk cache, and the Cornell box timing.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::{UVec3, Vec3};
use sweeplab::scene::synthetic::cornell_box;
use sweeplab::scene::{Volume, VoxelData};
use sweeplab::techniques::ao::cache::{AoCache, CacheKey, CacheMiss};
use sweeplab::techniques::ao::histogram::{LocalHistograms, SphereStencil};
use sweeplab::techniques::ao::packing::PackingScheme;
use sweeplab::techniques::ao::quantize::{distance, unpack_cluster_ids};
use sweeplab::techniques::ao::{
    preprocess, preprocess_cached, AoPreprocessed, AoSettings, CacheOutcome, Metric, TrainingSet,
};
use sweeplab::techniques::load_scene;

/// 9^3 U8 volume: material A (100) for z <= 4, material B (200) for z >= 5.
fn two_materials() -> Volume {
    let n = 9u32;
    let data = (0..n * n * n).map(|i| if i / (n * n) <= 4 { 100 } else { 200 }).collect();
    Volume {
        name: "two-materials".into(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(data),
        value_range: (100.0, 200.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

fn index(v: &Volume, p: [u32; 3]) -> usize {
    ((p[2] * v.dims.y + p[1]) * v.dims.x + p[0]) as usize
}

fn histograms_of(h: &LocalHistograms, voxel: usize) -> (Vec<f32>, Vec<f32>) {
    let (mut f, mut b) = (vec![0.0; h.bins()], vec![0.0; h.bins()]);
    h.voxel_into(voxel, &mut h.scratch(), &mut f, &mut b);
    (f, b)
}

fn close(a: f32, b: f64) -> bool {
    (a as f64 - b).abs() < 1e-6
}

/// Radius 2 around a voxel, by hand (offsets (x, y, z), d^2 = x^2 + y^2 + z^2):
/// - plane z = 0: 4 at d^2 = 1, 4 at 2, 4 at 4: weights 4 + 4/2 + 4/4 = 7, 12 voxels;
/// - layer z = +-1: 1 at d^2 = 1, 4 at 2, 4 at 3: 1 + 2 + 4/3 = 13/3, 9 voxels each;
/// - layer z = +-2: 1 at d^2 = 4: 1/4, 1 voxel each.
///
/// N_r = 12 + 18 + 2 = 32 (33 lattice points with the centre).
const PLANE: f64 = 7.0;
const LAYER1: f64 = 13.0 / 3.0;
const LAYER2: f64 = 0.25;
const N_R: f64 = 32.0;

#[test]
fn histograms_of_two_materials_match_hand_computed_weights() {
    let v = two_materials();
    let h = LocalHistograms::new(&v, 2, 8);
    assert_eq!(h.stencil().voxel_count(), 32);
    // On the interface: gradient +z (towards B). Forward (against the gradient)
    // holds the A layers below; backward the B layers above; the plane z = 4 is
    // A and is shared half and half.
    let (f, b) = histograms_of(&h, index(&v, [4, 4, 4]));
    assert!(close(f[100], (LAYER1 + LAYER2 + PLANE / 2.0) / N_R), "{}", f[100]);
    assert!(close(f[200], 0.0));
    assert!(close(b[100], PLANE / 2.0 / N_R), "{}", b[100]);
    assert!(close(b[200], (LAYER1 + LAYER2) / N_R), "{}", b[200]);
    let other: f32 = (0..256).filter(|&k| k != 100 && k != 200).map(|k| f[k] + b[k]).sum();
    assert_eq!(other, 0.0);

    // Inside A near the lower border, zero gradient: both hemispheres hold half
    // of what is in the volume (the layer z = -1 is outside and adds nothing).
    let (f, b) = histograms_of(&h, index(&v, [4, 4, 1]));
    let inside = (PLANE + 2.0 * LAYER1 + LAYER2) / N_R;
    assert!(close(f[100], inside / 2.0) && close(b[100], inside / 2.0), "{} {}", f[100], b[100]);

    // Fully inside the volume, each hemisphere sums to the stencil's half mass
    // (whatever the gradient): (7 + 2 * 13/3 + 2/4) / 2 / 32.
    let half = (PLANE + 2.0 * LAYER1 + 2.0 * LAYER2) / 2.0 / N_R;
    assert!((h.stencil().full_hemisphere_mass() - half).abs() < 1e-12);
    for p in [[4, 4, 4], [4, 4, 3], [4, 4, 5], [3, 4, 6]] {
        let (f, b) = histograms_of(&h, index(&v, p));
        let (sf, sb): (f32, f32) = (f.iter().sum(), b.iter().sum());
        assert!(close(sf, half) && close(sb, half), "{p:?}: {sf} {sb} vs {half}");
    }

    // Four bins (b = 2): 100 -> bin 1, 200 -> bin 3.
    let h2 = LocalHistograms::new(&v, 2, 2);
    let (f, b) = histograms_of(&h2, index(&v, [4, 4, 4]));
    assert!(close(f[1], (LAYER1 + LAYER2 + PLANE / 2.0) / N_R) && close(b[3], (LAYER1 + LAYER2) / N_R));
    assert_eq!((f[0], f[2], f[3], b[0], b[2]), (0.0, 0.0, 0.0, 0.0, 0.0));
}

#[test]
fn the_sphere_follows_anisotropic_spacing_in_units_of_d_min() {
    assert_eq!(SphereStencil::new(2, Vec3::ONE).voxel_count(), 32);
    // Spacing 2 along z: d_min = 1; offsets z = +-1 are 2 d_min away, so only
    // (0, 0, +-1) with weight 1/4 remain beside the plane z = 0.
    let s = SphereStencil::new(2, Vec3::new(1.0, 1.0, 2.0));
    assert_eq!(s.voxel_count(), 14);
    assert_eq!(s.extent, UVec3::new(2, 2, 1));
    let off_plane: Vec<f64> = (0..14).filter(|&i| s.offsets[i].z != 0).map(|i| s.weights[i]).collect();
    assert_eq!(off_plane, vec![0.25, 0.25]);
}

#[test]
fn streamed_slabs_cover_every_voxel_once_and_equal_single_voxels() {
    let v = cornell_box(12);
    let h = LocalHistograms::new(&v, 3, 8);
    let mut seen = vec![0u32; v.voxel_count()];
    let mut mismatches = 0;
    // A tiny slab size: one x-row per slab.
    h.stream(
        1,
        |slab| slab.clone(),
        |_, slab, _, _| {
            for (i, voxel) in slab.voxels.clone().enumerate() {
                seen[voxel] += 1;
                let (f, b) = histograms_of(&h, voxel);
                let (sf, sb) = slab.voxel(i);
                mismatches += usize::from(sf != f.as_slice() || sb != b.as_slice());
                // Forward + backward is the full sphere, at most 1 (all of it inside).
                let total: f32 = sf.iter().chain(sb).sum();
                assert!(total > 0.0 && total <= 1.0 + 1e-5);
            }
        },
    );
    assert!(seen.iter().all(|&s| s == 1));
    assert_eq!(mismatches, 0);
}

/// Small settings for a volume of a few thousand voxels.
fn small(clusters: u32, metric: Metric) -> AoSettings {
    AoSettings {
        radius: 3,
        bits: 8,
        packed_dim: 16,
        clusters,
        metric,
        training: TrainingSet::Random { count: 4096, seed: 3 },
        lbg_iterations: 20,
        lbg_threshold: 1e-4,
        cache: false,
        cache_dir: None,
        backend: None,
        // The rendering keys do not touch the preprocessing.
        ..AoSettings::default()
    }
}

fn run(volume: &Volume, settings: &AoSettings) -> AoPreprocessed {
    preprocess(volume, settings, &mut |_| {}).expect("preprocess")
}

#[test]
fn ids_are_the_nearest_packed_codewords_and_the_codebook_averages_members() {
    let v = cornell_box(16);
    let s = small(16, Metric::L2);
    let r = run(&v, &s);
    assert_eq!(r.cluster_ids.len(), v.voxel_count());
    assert_eq!((r.clusters, r.bins, r.packed_dim), (16, 256, 16));
    let h = LocalHistograms::new(&v, s.radius, s.bits);
    let dim = r.packed_dim as usize;
    let bins = r.bins as usize;
    let packed_word = |c: usize| &r.packed_codebook[c * dim..(c + 1) * dim];
    let mut sums = vec![0f64; 16 * bins];
    let mut sizes = vec![0u64; 16];
    for voxel in 0..v.voxel_count() {
        let (f, b) = histograms_of(&h, voxel);
        let (fid, bid) = unpack_cluster_ids(r.cluster_ids[voxel]);
        for (hist, id) in [(&f, fid as usize), (&b, bid as usize)] {
            let packed: Vec<f32> =
                (0..dim).map(|j| (0..bins).map(|k| hist[k] * r.packing_matrix[k * dim + j]).sum()).collect();
            let d_id = distance(Metric::L2, &packed, packed_word(id));
            for c in 0..16 {
                // The matrix product sums in another order than the packing:
                // allow float noise, nothing more.
                assert!(d_id <= distance(Metric::L2, &packed, packed_word(c)) + 1e-6, "voxel {voxel}: {id} vs {c}");
            }
            sizes[id] += 1;
            for k in 0..bins {
                sums[id * bins + k] += hist[k] as f64;
            }
        }
    }
    assert_eq!(sizes, r.cluster_sizes);
    for c in 0..16 {
        for k in 0..bins {
            let mean = if sizes[c] == 0 { 0.0 } else { sums[c * bins + k] / sizes[c] as f64 };
            assert!((r.codebook[c * bins + k] as f64 - mean).abs() < 1e-6, "cluster {c} bin {k}");
        }
    }
    // Several clusters in use, and the packing matrix is the one of the volume's histogram.
    assert!(sizes.iter().filter(|&&n| n > 0).count() >= 8, "{sizes:?}");
    let mut global = vec![0f64; 256];
    for &k in h.voxel_bins() {
        global[k as usize] += 1.0 / v.voxel_count() as f64;
    }
    assert_eq!(r.packing_matrix, PackingScheme::from_histogram(&global, 16).matrix());
}

#[test]
fn distortion_falls_with_the_codebook_size_for_every_metric_and_metrics_differ() {
    let v = cornell_box(16);
    let mut codebooks = vec![];
    for metric in Metric::ALL {
        let results: Vec<AoPreprocessed> = [4, 16, 64].iter().map(|&n| run(&v, &small(n, metric))).collect();
        let training: Vec<f64> = results.iter().map(|r| r.stats.training_distortion).collect();
        let all: Vec<f64> = results.iter().map(|r| r.stats.assignment_distortion).collect();
        assert!(training.windows(2).all(|w| w[1] < w[0]), "{metric:?} training: {training:?}");
        assert!(all.windows(2).all(|w| w[1] < w[0]), "{metric:?} all voxels: {all:?}");
        codebooks.push(results[1].packed_codebook.clone());
    }
    assert_ne!(codebooks[0], codebooks[1], "L2 and L1 trained the same codebook");
    assert_ne!(codebooks[0], codebooks[2], "L2 and Lmax trained the same codebook");
    assert_ne!(codebooks[1], codebooks[2], "L1 and Lmax trained the same codebook");
}

#[test]
fn the_gradient_training_set_trains_on_surfaces() {
    let v = cornell_box(16);
    let mut s = small(8, Metric::L1);
    s.training = TrainingSet::Gradient { eps: 0.05, count: 1000, seed: 2 };
    let r = run(&v, &s);
    assert_eq!(r.stats.training_vectors, 2000);
    s.training = TrainingSet::Gradient { eps: 5.0, count: 1000, seed: 2 };
    let e = preprocess(&v, &s, &mut |_| {}).unwrap_err().to_string();
    assert!(e.contains("ao.training.eps"), "{e}");
}

fn temp_cache(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sweeplab-ao-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn cached(volume: &Volume, s: &AoSettings) -> (AoPreprocessed, CacheOutcome) {
    preprocess_cached(volume, s, &mut |_| {}).expect("preprocess_cached")
}

/// Equal results, apart from the wall-clock timings of the run that made them.
fn same_result(a: &AoPreprocessed, b: &AoPreprocessed) -> bool {
    let mut b = b.clone();
    b.stats.timings = a.stats.timings.clone();
    *a == b
}

fn stored_reason(outcome: CacheOutcome) -> CacheMiss {
    match outcome {
        CacheOutcome::Stored(_, miss) => miss,
        other => panic!("expected a rebuild, got {other:?}"),
    }
}

#[test]
fn the_cache_hits_and_is_invalidated_by_content_and_parameters() {
    let dir = temp_cache("hit");
    let mut s = small(8, Metric::L2);
    s.cache = true;
    s.cache_dir = Some(dir.display().to_string());
    let v = cornell_box(12);

    let (first, outcome) = cached(&v, &s);
    assert_eq!(stored_reason(outcome), CacheMiss::Absent);
    let (second, outcome) = cached(&v, &s);
    assert!(matches!(outcome, CacheOutcome::Hit(_)), "{outcome:?}");
    assert!(first == second, "a hit returns exactly what was stored, timings included");

    // Content: one voxel changed.
    let mut changed = v.clone();
    if let VoxelData::U8(d) = &mut changed.data {
        d[700] ^= 1;
    }
    assert_ne!(CacheKey::new(&v, &s), CacheKey::new(&changed, &s));
    assert_eq!(stored_reason(cached(&changed, &s).1), CacheMiss::Absent);

    // Every parameter is in the key.
    let variants: [fn(&mut AoSettings); 8] = [
        |s| s.radius = 2,
        |s| s.bits = 6,
        |s| s.packed_dim = 8,
        |s| s.clusters = 4,
        |s| s.metric = Metric::Lmax,
        |s| s.training = TrainingSet::Random { count: 4096, seed: 4 },
        |s| s.training = TrainingSet::Gradient { eps: 0.05, count: 4096, seed: 3 },
        |s| s.lbg_iterations = 3,
    ];
    for change in variants {
        let mut other = s.clone();
        change(&mut other);
        assert_ne!(CacheKey::new(&v, &s), CacheKey::new(&v, &other), "{other:?}");
    }
    let mut other = s.clone();
    other.radius = 2;
    let (r2, outcome) = cached(&v, &other);
    assert_eq!(stored_reason(outcome), CacheMiss::Absent);
    assert!(r2.cluster_ids != first.cluster_ids);
    // The first result is still there.
    assert!(matches!(cached(&v, &s).1, CacheOutcome::Hit(_)));
    // Directory and on/off are not part of the key.
    let mut elsewhere = s.clone();
    elsewhere.cache_dir = Some("/elsewhere".into());
    assert_eq!(CacheKey::new(&v, &s), CacheKey::new(&v, &elsewhere));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_corrupt_or_stale_cache_file_is_rebuilt_never_trusted() {
    let dir = temp_cache("corrupt");
    let mut s = small(8, Metric::L1);
    s.cache = true;
    s.cache_dir = Some(dir.display().to_string());
    let v = cornell_box(12);
    let (good, _) = cached(&v, &s);
    let cache = AoCache::new(&dir);
    let key = CacheKey::new(&v, &s);
    let path = cache.path(&key);
    let bytes = std::fs::read(&path).unwrap();

    let damage: Vec<(&str, Vec<u8>)> = vec![
        ("truncated", bytes[..bytes.len() / 2].to_vec()),
        ("truncated by one byte", bytes[..bytes.len() - 1].to_vec()),
        ("empty", vec![]),
        ("bit flipped in the payload", {
            let mut b = bytes.clone();
            let i = b.len() / 2;
            b[i] ^= 0x10;
            b
        }),
        ("bit flipped in the magic", {
            let mut b = bytes.clone();
            b[0] ^= 1;
            b
        }),
        ("bit flipped in the checksum", {
            let mut b = bytes.clone();
            let i = b.len() - 1;
            b[i] ^= 0x80;
            b
        }),
    ];
    for (what, damaged) in damage {
        std::fs::write(&path, &damaged).unwrap();
        let (rebuilt, outcome) = cached(&v, &s);
        assert!(matches!(stored_reason(outcome), CacheMiss::Corrupt(_)), "{what}");
        assert!(same_result(&rebuilt, &good), "{what}: the rebuilt result differs");
        let reloaded = cache.load(&key).unwrap().unwrap_or_else(|miss| panic!("{what}: rewritten file {miss:?}"));
        assert!(same_result(&reloaded, &good), "{what}: the rewritten file");
        assert!(matches!(cached(&v, &s).1, CacheOutcome::Hit(_)), "{what}");
    }

    // A sound file written for other parameters, under this key's name: stale.
    let mut other = s.clone();
    other.clusters = 4;
    let other_key = CacheKey::new(&v, &other);
    let (other_result, _) = cached(&v, &other);
    std::fs::copy(cache.path(&other_key), &path).unwrap();
    let (rebuilt, outcome) = cached(&v, &s);
    assert!(matches!(stored_reason(outcome), CacheMiss::Stale(_)));
    assert!(same_result(&rebuilt, &good));
    assert!(!same_result(&rebuilt, &other_result));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_cornell_scene_reads_its_ao_table_and_preprocesses_in_seconds() {
    // The [ao] table comes by --set: an example scene names only the techniques
    // that render it (tests/scene_examples_render.rs), and AO does not render yet.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/cornell-box.toml");
    let scene = load_scene(&path, &["ao.radius=8".to_string()]).expect("cornell-box.toml");
    let mut s = AoSettings::from_scene(&scene).expect("[ao]");
    assert_eq!(s.radius, 8);
    s.cache = false;
    s.clusters = 256;
    let started = Instant::now();
    let mut steps: Vec<String> = vec![];
    let r = preprocess(&scene.volume, &s, &mut |p| {
        if steps.last().map(String::as_str) != Some(p.step) {
            steps.push(p.step.to_string());
        }
    })
    .expect("preprocess");
    let seconds = started.elapsed().as_secs_f64();
    let t = &r.stats.timings;
    eprintln!(
        "cornell-box 64^3 r = 8, n_c = 256: {seconds:.2} s (packing {:.3}, TS histograms {:.2}, training {:.2}, assignment {:.2}), {} Lloyd iterations",
        t.packing, t.training_histograms, t.training, t.assignment, r.stats.lloyd_iterations
    );
    assert_eq!(steps, ["ao packing", "ao training-set histograms", "ao training", "ao assignment"]);
    assert_eq!(r.dims, UVec3::splat(64));
    // "A few seconds" on two shared cores; the bound leaves room for a busy machine.
    assert!(seconds < 60.0, "{seconds} s");
}

/// engine.vti (256 x 256 x 128) from the data folder (`data/`, or `SWEEPLAB_DATA`), for the hand-run measurements.
fn engine_volume() -> Volume {
    let path = sweeplab::scene::loaders::data_dir().join("engine.vti");
    sweeplab::scene::loaders::load_volume(&path).expect("engine.vti in the data folder")
}

/// A whole number from the environment variable `name`, else `default`.
fn env_u32(name: &str, default: u32) -> u32 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Timing of engine.vti (256 x 256 x 128), run by hand:
/// `AO_RADIUS=8 AO_CLUSTERS=2048 cargo test --release
/// --test suite ao_preprocess::engine -- --ignored --nocapture`
#[test]
#[ignore = "a measurement of minutes, not a check"]
fn engine_preprocessing_timing() {
    let volume = engine_volume();
    let s = AoSettings {
        radius: env_u32("AO_RADIUS", 8),
        clusters: env_u32("AO_CLUSTERS", 2048),
        cache: false,
        ..AoSettings::default()
    };
    let started = Instant::now();
    let mut last_step = String::new();
    let r = preprocess(&volume, &s, &mut |p| {
        if p.step != last_step || p.fraction >= 1.0 {
            eprintln!("{}", p.line());
            last_step = p.step.to_string();
        }
    })
    .expect("preprocess");
    let t = &r.stats.timings;
    eprintln!(
        "engine {:?} r = {} n_c = {} packed {}: total {:.1} s: packing {:.3}, TS histograms {:.2}, training {:.2} ({} Lloyd iterations, {} vectors), assignment {:.2}; stencil {} voxels; distortion TS {:.3e}, all {:.3e}",
        volume.dims,
        s.radius,
        s.clusters,
        s.packed_dim,
        started.elapsed().as_secs_f64(),
        t.packing,
        t.training_histograms,
        t.training,
        r.stats.lloyd_iterations,
        r.stats.training_vectors,
        t.assignment,
        SphereStencil::new(s.radius, volume.spacing).voxel_count(),
        r.stats.training_distortion,
        r.stats.assignment_distortion,
    );
}

/// `dims` U8 volume: seeded noise of `levels` intensities (few levels: long
/// runs and many gradients with exact zeros along a row), a flat block (zero
/// gradient) and a plateau, so forward, backward and on-plane pieces, flat
/// regions and borders all occur.
fn noise_volume(dims: UVec3, spacing: Vec3, levels: u8, seed: u64) -> Volume {
    common::seeded_volume("row-runs-test", dims, spacing, seed, |p, random| {
        if p.x < 4 && p.y < 5 && p.z < 3 {
            90
        } else if p.y > dims.y / 2 {
            200
        } else {
            ((random >> 33) % levels as u64) as u8 * (255 / levels.max(2) - 1)
        }
    })
}

/// The preprocessing's histograms (by stencil rows and runs of equal bin, and
/// by centres in lanes over whole and partial x rows) equal the brute force's,
/// voxel by voxel and bin by bin.
#[test]
fn histograms_by_rows_and_runs_equal_the_brute_force() {
    let cases = [
        (UVec3::new(14, 12, 11), Vec3::ONE, 3u8, 4u32, 8u32),
        (UVec3::new(14, 12, 11), Vec3::ONE, 40, 5, 4),
        (UVec3::new(13, 11, 12), Vec3::new(1.0, 1.5, 2.5), 3, 6, 8),
        (UVec3::new(12, 13, 10), Vec3::new(0.7, 1.0, 1.0), 7, 4, 8),
        (UVec3::new(9, 9, 9), Vec3::ONE, 2, 1, 8),
    ];
    for (c, &(dims, spacing, levels, radius, bits)) in cases.iter().enumerate() {
        let v = noise_volume(dims, spacing, levels, 7 + c as u64);
        let h = LocalHistograms::new(&v, radius, bits);
        let mut scratch = h.scratch();
        let n = h.bins();
        let (mut f, mut b, mut rf, mut rb) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let (mut differing, mut worst) = (0usize, 0f32);
        for voxel in 0..v.voxel_count() {
            h.voxel_into(voxel, &mut scratch, &mut f, &mut b);
            h.voxel_into_by_rows(voxel, &mut scratch, &mut rf, &mut rb);
            for k in 0..n {
                for (brute, rows) in [(f[k], rf[k]), (b[k], rb[k])] {
                    if brute != rows {
                        differing += 1;
                        worst = worst.max((brute - rows).abs() / brute.abs().max(f32::MIN_POSITIVE));
                    }
                }
            }
        }
        // Centres in lanes: whole x rows (groups and a remainder) and a piece
        // of a row starting off a group boundary.
        let nx = dims.x as usize;
        let (mut lanes_differing, mut lanes_worst) = (0usize, 0f32);
        let pieces: Vec<(usize, usize)> =
            (0..v.voxel_count() / nx).map(|row| (row * nx, nx)).chain([(3 * nx + 1, nx - 2)]).collect();
        for (first, count) in pieces {
            let (mut lf, mut lb) = (vec![0.0; count * n], vec![0.0; count * n]);
            h.x_run_into(first, count, &mut scratch, &mut lf, &mut lb);
            for i in 0..count {
                h.voxel_into(first + i, &mut scratch, &mut f, &mut b);
                for k in 0..n {
                    for (brute, lanes) in [(f[k], lf[i * n + k]), (b[k], lb[i * n + k])] {
                        if brute != lanes {
                            lanes_differing += 1;
                            lanes_worst = lanes_worst.max((brute - lanes).abs() / brute.abs().max(f32::MIN_POSITIVE));
                        }
                    }
                }
            }
        }
        eprintln!(
            "case {c}: {differing} bins differ by rows, worst relative {worst:e}; {lanes_differing} in lanes, worst {lanes_worst:e}"
        );
        // Only the order of the f64 sums differs: at most one f32 rounding step.
        assert!(worst <= f32::EPSILON, "case {c}: {differing} bins differ, worst relative {worst:e}");
        assert!(lanes_worst <= f32::EPSILON, "case {c}: {lanes_differing} bins differ in lanes, worst {lanes_worst:e}");
    }
}

/// The histogram step's cost per voxel on engine.vti, rows and runs against
/// the brute force and centres in lanes against rows and runs, in thread CPU
/// time (steady on a shared machine), on 64
/// whole x-rows spread over the volume, run by hand:
/// `AO_RADIUS=16 AO_BITS=4 cargo test --release
/// --test suite ao_preprocess::histogram_cost -- --ignored --nocapture`
#[test]
#[ignore = "a measurement, not a check"]
fn histogram_cost_per_voxel_rows_against_brute_force() {
    let volume = engine_volume();
    let (radius, bits) = (env_u32("AO_RADIUS", 16), env_u32("AO_BITS", 4));
    let h = LocalHistograms::new(&volume, radius, bits);
    let (nx, rows) = (volume.dims.x as usize, (volume.dims.y * volume.dims.z) as usize);
    let voxels: Vec<usize> = (0..64).flat_map(|i| (i * 7919 % rows) * nx..(i * 7919 % rows + 1) * nx).collect();
    let mut scratch = h.scratch();
    let (mut f, mut b) = (vec![0.0; h.bins()], vec![0.0; h.bins()]);
    let mut per_voxel = |by_rows: bool| {
        let start = common::cpu_seconds("/proc/thread-self/stat");
        for &voxel in &voxels {
            match by_rows {
                true => h.voxel_into_by_rows(voxel, &mut scratch, &mut f, &mut b),
                false => h.voxel_into(voxel, &mut scratch, &mut f, &mut b),
            }
        }
        (common::cpu_seconds("/proc/thread-self/stat") - start) / voxels.len() as f64 * 1e6
    };
    let (rows_us, brute_us, rows_again) = (per_voxel(true), per_voxel(false), per_voxel(true));
    // Centres in lanes, as the preprocessing runs: whole x rows, four times
    // over (the clock ticks in 10 ms).
    let (mut lf, mut lb) = (vec![0.0; nx * h.bins()], vec![0.0; nx * h.bins()]);
    let mut lanes_per_voxel = || {
        let start = common::cpu_seconds("/proc/thread-self/stat");
        for _ in 0..4 {
            for row in voxels.chunks(nx) {
                h.x_run_into(row[0], nx, &mut scratch, &mut lf, &mut lb);
            }
        }
        (common::cpu_seconds("/proc/thread-self/stat") - start) / (4 * voxels.len()) as f64 * 1e6
    };
    let (lanes_us, lanes_again) = (lanes_per_voxel(), lanes_per_voxel());
    eprintln!(
        "engine r = {radius} b = {bits}, {} voxels: rows and runs {rows_us:.2} / {rows_again:.2} us per voxel, brute force {brute_us:.2} us ({:.1}x), centres in lanes {lanes_us:.2} / {lanes_again:.2} us ({:.1}x over rows)",
        voxels.len(),
        brute_us / rows_us.max(rows_again),
        rows_us.min(rows_again) / lanes_us.max(lanes_again)
    );
    // What the walk's cost is made of: runs of equal bin the stencil's rows
    // cross per voxel (what each adds to a bin), along x as walked and along y
    // and z for comparison, counted here from the bins, independently of the
    // walk.
    let dims = volume.dims.as_ivec3();
    let bin_at = |p: glam::IVec3| -> usize {
        if p.cmplt(glam::IVec3::ZERO).any() || p.cmpge(dims).any() {
            return h.bins(); // outside: a bin of its own, as the padding
        }
        h.voxel_bins()[((p.z * dims.y + p.y) * dims.x + p.x) as usize] as usize
    };
    let sorted_offsets: Vec<Vec<glam::IVec3>> = (0..3)
        .map(|axis| {
            let mut o = h.stencil().offsets.clone();
            o.sort_by_key(|v| {
                let mut key = [v.x, v.y, v.z];
                key.rotate_left(axis);
                [key[2], key[1], key[0]]
            });
            o
        })
        .collect();
    let runs_per_voxel = |axis: usize| {
        let mut runs = 0usize;
        for &voxel in &voxels {
            let c = h.position(voxel).as_ivec3();
            let mut previous: Option<(glam::IVec3, usize)> = None;
            // Stencil offsets sorted so that rows along `axis` are consecutive.
            for o in &sorted_offsets[axis] {
                let (p, k) = (c + *o, bin_at(c + *o));
                let mut along = *o;
                along[axis] -= 1;
                let continues = previous.is_some_and(|(q, j)| q == c + along && j == k);
                runs += usize::from(!continues);
                previous = Some((p, k));
            }
        }
        runs as f64 / voxels.len() as f64
    };
    let runs = [runs_per_voxel(0), runs_per_voxel(1), runs_per_voxel(2)];
    eprintln!(
        "stencil of {} voxels crosses runs of one bin per voxel: {:.0} along x (walked; {:.1} ns each), {:.0} along y, {:.0} along z",
        h.stencil().offsets.len(),
        runs[0],
        rows_us.min(rows_again) * 1e3 / runs[0],
        runs[1],
        runs[2]
    );
}
