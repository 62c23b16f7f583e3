//! Scene files: the examples under tests/scenes, `--set` overrides, and the
//! errors for bad files and arguments.

use std::path::{Path, PathBuf};

use glam::Vec3;
use sweeplab::scene::framing::{visible_box, FRAME_FILL};
use sweeplab::scene::loaders::data_dir;
use sweeplab::scene::scene_file::SceneError;
use sweeplab::scene::scene_spec::{CameraPlacement, ProjectionSpec, SceneSpec, TransferSpec, VolumeSource};
use sweeplab::scene::settings_table::known_keys;
use sweeplab::scene::synthetic::{three_spheres, SyntheticKind};
use sweeplab::scene::{Falloff, LightKind, OpticalModel, TechniqueSettings};
use sweeplab::techniques::ao::AoSettings;
use sweeplab::techniques::half_angle::HalfAngleSettings;
use sweeplab::techniques::ipsvi::{
    CacheUpdate, CacheWrite, EarlyTermination, IpsviSettings, ReadFronts, SyncStrategy, WritePass, WriteRule,
    WriteValue,
};
use sweeplab::techniques::lightvolume::{CostEstimate, LightVolumeSettings};
use sweeplab::techniques::volume_file_scene_spec;
use sweeplab::techniques::{parse_scene_file, parse_scene_str, scene_from_toml_str};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes")
}

fn example_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("tests/scenes exists")
        .map(|e| e.expect("readable directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
}

fn example(name: &str, overrides: &[&str]) -> SceneSpec {
    let path = scenes_dir().join(name);
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    parse_scene_file(&path, &overrides).unwrap_or_else(|e| panic!("{e}"))
}

/// The error message for a scene given as text (origin "test.toml").
fn error_of(text: &str, overrides: &[&str]) -> String {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match parse_scene_str(text, Path::new("/scenes"), "test.toml", &overrides) {
        Ok(_) => panic!("expected an error for:\n{text}\nwith {overrides:?}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "message does not mention {part:?}: {message}");
    }
}

const MINIMAL: &str = "[volume]\nsynthetic = \"noise\"\nsize = 8\n";

#[test]
fn every_example_scene_parses() {
    let paths = example_paths();
    let names: Vec<String> = paths.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    for expected in
        ["phantom.toml", "three-spheres.toml", "cornell-box.toml", "slab-under-sphere.toml", "all-keys.toml"]
    {
        assert!(names.iter().any(|n| n == expected), "{expected} missing from {names:?}");
    }
    for path in &paths {
        if let Err(e) = parse_scene_file(path, &[]) {
            panic!("{}: {e}", path.display());
        }
    }
}

#[test]
fn synthetic_example_scenes_build() {
    for path in example_paths() {
        let spec = parse_scene_file(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
        let VolumeSource::Synthetic { size, .. } = spec.volume else {
            continue;
        };
        let scene = spec.build().unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(scene.volume.dims, glam::UVec3::splat(size), "{}", path.display());
        assert!(!scene.transfer.points.is_empty());
    }
}

#[test]
fn data_example_scenes_load_their_volumes() {
    let dir = data_dir();
    for path in example_paths() {
        let spec = parse_scene_file(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
        let VolumeSource::File(file) = &spec.volume else {
            continue;
        };
        assert!(file.starts_with(&dir), "{}: data_file must resolve under {}", path.display(), dir.display());
        assert!(
            file.exists(),
            "{}: {} is missing; the real data sets are read from data/ or SWEEPLAB_DATA (now {})",
            path.display(),
            file.display(),
            dir.display()
        );
        let scene = spec.build().unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.volume.voxel_count() > 0);
    }
}

#[test]
fn examples_read_what_they_say() {
    let spheres = example("three-spheres.toml", &[]);
    assert_eq!(spheres.lights.len(), 2);
    assert_eq!(spheres.lights[0].kind, LightKind::Point { position: Vec3::new(-1.2, 0.2, 0.3) });
    assert_eq!(spheres.lights[1].color, Vec3::new(0.2, 0.4, 1.0));
    assert_eq!(
        *spheres.settings.get::<LightVolumeSettings>(),
        LightVolumeSettings { scale: 2, ..LightVolumeSettings::default() }
    );

    let cornell = example("cornell-box.toml", &[]);
    let LightKind::Spot { direction, inner_cone_deg, outer_cone_deg, .. } = cornell.lights[0].kind else {
        panic!("cornell-box.toml: expected a spot light");
    };
    assert_eq!((direction, inner_cone_deg, outer_cone_deg), (Vec3::NEG_Y, 50.0, 70.0));
    assert_eq!(cornell.lights[0].falloff, Falloff::InverseSquare);
    assert_eq!(cornell.camera.projection, ProjectionSpec::Perspective { fov_y_deg: 40.0 });

    let voxel = example("single-voxel.toml", &[]);
    assert!(voxel.lights.is_empty(), "`lights = []` means no lights");
    assert_eq!(voxel.camera.projection, ProjectionSpec::Orthographic { height: Some(1.0) });

    let noise = example("noise.toml", &[]);
    assert_eq!(noise.transfer, TransferSpec::FromHistogram);
    assert_eq!(noise.reference.model, OpticalModel::EmissiveScattering);
    assert_eq!(noise.volume, VolumeSource::Synthetic { kind: SyntheticKind::Noise, size: 48, seed: 7 });

    let nucleon = example("nucleon.toml", &[]);
    assert_eq!(
        nucleon.camera.placement,
        CameraPlacement::LookAt { eye: Vec3::new(1.2, 0.8, 1.6), target: Vec3::ZERO, up: Vec3::Y }
    );
    let TransferSpec::Given(tf) = &nucleon.transfer else { panic!("nucleon.toml: expected explicit points") };
    assert_eq!(tf.points.len(), 4);
    assert_eq!(tf.points[2].rgba, [0.9, 0.5, 0.2, 0.2]);
}

#[test]
fn an_almost_empty_file_gets_the_documented_defaults() {
    let spec = parse_scene_str(MINIMAL, Path::new(""), "minimal", &[]).unwrap();
    assert_eq!((spec.render.width, spec.render.height, spec.render.step_voxels), (512, 512, 0.5));
    assert_eq!((spec.render.background, spec.render.emission), (Vec3::ZERO, 0.1));
    assert_eq!(spec.reference.model, OpticalModel::SingleScattering);
    assert_eq!((spec.reference.step_voxels, spec.reference.shadow_step_voxels), (0.25, 0.5));
    assert_eq!(spec.reference.min_transmittance, 1e-4);
    assert_eq!(
        (spec.phong.ambient, spec.phong.diffuse, spec.phong.specular, spec.phong.shininess),
        (0.2, 0.8, 0.3, 32.0)
    );
    assert_eq!(spec.camera.projection, ProjectionSpec::Perspective { fov_y_deg: 30.0 });
    assert_eq!(
        spec.camera.placement,
        CameraPlacement::Orbit { target: Vec3::ZERO, azimuth_deg: 30.0, elevation_deg: 20.0, distance: None }
    );
    assert_eq!(spec.lights.len(), 1);
    assert_eq!(spec.lights[0].kind, LightKind::Directional { direction: Vec3::new(1.0, -1.0, -1.0).normalize() });
    assert_eq!((spec.lights[0].color, spec.lights[0].intensity), (Vec3::ONE, 1.0));
    assert_eq!(spec.settings, TechniqueSettings::default());
    // The noise volume's own preset.
    assert_eq!(spec.transfer, TransferSpec::Given(sweeplab::scene::presets::preset("grayscale-ramp").unwrap()));
}

#[test]
fn set_changes_the_named_fields() {
    let before = example("phantom.toml", &[]);
    let after = example(
        "phantom.toml",
        &[
            "camera.azimuth=45",
            "render.width=128",
            "lights.0.intensity=5",
            "ipsvi.line_width=4",
            "camera.projection=orthographic",
            "reference.model=emissive-scattering",
            "volume.size=16",
        ],
    );
    let azimuth = |s: &SceneSpec| match s.camera.placement {
        CameraPlacement::Orbit { azimuth_deg, .. } => azimuth_deg,
        CameraPlacement::LookAt { .. } => panic!("expected an orbit camera"),
    };
    assert_eq!((azimuth(&before), azimuth(&after)), (30.0, 45.0));
    assert_eq!((before.render.width, after.render.width), (256, 128));
    assert_eq!(after.render.height, 256, "other keys keep their values");
    assert_eq!((before.lights[0].intensity, after.lights[0].intensity), (1.0, 5.0));
    assert_eq!(before.settings, TechniqueSettings::default());
    assert_eq!(after.settings.get::<IpsviSettings>().line_width, 4);
    assert_eq!(after.camera.projection, ProjectionSpec::Orthographic { height: None });
    assert_eq!(after.reference.model, OpticalModel::EmissiveScattering);
    assert_eq!(after.volume, VolumeSource::Synthetic { kind: SyntheticKind::SheppLogan, size: 16, seed: 1 });
    // The orbit camera is placed by the overridden azimuth.
    let scene = after.build().unwrap();
    let eye = scene.camera.eye;
    assert!((eye.x / eye.z - 45f32.to_radians().tan()).abs() < 1e-5, "eye {eye}");
}

#[test]
fn set_applies_to_the_default_light_and_replaces_whole_tables() {
    let spec = parse_scene_str(MINIMAL, Path::new(""), "minimal", &["lights.0.intensity=3".into()]).unwrap();
    assert_eq!(spec.lights[0].intensity, 3.0);

    let spec = example(
        "phantom.toml",
        &["lights=[{type=\"point\", position=[0, 1, 0]}, {type=\"directional\"}]", "transfer={auto=true}"],
    );
    assert_eq!(spec.lights.len(), 2);
    assert_eq!(spec.lights[0].kind, LightKind::Point { position: Vec3::Y });
    assert_eq!(spec.transfer, TransferSpec::FromHistogram);

    // A later --set wins.
    let spec = example("phantom.toml", &["render.width=100", "render.width=200"]);
    assert_eq!(spec.render.width, 200);
}

#[test]
fn volume_paths_resolve_against_the_scene_folder_and_the_data_folder() {
    let text = "[volume]\nfile = \"sub/ct.nrrd\"\n";
    let spec = parse_scene_str(text, Path::new("/scenes/here"), "s", &[]).unwrap();
    assert_eq!(spec.volume, VolumeSource::File(PathBuf::from("/scenes/here/sub/ct.nrrd")));
    assert_eq!(spec.transfer, TransferSpec::FromHistogram, "file volumes default to the automatic transfer");

    let text = "[volume]\nfile = \"/abs/ct.nrrd\"\n";
    let spec = parse_scene_str(text, Path::new("/scenes/here"), "s", &[]).unwrap();
    assert_eq!(spec.volume, VolumeSource::File(PathBuf::from("/abs/ct.nrrd")));

    let spec = parse_scene_str("[volume]\ndata_file = \"engine.vti\"\n", Path::new("/x"), "s", &[]).unwrap();
    assert_eq!(spec.volume, VolumeSource::File(data_dir().join("engine.vti")));

    // parse_scene_file takes the folder of the file.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scene_files_relative");
    std::fs::create_dir_all(&dir).unwrap();
    let scene_path = dir.join("scene.toml");
    std::fs::write(&scene_path, "[volume]\nfile = \"vol.raw\"\n").unwrap();
    let spec = parse_scene_file(&scene_path, &[]).unwrap();
    assert_eq!(spec.volume, VolumeSource::File(dir.join("vol.raw")));
}

#[test]
fn a_missing_volume_file_is_an_error_naming_scene_and_volume() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scene_files_missing");
    std::fs::create_dir_all(&dir).unwrap();
    let scene_path = dir.join("missing-volume.toml");
    std::fs::write(&scene_path, "[volume]\nfile = \"no-such-volume.nrrd\"\n").unwrap();
    std::fs::write(dir.join("no-such-volume.nrd"), "x").unwrap();
    let e = sweeplab::techniques::load_scene(&scene_path, &[]).unwrap_err();
    assert!(matches!(e, SceneError::MissingVolume { .. }), "{e:?}");
    let message = e.to_string();
    assert_mentions(&message, &["missing-volume.toml", "no volume file", "did you mean", "no-such-volume.nrd"]);
    assert_eq!(message.matches("no-such-volume.nrrd").count(), 1, "the path once: {message}");
}

#[test]
fn a_missing_or_malformed_scene_file_is_an_error_naming_it() {
    let e = parse_scene_file(Path::new("/no/such/scene.toml"), &[]).unwrap_err();
    assert!(matches!(e, SceneError::Read { .. }));
    assert_mentions(&e.to_string(), &["/no/such/scene.toml"]);

    let e = error_of("[volume]\nsynthetic = noise\n", &[]);
    assert_mentions(&e, &["test.toml", "TOML", "line 2"]);
}

#[test]
fn misspelt_keys_are_errors_naming_file_and_key() {
    let e = error_of(&format!("{MINIMAL}[camera]\nazimth = 3.0\n"), &[]);
    assert_mentions(&e, &["test.toml", "`camera`", "azimth"]);
    let e = error_of(&format!("{MINIMAL}[[lights]]\ntype = \"point\"\nintensty = 2.0\n"), &[]);
    assert_mentions(&e, &["test.toml", "`lights.0`", "intensty"]);
    let e = error_of(&format!("{MINIMAL}[[lights]]\n[[lights]]\ncolour = [1, 1, 1]\n"), &[]);
    assert_mentions(&e, &["`lights.1`", "colour"]);
    let e = error_of(&format!("{MINIMAL}[render]\nwidht = 3\n"), &[]);
    assert_mentions(&e, &["`render`", "widht"]);
    let e = error_of("[volume]\nsynthetic = \"noise\"\nsise = 3\n", &[]);
    assert_mentions(&e, &["`volume`", "sise"]);
    let e = error_of(&format!("{MINIMAL}[camra]\nazimuth = 3.0\n"), &[]);
    assert_mentions(&e, &["test.toml", "camra", "did you mean [camera]"]);
    let e = error_of(&format!("width = 3\n{MINIMAL}"), &[]);
    assert_mentions(&e, &["test.toml", "`width`", "not a scene setting"]);
    // Misspelt through --set: caught the same way.
    let e = error_of(MINIMAL, &["render.widht=3"]);
    assert_mentions(&e, &["`render`", "widht"]);
}

#[test]
fn values_of_the_wrong_type_or_name_are_errors_naming_the_key() {
    let e = error_of(&format!("{MINIMAL}[render]\nwidth = \"big\"\n"), &[]);
    assert_mentions(&e, &["test.toml", "`render.width`"]);
    let e = error_of(&format!("{MINIMAL}[camera]\nprojection = \"fisheye\"\n"), &[]);
    assert_mentions(&e, &["`camera.projection`", "fisheye", "orthographic"]);
    let e = error_of(&format!("{MINIMAL}[camera]\ntarget = [0, 0]\n"), &[]);
    assert_mentions(&e, &["`camera.target`", "length"]);
    let e = error_of(&format!("{MINIMAL}[[lights]]\ntype = \"area\"\n"), &[]);
    assert_mentions(&e, &["`lights.0.type`", "area"]);
    let e = error_of("[volume]\nsynthetic = \"sphere\"\n", &[]);
    assert_mentions(&e, &["`volume.synthetic`", "sphere", "three-spheres"]);
    let e = error_of(&format!("{MINIMAL}[transfer]\npreset = \"bone\"\n"), &[]);
    assert_mentions(&e, &["`transfer.preset`", "bone", "ct-bone"]);
    let e = error_of(&format!("{MINIMAL}lights = 3\n"), &[]);
    assert_mentions(&e, &["`lights`"]);
    let e = error_of("[volume]\nsynthetic = \"noise\"\nsize = -4\n", &[]);
    assert_mentions(&e, &["`volume.size`"]);
}

#[test]
fn out_of_range_values_are_errors_naming_the_key() {
    let cases: &[(&str, &str)] = &[
        ("[render]\nwidth = 0", "render.width"),
        ("[render]\nheight = 16385", "render.height"),
        ("[render]\nstep = 0.0", "render.step"),
        ("[render]\nstep = -1.0", "render.step"),
        ("[render]\nstep = nan", "render.step"),
        ("[render]\nemission = -0.5", "render.emission"),
        ("[render]\nbackground = [0, inf, 0]", "render.background"),
        ("[camera]\nfov_y = 180.0", "camera.fov_y"),
        ("[camera]\nfov_y = 0.0", "camera.fov_y"),
        // Found by tests/scene_fuzz.rs: framing at this field of view put the eye at infinity.
        ("[camera]\nfov_y = 1e-45", "camera.fov_y"),
        // Found by tests/scene_fuzz.rs: eye and target rounded to one point (a NaN view).
        ("[camera]\ntarget = [1e30, 1e30, 1e30]", "camera.target"),
        ("[camera]\neye = [1e30, 0, 0]", "camera.eye"),
        ("[camera]\ndistance = 1e30", "camera.distance"),
        ("[camera]\ntarget = [1e5, 0, 0]\ndistance = 1e-6", "camera.distance"),
        ("[camera]\nelevation = 100.0", "camera.elevation"),
        ("[camera]\ndistance = 0.0", "camera.distance"),
        ("[camera]\nprojection = \"orthographic\"\northo_height = -1.0", "camera.ortho_height"),
        ("[camera]\neye = [0, 0, 0]", "camera.eye"),
        ("[camera]\neye = [0, 2, 0]", "camera.up"),
        ("[[lights]]\nintensity = -1.0", "lights.0.intensity"),
        ("[[lights]]\nintensity = inf", "lights.0.intensity"),
        ("[[lights]]\ndirection = [0, 0, 0]", "lights.0.direction"),
        ("[[lights]]\ncolor = [1, -1, 1]", "lights.0.color"),
        ("[[lights]]\ntype = \"point\"\nposition = [nan, 0, 0]", "lights.0.position"),
        ("[[lights]]\ntype = \"spot\"\ninner_cone = 30.0\nouter_cone = 30.0", "lights.0.inner_cone"),
        ("[[lights]]\ntype = \"spot\"\ninner_cone = -1.0", "lights.0.inner_cone"),
        ("[[lights]]\ntype = \"spot\"\nouter_cone = 190.0", "lights.0.outer_cone"),
        ("[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]", "lights.0.direction"),
        ("[reference]\nmin_transmittance = 1.0", "reference.min_transmittance"),
        ("[reference]\nshadow_step = 0.0", "reference.shadow_step"),
        ("[phong]\nshininess = -2.0", "phong.shininess"),
        ("[transfer]\npoints = []", "transfer.points"),
        ("[transfer]\npoints = [[0.5, 0, 0, 0, 0], [0.2, 0, 0, 0, 0]]", "transfer.points.1"),
        ("[transfer]\npoints = [[0.0, 0, 0, 0, 0], [1.5, 0, 0, 0, 0]]", "transfer.points.1"),
        ("[transfer]\npoints = [[0.0, 0, 0, 2, 0]]", "transfer.points.0"),
    ];
    for (table, key) in cases {
        let e = error_of(&format!("{MINIMAL}{table}\n"), &[]);
        assert_mentions(&e, &["test.toml", &format!("`{key}`")]);
    }
    let many: Vec<String> = (0..=256).map(|i| format!("[{}, 0, 0, 0, 0]", i as f32 / 256.0)).collect();
    let e = error_of(&format!("{MINIMAL}[transfer]\npoints = [{}]\n", many.join(", ")), &[]);
    assert_mentions(&e, &["`transfer.points`", "257"]);
    let e = error_of("[volume]\nsynthetic = \"noise\"\nsize = 0\n", &[]);
    assert_mentions(&e, &["`volume.size`"]);
    let e = error_of("[volume]\nsynthetic = \"noise\"\nsize = 513\n", &[]);
    assert_mentions(&e, &["`volume.size`"]);
}

#[test]
fn contradicting_keys_are_errors_naming_them() {
    let cases: &[(&str, &str)] = &[
        ("[volume]\nfile = \"a.raw\"\nsynthetic = \"noise\"\n", "volume"),
        ("[volume]\n", "volume"),
        ("[render]\nwidth = 8\n", "volume"),
        ("[volume]\nfile = \"\"\n", "volume.file"),
        ("[volume]\nfile = \"a.raw\"\nsize = 8\n", "volume.size"),
        ("[volume]\nsynthetic = \"cornell-box\"\nseed = 3\n", "volume.seed"),
        ("[volume]\nsynthetic = \"noise\"\n[transfer]\npreset = \"ct-bone\"\nauto = true\n", "transfer"),
        ("[volume]\nsynthetic = \"noise\"\n[camera]\neye = [1, 1, 1]\nazimuth = 3.0\n", "camera.azimuth"),
        ("[volume]\nsynthetic = \"noise\"\n[camera]\nup = [0, 0, 1]\n", "camera.up"),
        ("[volume]\nsynthetic = \"noise\"\n[camera]\northo_height = 1.0\n", "camera.ortho_height"),
        ("[volume]\nsynthetic = \"noise\"\n[camera]\nprojection = \"orthographic\"\nfov_y = 20.0\n", "camera.fov_y"),
        ("[volume]\nsynthetic = \"noise\"\n[[lights]]\nposition = [0, 1, 0]\n", "lights.0.position"),
        (
            "[volume]\nsynthetic = \"noise\"\n[[lights]]\ntype = \"point\"\ndirection = [0, 1, 0]\n",
            "lights.0.direction",
        ),
        ("[volume]\nsynthetic = \"noise\"\n[[lights]]\ntype = \"point\"\nouter_cone = 9.0\n", "lights.0.outer_cone"),
        ("[volume]\nsynthetic = \"noise\"\n[[lights]]\nfalloff = \"inverse-square\"\n", "lights.0.falloff"),
    ];
    for (text, key) in cases {
        let e = error_of(text, &[]);
        assert_mentions(&e, &["test.toml", &format!("`{key}`")]);
    }
}

#[test]
fn bad_set_arguments_are_errors_naming_them() {
    let e = error_of(MINIMAL, &["render.width"]);
    assert_mentions(&e, &["test.toml", "--set `render.width`", "KEY=VALUE"]);
    let e = error_of(MINIMAL, &["=5"]);
    assert_mentions(&e, &["--set `=5`", "empty"]);
    let e = error_of(MINIMAL, &["camera..azimuth=5"]);
    assert_mentions(&e, &["--set `camera..azimuth=5`"]);
    let e = error_of(MINIMAL, &["lights.1.intensity=5"]);
    assert_mentions(&e, &["--set `lights.1.intensity=5`", "index 1 is out of range", "`lights` has 1 entry"]);
    let e = error_of(MINIMAL, &["lights.key.intensity=5"]);
    assert_mentions(&e, &["--set `lights.key.intensity=5`", "index"]);
    let e = error_of(MINIMAL, &["volume.size.x=5"]);
    assert_mentions(&e, &["--set `volume.size.x=5`", "`volume.size` is an integer"]);
    // A well-formed --set with a bad value is caught by the checks, naming the key.
    let e = error_of(MINIMAL, &["render.width=0"]);
    assert_mentions(&e, &["test.toml", "`render.width`"]);
    // A negative size gets the real range, not "a whole number (0 or more)".
    let e = error_of(MINIMAL, &["render.width=-5"]);
    assert_mentions(&e, &["`render.width`", "must be in 1..=16384, got -5"]);
    let e = error_of(MINIMAL, &["lights.0.type=laser"]);
    assert_mentions(&e, &["`lights.0.type`", "laser"]);
}

#[test]
fn scene_from_toml_str_builds_synthetic_scenes() {
    let scene = scene_from_toml_str(MINIMAL, Path::new(""), "minimal", &["render.width=64".into()]).unwrap();
    assert_eq!(scene.volume.dims, glam::UVec3::splat(8));
    assert_eq!(scene.render.width, 64);
}

#[test]
fn volume_file_scene_frames_what_shows_and_makes_the_background_clear() {
    let spec = volume_file_scene_spec(Path::new("x.raw"), &["render.height=256".into()]).unwrap();
    assert_eq!(spec.transfer, TransferSpec::FromHistogram);
    let scene = spec.build_with_volume(three_spheres(32));
    assert_eq!(scene.transfer.eval(0.0)[3], 0.0, "background (empty space) must be clear");
    assert!(scene.transfer.eval(1.0)[3] > 0.0, "the spheres must be visible");
    // Light from the upper right of the default camera (azimuth 30), square to
    // the view, so its shadows show.
    let LightKind::Directional { direction } = scene.lights[0].kind else { panic!("expected a directional light") };
    let basis = scene.camera.basis(scene.render.width, scene.render.height);
    let from = -direction;
    assert!(
        from.dot(basis.right.normalize()) > 0.5
            && from.dot(basis.up.normalize()) > 0.3
            && from.dot(basis.forward).abs() < 0.1,
        "{direction}"
    );
    // What the transfer function shows fills the view: the corners of its box
    // reach FRAME_FILL of the half view, none beyond.
    let framed = visible_box(&scene.volume, &scene.transfer, &scene.volume_box());
    let mut reach = 0.0f32;
    for corner in framed.corners() {
        let d = corner - basis.origin;
        let along = d.dot(basis.forward);
        assert!(along > 0.0);
        let x = d.dot(basis.right) / basis.right.length_squared() / along;
        let y = d.dot(basis.up) / basis.up.length_squared() / along;
        reach = reach.max(x.abs()).max(y.abs());
    }
    assert!((reach - FRAME_FILL).abs() < 1e-3, "corners reach {reach}");
}

// The techniques' tables: typed settings read with the scene.

fn settings_of(tables: &str, overrides: &[&str]) -> TechniqueSettings {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    parse_scene_str(&format!("{MINIMAL}{tables}"), Path::new(""), "test.toml", &overrides)
        .unwrap_or_else(|e| panic!("{e}"))
        .settings
}

#[test]
fn technique_defaults_are_the_documented_ones() {
    let ipsvi = IpsviSettings::default();
    assert_eq!((ipsvi.line_width, ipsvi.cache_size, ipsvi.piecewise), (1, 0, true));
    assert_eq!((ipsvi.early_termination, ipsvi.albedo, ipsvi.cone_angle_deg), (EarlyTermination::Plain, 0.0, 15.0));
    assert_eq!((ipsvi.zone_blend_px, ipsvi.light_step_voxels, ipsvi.ert_scale), (2.0, 0.5, 4));
    assert_eq!(ipsvi.sync, SyncStrategy::BarrierGlobal);
    assert_eq!(
        (ipsvi.line_kernel, ipsvi.segments, ipsvi.segment_rounds),
        (sweeplab::techniques::ipsvi::LineKernel::Auto, 0, 16)
    );
    assert_eq!((ipsvi.cache_update, ipsvi.cache_write), (CacheUpdate::ViewSamples, CacheWrite::Farthest));
    let lv = LightVolumeSettings::default();
    assert_eq!((lv.scale, lv.coherent, lv.compensated, lv.cost_estimate), (2, true, true, CostEstimate::Passes));
    assert_eq!((lv.max_passes_per_frame, lv.pass_lights, lv.rebase_tolerance), (0, 64, 1e-6));
    assert_eq!((lv.substep, lv.shared_medium, lv.chromatic, lv.racy), (0.25, true, true, false));
    assert_eq!(HalfAngleSettings::default(), HalfAngleSettings { slice_step: None, light_buffer_size: 256 });
    // The slice step follows render.step unless given.
    let scene = scene_from_toml_str(&format!("{MINIMAL}[render]\nstep = 0.75\n"), Path::new(""), "t", &[]).unwrap();
    assert_eq!(scene.settings.get::<HalfAngleSettings>().slice_step_voxels(&scene), 0.75);
}

#[test]
fn all_keys_example_names_every_technique_key_at_its_default() {
    let text = std::fs::read_to_string(scenes_dir().join("all-keys.toml")).unwrap();
    let keys = [
        known_keys::<IpsviSettings>(),
        known_keys::<LightVolumeSettings>(),
        known_keys::<HalfAngleSettings>(),
        known_keys::<AoSettings>(),
    ];
    for key in keys.concat() {
        assert!(text.contains(&format!("{key} = ")), "all-keys.toml does not show `{key}`");
    }
    assert_eq!(example("all-keys.toml", &[]).settings, TechniqueSettings::default());
    // The technique tables are the declarations' reference, as `sweeplab keys` prints it.
    let marker = "by `sweeplab keys`; tests/scene_files.rs keeps them equal.\n";
    let written = &text[text.find(marker).expect("all-keys.toml names where its tables come from") + marker.len()..];
    assert!(
        written == sweeplab::techniques::CATALOGUE.documented_tables(),
        "all-keys.toml's technique tables differ from the declared keys: run \
         `sweeplab keys` and put its output after the marker line"
    );
}

#[test]
fn technique_tables_are_read_into_typed_settings() {
    let s = settings_of(
        "[ipsvi]\nline_width = 4\ncache_size = 128\npiecewise = false\nread_fronts = \"per-texel\"\nearly_termination = \"exit-points\"\n\
         albedo = 0.5\ncone_angle = 30\nzone_blend = 4.5\nlight_step = 0.125\nert_scale = 2\nsync = \"events\"\n\
         cache_update = \"light-rays\"\ncache_write = \"racy\"\nwrite_value = \"sample\"\nmerge_sweeps = true\n\
         write_rule = \"every-sample\"\nempty_runs_move_depth = true\npacked_store = true\nfit_to_visible = true\nwrite_pass = \"texel\"\n\
         line_kernel = \"segmented\"\nsegments = 4\ntexel_segments = 2\nsegment_rounds = 2\n\
         [lightvolume]\nscale = 4\ncoherent = false\ncompensated = false\ncost_estimate = \"selective\"\n\
         max_passes_per_frame = 3\npass_lights = 8\nrebase_tolerance = 1e-3\nsubstep = 0.5\nshared_medium = false\n\
         chromatic = false\nracy = true\n[half_angle]\nslice_step = 0.25\nlight_buffer_size = 64\n[ao]\nradius = 4\nclusters = 64\n",
        &[],
    );
    let ipsvi = IpsviSettings {
        line_width: 4,
        cache_size: 128,
        piecewise: false,
        read_fronts: ReadFronts::PerTexel,
        early_termination: EarlyTermination::ExitPoints,
        albedo: 0.5,
        cone_angle_deg: 30.0,
        zone_blend_px: 4.5,
        light_step_voxels: 0.125,
        ert_scale: 2,
        cache_update: CacheUpdate::LightRays,
        cache_write: CacheWrite::Racy,
        write_value: WriteValue::Sample,
        write_rule: WriteRule::EverySample,
        empty_runs_move_depth: true,
        write_pass: WritePass::Texel,
        packed_store: true,
        fit_to_visible: true,
        sync: SyncStrategy::Events,
        merge_sweeps: true,
        line_kernel: sweeplab::techniques::ipsvi::LineKernel::Segmented,
        segments: 4,
        texel_segments: 2,
        segment_rounds: 2,
    };
    let lightvolume = LightVolumeSettings {
        scale: 4,
        coherent: false,
        compensated: false,
        cost_estimate: CostEstimate::Selective,
        max_passes_per_frame: 3,
        pass_lights: 8,
        rebase_tolerance: 1e-3,
        substep: 0.5,
        shared_medium: false,
        chromatic: false,
        racy: true,
    };
    let half_angle = HalfAngleSettings { slice_step: Some(0.25), light_buffer_size: 64 };
    let ao = AoSettings { radius: 4, clusters: 64, ..AoSettings::default() };
    let mut expected = TechniqueSettings::default();
    expected.set(ipsvi);
    expected.set(lightvolume);
    expected.set(half_angle);
    expected.set(ao);
    assert_eq!(s, expected);
    // early_termination also takes true (plain) and false (off).
    for (value, expected) in
        [("true", EarlyTermination::Plain), ("false", EarlyTermination::Off), ("\"off\"", EarlyTermination::Off)]
    {
        let s = settings_of(&format!("[ipsvi]\nearly_termination = {value}\n"), &[]);
        assert_eq!(s.get::<IpsviSettings>().early_termination, expected, "{value}");
    }
    // --set edits the same table before it is read.
    let s = settings_of("[ipsvi]\nline_width = 2\n", &["ipsvi.line_width=8", "half_angle.slice_step=0.5"]);
    assert_eq!((s.get::<IpsviSettings>().line_width, s.get::<HalfAngleSettings>().slice_step), (8, Some(0.5)));
}

#[test]
fn unknown_technique_keys_are_errors_suggesting_the_nearest() {
    let e = error_of(&format!("{MINIMAL}[ipsvi]\ncone_angel = 20\n"), &[]);
    assert_mentions(&e, &["test.toml", "ipsvi.cone_angel", "did you mean `cone_angle`?", "line_width, cache_size"]);
    // From the command line: the same parser, the same message.
    let e = error_of(MINIMAL, &["ipsvi.cone_angel=20"]);
    assert_mentions(&e, &["test.toml", "ipsvi.cone_angel", "did you mean `cone_angle`?"]);
    let e = error_of(&format!("{MINIMAL}[half_angle]\nslice_stp = 1\n"), &[]);
    assert_mentions(&e, &["half_angle.slice_stp", "did you mean `slice_step`?", "light_buffer_size"]);
    // Nothing near: the known keys only.
    let e = error_of(&format!("{MINIMAL}[lightvolume]\nalbedo = 1\n"), &[]);
    assert_mentions(&e, &["lightvolume.albedo", "the known keys are scale, coherent"]);
    assert!(!e.contains("did you mean"), "{e}");
    // A code-only field is not a key.
    let e = error_of(&format!("{MINIMAL}[ipsvi]\nsingle_dispatch_baseline = true\n"), &[]);
    assert_mentions(&e, &["unknown key ipsvi.single_dispatch_baseline"]);
}

#[test]
fn unknown_tables_are_errors_naming_them() {
    let e = error_of(&format!("{MINIMAL}[occlusion]\nradius = 8\n"), &[]);
    assert_mentions(&e, &["test.toml", "`occlusion`", "not a known table", "[ipsvi] [half_angle] [lightvolume] [ao]"]);
    let e = error_of(&format!("{MINIMAL}[ipsvvi]\nline_width = 2\n"), &[]);
    assert_mentions(&e, &["`ipsvvi`", "did you mean [ipsvi]?"]);
    let e = error_of(MINIMAL, &["lightvolumes.scale=2"]);
    assert_mentions(&e, &["`lightvolumes`", "did you mean [lightvolume]?"]);
    let e = error_of(&format!("{MINIMAL}ipsvi = 2\n"), &[]);
    assert_mentions(&e, &["`ipsvi`"]);
}

#[test]
fn technique_values_out_of_range_name_key_value_and_range() {
    let cases: &[(&str, &str)] = &[
        ("[ipsvi]\nline_width = 99", "ipsvi.line_width = 99: must be a whole number in 1..=32"),
        ("[ipsvi]\ncache_size = 8", "ipsvi.cache_size = 8: must be 0 (auto) or a whole number in 16..=4096"),
        (
            "[ipsvi]\ncache_size = -5",
            "ipsvi.cache_size: must be 0 (auto) or a whole number in 16..=4096, not the integer `-5`",
        ),
        ("[ipsvi]\nalbedo = 1.5", "ipsvi.albedo = 1.5: must be in 0..=1"),
        ("[ipsvi]\ncone_angle = 90", "ipsvi.cone_angle = 90: must be in 0..=80"),
        ("[ipsvi]\nzone_blend = -1", "ipsvi.zone_blend = -1: must be in 0..=64"),
        ("[ipsvi]\nlight_step = nan", "ipsvi.light_step = NaN: must be in 0.01..=16"),
        ("[ipsvi]\nert_scale = 0", "ipsvi.ert_scale = 0: must be a whole number in 1..=16"),
        (
            "[ipsvi]\nline_kernel = \"segmented\"\nsegments = 3",
            "ipsvi.segments = 3: must be 0, 1, 2, 4, 8, 16, 32, 64 or 128",
        ),
        ("[lightvolume]\nscale = 3", "lightvolume.scale = 3: must be 1, 2 or 4"),
        ("[lightvolume]\npass_lights = 65", "lightvolume.pass_lights = 65: must be a whole number in 1..=64"),
        ("[lightvolume]\nrebase_tolerance = 0.0", "lightvolume.rebase_tolerance = 0: must be finite and > 0"),
        ("[lightvolume]\nsubstep = 0.01", "lightvolume.substep = 0.01: must be in 0.05..=4"),
        ("[half_angle]\nslice_step = 20", "half_angle.slice_step = 20: must be in 0.01..=16"),
        (
            "[half_angle]\nlight_buffer_size = 8",
            "half_angle.light_buffer_size = 8: must be a whole number in 16..=4096",
        ),
    ];
    for (table, message) in cases {
        let e = error_of(&format!("{MINIMAL}{table}\n"), &[]);
        assert_mentions(&e, &["test.toml", message]);
    }
    // The cache modes: a typo gets a suggestion; scattering needs light rays.
    let e = error_of(&format!("{MINIMAL}[ipsvi]\ncache_update = \"view-sample\"\n"), &[]);
    assert_mentions(&e, &["cache_update", "did you mean `view-samples`"]);
    let e = error_of(&format!("{MINIMAL}[ipsvi]\ncache_write = \"farest\"\n"), &[]);
    assert_mentions(&e, &["cache_write", "did you mean `farthest`"]);
    let e = error_of(&format!("{MINIMAL}[render]\nfilter = \"gpu-8-bit\"\n"), &[]);
    assert_mentions(&e, &["render.filter", "did you mean `gpu-8bit`"]);
    let e = error_of(&format!("{MINIMAL}[ipsvi]\nalbedo = 0.5\n"), &[]);
    assert_mentions(&e, &["ipsvi.albedo = 0.5 needs ipsvi.cache_update = \"light-rays\""]);
    // The texel write pass computes a write without its sample: it refuses
    // what would need one, naming the setting.
    let e = error_of(&format!("{MINIMAL}[ipsvi]\nwrite_pass = \"texels\"\n"), &[]);
    assert_mentions(&e, &["ipsvi.write_pass", "did you mean `texel`"]);
    let refused = [
        ("write_value = \"sample\"", "ipsvi.write_pass = \"texel\" needs ipsvi.write_value = \"texel-ray\""),
        ("piecewise = false", "needs ipsvi.piecewise = true"),
        ("cache_write = \"racy\"", "needs ipsvi.cache_write = \"farthest\" or \"nearest\""),
        ("write_rule = \"every-sample\"\nempty_runs_move_depth = true", "needs ipsvi.empty_runs_move_depth = false"),
    ];
    for (setting, message) in refused {
        let e = error_of(&format!("{MINIMAL}[ipsvi]\nwrite_pass = \"texel\"\n{setting}\n"), &[]);
        assert_mentions(&e, &[message]);
    }
    // Light rays have no view-sample writes: the key is then without effect, as cache_write is.
    assert!(parse_scene_str(
        &format!("{MINIMAL}[ipsvi]\nwrite_pass = \"texel\"\ncache_update = \"light-rays\"\npiecewise = false\n"),
        Path::new(""),
        "t",
        &[]
    )
    .is_ok());
    // Wrong types and unknown names name the key too.
    let cases: &[(&str, &[&str])] = &[
        ("[ipsvi]\nline_width = \"wide\"", &["ipsvi.line_width", "a whole number in 1..=32", "\"wide\""]),
        ("[ipsvi]\nearly_termination = \"sometimes\"", &["ipsvi.early_termination", "sometimes", "exit-points"]),
        ("[ipsvi]\nsync = \"fences\"", &["ipsvi.sync", "fences", "barrier-global"]),
        ("[ipsvi]\nmerge_sweeps = \"yes\"", &["ipsvi.merge_sweeps", "invalid type"]),
        ("[lightvolume]\ncost_estimate = \"cheap\"", &["lightvolume.cost_estimate", "cheap", "passes"]),
        ("[lightvolume]\ncoherent = 1", &["lightvolume.coherent", "invalid type"]),
    ];
    for (table, parts) in cases {
        assert_mentions(&error_of(&format!("{MINIMAL}{table}\n"), &[]), parts);
    }
}

#[test]
fn reference_chromatic_parses_and_is_refused_with_model_ii() {
    let spec = parse_scene_str(&format!("{MINIMAL}[reference]\nchromatic = true\n"), Path::new(""), "t", &[]).unwrap();
    assert!(spec.build().unwrap().reference.chromatic);
    let message = error_of(&format!("{MINIMAL}[reference]\nmodel = \"emissive-scattering\"\nchromatic = true\n"), &[]);
    assert_mentions(&message, &["reference.chromatic", "single-scattering"]);
    assert_mentions(&error_of(MINIMAL, &["reference.chromatic=yes"]), &["chromatic"]);
}
