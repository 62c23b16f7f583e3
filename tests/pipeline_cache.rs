//! The driver's pipeline cache on disk and the context's reuse of pipelines
//! and descriptor pools: a second context loads what the first saved; a
//! corrupt file and a header of another device are ignored with a note; the
//! same pipeline asked for twice is compiled once.

use sweeplab::shaders::raycast;
use sweeplab::vk::pipeline_cache::{self, CacheDevice, PipelineCacheDir};
use sweeplab::vk::{ComputePipeline, ComputePipelineDesc, Context, ContextOptions};

fn context(dir: &std::path::Path) -> Context {
    Context::new(&ContextOptions {
        device: std::env::var("SWEEPLAB_DEVICE").ok(),
        validate: true,
        pipeline_cache: PipelineCacheDir::At(dir.to_path_buf()),
        ..Default::default()
    })
    .expect("Vulkan context with validation")
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sweeplab-pipeline-cache-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn dvr_pipeline(ctx: &Context) -> ComputePipeline {
    let desc = ComputePipelineDesc { name: "dvr", shader: &raycast::INTERFACE, specialization: &[(0, 0)], max_sets: 1 };
    ComputePipeline::new(ctx, &desc).unwrap()
}

fn assert_clean(ctx: &Context) {
    let m = ctx.take_validation_messages();
    assert!(m.is_empty(), "{}", m.join("\n"));
}

/// The one file the first context of `dir` saved.
fn saved_file(dir: &std::path::Path) -> std::path::PathBuf {
    let files: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    assert_eq!(files.len(), 1, "one file per device, no temporary left: {files:?}");
    files[0].clone()
}

#[test]
fn a_second_context_loads_the_cache_the_first_saved_and_pipelines_are_compiled_once() {
    let dir = temp_dir("load");
    {
        let ctx = context(&dir);
        assert_eq!(ctx.pipeline_cache.loaded_bytes, 0, "no file yet");
        let (a, b) = (dvr_pipeline(&ctx), dvr_pipeline(&ctx));
        assert_eq!(a.raw, b.raw, "the same variant is one pipeline");
        let phong =
            ComputePipelineDesc { name: "phong", shader: &raycast::INTERFACE, specialization: &[(0, 1)], max_sets: 1 };
        let c = ComputePipeline::new(&ctx, &phong).unwrap();
        assert_ne!(a.raw, c.raw, "another specialization constant is another pipeline");
        let counts = ctx.creation_counts();
        assert_eq!((counts.pipelines, counts.pipelines_reused), (2, 1));
        assert_eq!(counts.descriptor_pools, 3, "one pool each while all three live: {counts:?}");
        drop((a, b, c));
        // Their pools went back to the shelf: the next of their shape takes one.
        let d = dvr_pipeline(&ctx);
        assert_eq!(ctx.creation_counts().descriptor_pools, 3, "a shelved pool is reused");
        drop(d);
        assert_clean(&ctx);
    }
    let file = saved_file(&dir);
    let ctx = context(&dir);
    // Everything the first saved (lavapipe's data is its 32-byte header alone:
    // it keeps compiled shaders in Mesa's own disk cache; a GPU driver's
    // holds the pipelines).
    let saved = std::fs::read(&file).unwrap().len() - 24;
    assert!(saved >= 32, "a header at least: {saved} bytes");
    assert_eq!(ctx.pipeline_cache.loaded_bytes, saved);
    assert_eq!(ctx.pipeline_cache.note, None);
    assert_eq!(ctx.pipeline_cache.path.as_deref(), Some(file.as_path()));
    drop(dvr_pipeline(&ctx));
    assert_clean(&ctx);
    drop(ctx);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_corrupt_file_and_a_header_of_another_device_are_ignored_with_a_note() {
    let dir = temp_dir("ignored");
    {
        let ctx = context(&dir);
        drop(dvr_pipeline(&ctx));
    }
    let file = saved_file(&dir);
    let good = std::fs::read(&file).unwrap();

    // One byte of the driver's data flipped: the checksum says so.
    let mut corrupt = good.clone();
    *corrupt.last_mut().unwrap() ^= 0x5a;
    std::fs::write(&file, &corrupt).unwrap();
    let ctx = context(&dir);
    assert_eq!(ctx.pipeline_cache.loaded_bytes, 0);
    let note = ctx.pipeline_cache.note.clone().unwrap_or_default();
    assert!(note.contains("corrupt"), "{note}");
    drop(dvr_pipeline(&ctx));
    assert_clean(&ctx);
    drop(ctx);
    assert_eq!(std::fs::read(&file).unwrap().len(), good.len(), "the next save replaced it");

    // The same data framed correctly but naming another device.
    let data = &good[24..];
    let le = |at: usize| u32::from_le_bytes(data[at..at + 4].try_into().unwrap());
    let this = CacheDevice { vendor_id: le(8), device_id: le(12), uuid: data[16..32].try_into().unwrap() };
    assert_eq!(pipeline_cache::check_header(data, &this), Ok(()), "the saved header names this device");
    let mut other = data.to_vec();
    other[12..16].copy_from_slice(&(this.device_id ^ 0xbeef).to_le_bytes());
    std::fs::write(&file, pipeline_cache::encode(&other)).unwrap();
    let ctx = context(&dir);
    assert_eq!(ctx.pipeline_cache.loaded_bytes, 0);
    let note = ctx.pipeline_cache.note.clone().unwrap_or_default();
    assert!(note.contains("written for device"), "{note}");
    assert_clean(&ctx);
    drop(ctx);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_empty_directory_setting_turns_the_cache_off() {
    let ctx = Context::new(&ContextOptions {
        device: std::env::var("SWEEPLAB_DEVICE").ok(),
        pipeline_cache: PipelineCacheDir::Off,
        ..Default::default()
    })
    .unwrap();
    assert_eq!(ctx.pipeline_cache.path, None);
    drop(dvr_pipeline(&ctx));
    assert_eq!(ctx.save_pipeline_cache().unwrap(), None);
}

/// Files of Mesa's on-disk shader cache under `xdg_cache` (one per compiled
/// shader variant; `index` is not one).
fn mesa_cache_entries(xdg_cache: &std::path::Path) -> usize {
    fn walk(dir: &std::path::Path) -> usize {
        let Ok(entries) = std::fs::read_dir(dir) else { return 0 };
        entries
            .map(|e| e.unwrap().path())
            .map(|p| if p.is_dir() { walk(&p) } else { usize::from(p.file_name().is_some_and(|n| n != "index")) })
            .sum()
    }
    walk(&xdg_cache.join("mesa_shader_cache"))
}

/// On lavapipe a frame compiles each of its pipelines once: a process with an
/// empty cache folder leaves as many compiled shaders in Mesa's shader cache
/// as the frame creates pipelines. Lavapipe (Mesa 22.3) folds the values of a
/// uniform block that steer a shader's branches and loops into a variant of
/// their own at the first dispatch after the block is bound, and compiles the
/// shader again without them at the next; so the frame parameters are read
/// from storage buffers (glsl/frame.glsl). Techniques of many dispatches per
/// frame, one pipeline each (half-angle) and two (IPSVI).
#[test]
fn a_frame_compiles_each_pipeline_once_on_lavapipe() {
    use crate::common::cli::temp_dir;
    use sweeplab::render::GpuScene;
    use sweeplab::techniques::{load_scene, render, Technique};
    let scene_file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/slab-under-sphere.toml");
    for (name, technique) in [("half-angle", Technique::HalfAngle), ("ipsvi", Technique::Ipsvi)] {
        // The pipelines the frame creates, counted by a context of its own.
        let ctx = crate::common::validated_context();
        if !ctx.info.name.contains("llvmpipe") {
            println!("{}: not lavapipe, nothing to check", ctx.info.name);
            return;
        }
        let scene = load_scene(&scene_file, &[]).unwrap();
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let mut profiler = sweeplab::vk::Profiler::new(&ctx, 4096).unwrap();
        render(&gpu, technique, 8, 8, &mut profiler).unwrap();
        let pipelines = ctx.creation_counts().pipelines as usize;
        crate::common::assert_validation_clean(&ctx);

        let dir = temp_dir(&format!("compiles-once-{name}"));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_sweeplab"))
            .args(["render", "--scene", scene_file.to_str().unwrap(), "--technique", name, "--size", "8x8", "--out"])
            .arg(dir.join("frame.png"))
            .env("XDG_CACHE_HOME", &dir)
            .env("SWEEPLAB_PIPELINE_CACHE", dir.join("pipelines"))
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let compiled = mesa_cache_entries(&dir);
        assert_eq!(compiled, pipelines, "{name}: {compiled} shaders compiled for {pipelines} pipelines");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
