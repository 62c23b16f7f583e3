//! Compiles every `glsl/*.comp` to SPIR-V with shaderc (Debian's static libraries)
//! and embeds the words through `$OUT_DIR/shaders.rs`.
//!
//! Shaders share code through `#include "file.glsl"` resolved in `glsl/`; variants
//! come from specialization constants, so each `.comp` file is compiled once. The
//! one exception is [`BINDING_VARIANTS`]: which images a shader *statically uses*
//! is what synchronization validation checks, and a specialization constant
//! cannot remove a binding from the SPIR-V, so the two sides of a ping-pong pair
//! are compiled from the same file with a `PARITY` define.
//!
//! Each shader's interface is reflected from its SPIR-V (tools/spirv_reflect.rs)
//! into a module `shaders::<stem>`: one `Binding` const per descriptor binding,
//! named after the GLSL variable, the `ShaderInterface` pipelines are created
//! from, and `layout::<STRUCT>` with the std140/std430 member offsets that
//! `assert_gpu_layout!` compares with the Rust mirrors. The GLSL is the one
//! source of truth: a renamed or removed binding is a compile error where Rust
//! names it. Every shader also gets `EARLY_TERMINATION_TRANSMITTANCE` defined
//! from src/render/early_termination.rs, the constant every renderer shares.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};

#[path = "src/render/early_termination.rs"]
mod early_termination;
#[path = "tools/spirv_reflect.rs"]
mod spirv_reflect;
#[path = "tools/spirv_strip.rs"]
mod spirv_strip;

use spirv_reflect::{merge, reflect, Interface};
use spirv_strip::strip_source_debug;

/// Static archives that Debian's `libshaderc_combined.a` leaves unresolved.
const GLSLANG_SPIRV_ARCHIVES: &[&str] = &[
    "glslang",
    "MachineIndependent",
    "GenericCodeGen",
    "OSDependent",
    "OGLCompiler",
    "SPIRV",
    "glslang-default-resource-limits",
    "SPIRV-Tools-opt",
    "SPIRV-Tools",
];

/// (shader stem, [(constant suffix, defines)]): extra compilations of one file.
/// PARITY=0 reads the a side of its ping-pong pair and writes b; PARITY=1 the
/// opposite. Only those bindings are referenced, so each dispatch shows
/// validation exactly what it reads and writes.
const BINDING_VARIANTS: &[(&str, &[(&str, &str)])] = &[
    ("ipsvi_ert_sweep", &[("_READ_A", "0"), ("_READ_B", "1")]),
    ("probe_parity", &[("_READ_A", "0"), ("_READ_B", "1")]),
];

fn main() {
    link_debian_glslang();
    compile_shaders();
    embed_git_commit();
}

/// `SWEEPLAB_GIT_COMMIT` for bench reports: the commit this build comes from,
/// `-dirty` where the files the build reads (src, glsl, build.rs, the
/// manifest) differed from it at build time; `unknown` without git.
///
/// The script reruns when HEAD moves (a commit, a checkout) or one of those
/// files changes (the crate recompiles then anyway), never on the index alone:
/// `git status` and `git add` rewrite it, and a rerun rebuilds the library and
/// every test, which a `git status` must not cost.
fn embed_git_commit() {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let commit = match git(&["rev-parse", "--short=12", "HEAD"]) {
        Some(hash) => {
            let status = [&["status", "--porcelain", "--untracked-files=no", "--"][..], BUILD_INPUTS].concat();
            let dirty = git(&status).is_some_and(|s| !s.is_empty());
            if dirty {
                format!("{hash}-dirty")
            } else {
                hash
            }
        }
        None => "unknown".to_string(),
    };
    println!("cargo:rustc-env=SWEEPLAB_GIT_COMMIT={commit}");
    // A commit moves the branch (a loose ref, or packed-refs), a checkout
    // HEAD; in a worktree they live under the common git directory, which
    // rev-parse names. Only files that exist: cargo reruns on a missing one.
    let branch = git(&["rev-parse", "--symbolic-full-name", "HEAD"]).unwrap_or_default();
    for path in ["HEAD", branch.as_str(), "packed-refs"].into_iter().filter(|p| !p.is_empty()) {
        if let Some(p) = git(&["rev-parse", "--git-path", path]).filter(|p| Path::new(p).exists()) {
            println!("cargo:rerun-if-changed={p}");
        }
    }
    for path in BUILD_INPUTS {
        println!("cargo:rerun-if-changed={path}");
    }
}

/// What the build reads from the tree, for `-dirty`: a change elsewhere
/// (tests, docs, tools) does not change the binary.
const BUILD_INPUTS: &[&str] = &["src", "glsl", "build.rs", "Cargo.toml", "Cargo.lock"];

fn link_debian_glslang() {
    println!("cargo:rerun-if-env-changed=SHADERC_LIB_DIR");
    let dir = env::var("SHADERC_LIB_DIR").unwrap_or_else(|_| "/usr/lib/x86_64-linux-gnu".to_string());
    let mut missing = Vec::new();
    for name in ["shaderc_combined"].iter().chain(GLSLANG_SPIRV_ARCHIVES) {
        let path = Path::new(&dir).join(format!("lib{name}.a"));
        if !path.exists() {
            missing.push(path.display().to_string());
        }
    }
    if !missing.is_empty() {
        panic!(
            "static shaderc/glslang/SPIRV-Tools archives missing: {}\n\
             install them with: apt-get install libshaderc-dev glslang-dev spirv-tools\n\
             (or run tools/setup.sh); sweeplab never builds shaderc from source.",
            missing.join(", ")
        );
    }
    // The archives themselves are linked by .cargo/config.toml rustflags: they
    // are needed by this build script, which build.rs link args cannot reach.
}

fn compile_shaders() {
    let glsl_dir = PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap()).join("glsl");
    let out_dir = PathBuf::from(env::var("OUT_DIR").unwrap());
    println!("cargo:rerun-if-changed={}", glsl_dir.display());
    println!("cargo:rerun-if-changed=src/render/early_termination.rs");
    println!("cargo:rerun-if-changed=tools/spirv_reflect.rs");
    println!("cargo:rerun-if-changed=tools/spirv_strip.rs");

    let compiler = shaderc::Compiler::new().expect("shaderc compiler");
    let mut entries: Vec<PathBuf> =
        fs::read_dir(&glsl_dir).expect("glsl/ directory").map(|e| e.expect("glsl entry").path()).collect();
    entries.sort();

    // Debug formatting round-trips the f32 exactly, and is a valid GLSL float literal.
    let termination = format!("{:?}", early_termination::EARLY_TERMINATION_TRANSMITTANCE as f32);
    let mut index = String::from("// Generated by build.rs: every glsl/*.comp, its SPIR-V and its interface.\n");
    for path in &entries {
        println!("cargo:rerun-if-changed={}", path.display());
        if path.extension().and_then(|e| e.to_str()) != Some("comp") {
            continue;
        }
        let stem = path.file_stem().unwrap().to_str().unwrap().to_string();
        let source = fs::read_to_string(path).expect("read shader");
        let variants: Vec<(String, Option<&str>)> = match BINDING_VARIANTS.iter().find(|(s, _)| *s == stem) {
            Some((_, list)) => list.iter().map(|(suffix, parity)| (format!("{stem}{suffix}"), Some(*parity))).collect(),
            None => vec![(stem.clone(), None)],
        };
        let mut builds: Vec<(PathBuf, Interface)> = Vec::new();
        for (name, parity) in variants {
            let mut options = shaderc::CompileOptions::new().unwrap();
            // SPIR-V 1.6: the local size is an execution mode (LocalSizeId), not the
            // deprecated WorkgroupSize built-in; the device enables maintenance4 for it.
            options.set_target_env(shaderc::TargetEnv::Vulkan, shaderc::EnvVersion::Vulkan1_3 as u32);
            options.set_target_spirv(shaderc::SpirvVersion::V1_6);
            options.set_warnings_as_errors();
            options.set_optimization_level(shaderc::OptimizationLevel::Performance);
            options.set_generate_debug_info();
            options.add_macro_definition("EARLY_TERMINATION_TRANSMITTANCE", Some(&termination));
            if let Some(p) = parity {
                options.add_macro_definition("PARITY", Some(p));
            }
            let include_dir = glsl_dir.clone();
            options.set_include_callback(move |name, _kind, _from, _depth| {
                let p = include_dir.join(name);
                fs::read_to_string(&p)
                    .map(|content| shaderc::ResolvedInclude { resolved_name: p.display().to_string(), content })
                    .map_err(|e| format!("cannot include {}: {e}", p.display()))
            });
            let artifact = compiler
                .compile_into_spirv(
                    &source,
                    shaderc::ShaderKind::Compute,
                    &path.display().to_string(),
                    "main",
                    Some(&options),
                )
                .unwrap_or_else(|e| panic!("shader {} failed to compile:\n{e}", path.display()));
            let spv_path = out_dir.join(format!("{name}.spv"));
            let spirv = strip_source_debug(&name, artifact.as_binary_u8());
            fs::write(&spv_path, &spirv).expect("write spv");
            builds.push((spv_path, reflect(&name, &spirv)));
        }
        let interfaces: Vec<Interface> = builds.iter().map(|(_, i)| i.clone()).collect();
        let paths: Vec<&Path> = builds.iter().map(|(p, _)| p.as_path()).collect();
        index.push_str(&shader_module(&stem, &paths, &merge(&stem, &interfaces)));
    }
    fs::write(out_dir.join("shaders.rs"), index).expect("write shaders.rs");
}

/// `TransferLut` -> `TRANSFER_LUT`, `volume_tex` -> `VOLUME_TEX`.
fn const_name(name: &str) -> String {
    let mut out = String::new();
    let mut previous_lower = false;
    for c in name.chars() {
        if c.is_ascii_uppercase() && previous_lower {
            out.push('_');
        }
        previous_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        out.push(c.to_ascii_uppercase());
    }
    out
}

/// The generated module of one shader: its bindings, interface and struct layouts.
fn shader_module(stem: &str, spirv: &[&Path], interface: &Interface) -> String {
    let mut names: Vec<String> = Vec::new();
    let mut set1_names: Vec<String> = Vec::new();
    let mut bindings = String::new();
    for (set, list) in [(0, &interface.bindings), (1, &interface.set1)] {
        for b in list {
            let name = const_name(&b.name);
            assert!(!names.contains(&name) && !set1_names.contains(&name), "{stem}: two bindings are named {name}");
            bindings.push_str(&format!(
                "    /// `{}`: binding {} of set {set}.\n    pub const {name}: Binding = Binding {{ name: \"{}\", index: {}, kind: BindingKind::{} }};\n",
                b.name, b.index, b.name, b.index, b.kind.rust_name()
            ));
            if set == 0 {
                names.push(name)
            } else {
                set1_names.push(name)
            }
        }
    }
    let builds: Vec<String> = spirv.iter().map(|p| format!("include_bytes!(\"{}\") as &[u8]", p.display())).collect();
    let mut layouts = String::new();
    // Blocks that only wrap a runtime array have no layout worth mirroring.
    for (name, layout) in interface.layouts.iter().filter(|(_, l)| l.size() > 0) {
        let members: Vec<String> = layout
            .members
            .iter()
            .map(|m| format!("Member {{ name: \"{}\", offset: {}, size: {} }}", m.name, m.offset, m.size))
            .collect();
        layouts.push_str(&format!(
            "        pub const {}: StructLayout = StructLayout {{ name: \"{name}\", size: {}, array_stride: {:?}, members: &[{}] }};\n",
            const_name(name),
            layout.size(),
            layout.array_stride,
            members.join(", ")
        ));
    }
    let builds = builds.join(", ");
    let binding_list = names.join(", ");
    let set1_list = set1_names.join(", ");
    let push_constant_bytes = interface.push_constant_bytes;
    format!(
        r#"
/// glsl/{stem}.comp
pub mod {stem} {{
    #[allow(unused_imports)]
    use crate::vk::descriptors::BindingKind;
    #[allow(unused_imports)]
    use crate::vk::interface::{{Binding, ShaderInterface}};

{bindings}
    pub const INTERFACE: ShaderInterface = ShaderInterface {{
        name: "{stem}",
        builds: &[{builds}],
        bindings: &[{binding_list}],
        set1: &[{set1_list}],
        push_constant_bytes: {push_constant_bytes},
    }};

    /// The explicitly laid out structs (std140/std430 offsets from the SPIR-V).
    pub mod layout {{
        #[allow(unused_imports)]
        use crate::vk::interface::{{Member, StructLayout}};
{layouts}    }}
}}
"#
    )
}
