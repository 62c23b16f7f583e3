//! Pipelines and descriptor sets are made from the interface build.rs reflects
//! from each shader's SPIR-V: a set that leaves a binding out, fills it with the
//! wrong kind of resource or names a binding the shader does not declare is an
//! error that names the binding, and a ping-pong shader is not made into a
//! single pipeline.

use crate::common;

use ash::vk;
use common::*;
use glam::Vec3;
use sweeplab::render::{GpuScene, OutputImage};
use sweeplab::shaders::{ipsvi_ert_depths, ipsvi_ert_sweep, ipsvi_line, raycast};
use sweeplab::vk::descriptors::Resource;
use sweeplab::vk::pipeline::{parity_pair, ComputePipeline, ComputePipelineDesc};
use sweeplab::vk::{Buffer, VkError};

#[test]
fn sets_are_checked_by_binding_name() {
    let ctx = validated_context();
    let scene = scene_with(sphere_volume(8, 3.0), vec![directional(Vec3::NEG_Y, 1.0)], 4, 4);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let frame = Buffer::with_data(&ctx, "frame", &[0u32; 64], vk::BufferUsageFlags::STORAGE_BUFFER).unwrap();
    let output = OutputImage::new(&ctx, "out", 4, 4).unwrap();
    let desc = ComputePipelineDesc { name: "dvr", shader: &raycast::INTERFACE, specialization: &[], max_sets: 4 };
    let mut pipeline = ComputePipeline::new(&ctx, &desc).unwrap();
    let scene_part = [
        (raycast::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
        (raycast::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
        (raycast::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
        (raycast::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
    ];

    let missing = pipeline.create_set(&scene_part).unwrap_err();
    assert!(matches!(missing, VkError::Binding { binding: "out_image", .. }), "{missing}");
    assert_eq!(missing.to_string(), "shader raycast: binding out_image (index 4) has no resource");

    let wrong_kind = pipeline
        .create_set(&[&scene_part[..], &[(raycast::OUT_IMAGE, Resource::StorageBuffer(&gpu.lut))]].concat())
        .unwrap_err();
    assert_eq!(
        wrong_kind.to_string(),
        "shader raycast: binding out_image is a StorageImage binding, given a StorageBuffer"
    );

    // The pre-pass's `depths` sits at index 3, where the ray caster has its lights.
    let foreign = pipeline
        .create_set(
            &[
                &scene_part[..3],
                &[
                    (ipsvi_ert_depths::DEPTHS, Resource::StorageImage(&output.image)),
                    (raycast::OUT_IMAGE, Resource::StorageImage(&output.image)),
                ],
            ]
            .concat(),
        )
        .unwrap_err();
    assert_eq!(
        foreign.to_string(),
        "shader raycast: binding depths (index 3) is not declared by this shader: its binding 3 is Lights"
    );

    // Complete: the output and the view-chunk state it ping-pongs with.
    let complete = [
        (raycast::OUT_IMAGE, Resource::StorageImage(&output.image)),
        (raycast::STATE_IN, Resource::StorageImage(&output.image)),
    ];
    pipeline.create_set(&[&scene_part[..], &complete[..]].concat()).unwrap();
    drop(pipeline);
    drop(gpu);
    assert_validation_clean(&ctx);
}

#[test]
fn the_number_of_builds_picks_the_constructor() {
    let ctx = validated_context();
    let pair = ComputePipelineDesc {
        name: "ipsvi_ert_sweep",
        shader: &ipsvi_ert_sweep::INTERFACE,
        specialization: &[],
        max_sets: 1,
    };
    let single = ComputePipeline::new(&ctx, &pair).err().expect("a ping-pong shader is two pipelines");
    assert_eq!(
        single.to_string(),
        "shader ipsvi_ert_sweep: has 2 builds, a ping-pong pair: create its pipelines with parity_pair"
    );
    let once = ComputePipelineDesc { name: "dvr", shader: &raycast::INTERFACE, specialization: &[], max_sets: 1 };
    let pair_of_one = parity_pair(&ctx, &once).err().expect("a shader compiled once has no pair");
    assert_eq!(pair_of_one.to_string(), "shader raycast: has 1 build(s), not the two of a ping-pong pair");
    let [read_a, read_b] = parity_pair(&ctx, &pair).unwrap();
    assert_eq!(read_a.bindings, read_b.bindings);
    assert_eq!(read_a.push_constant_bytes, read_b.push_constant_bytes);
    drop((read_a, read_b));
    assert_validation_clean(&ctx);
}

/// A ping-pong shader of one build declares its pair in set 1 (issue 24: one
/// pipeline, the side bound per block): reads and writes on separate
/// bindings, so synchronization validation still sees which image a block
/// reads and which it writes. A shader without set 1 refuses a set-1 set.
#[test]
fn ping_pong_pairs_are_a_set_1_of_separate_read_and_write_bindings() {
    let names = |b: &[sweeplab::vk::interface::Binding]| b.iter().map(|b| b.name).collect::<Vec<_>>();
    assert_eq!(ipsvi_line::INTERFACE.builds.len(), 1);
    assert_eq!(
        names(ipsvi_line::INTERFACE.set1),
        [
            "cache_in",
            "front_in",
            "cache_out",
            "front_out",
            "samples_in",
            "stamps_in",
            "samples_out",
            "stamps_out",
            // ipsvi.packed_store: each pair in one image, still read and written apart.
            "history_in",
            "history_out",
            "packed_samples_in",
            "packed_samples_out"
        ]
    );
    assert_eq!(names(sweeplab::shaders::half_angle_slice::INTERFACE.set1), ["light_in", "light_out"]);
    assert_eq!(names(sweeplab::shaders::lightvolume_slice::INTERFACE.set1), ["slice_in", "slice_out"]);
    assert!(raycast::INTERFACE.set1.is_empty());
    let ctx = validated_context();
    let once = ComputePipelineDesc { name: "dvr", shader: &raycast::INTERFACE, specialization: &[], max_sets: 1 };
    let mut dvr = ComputePipeline::new(&ctx, &once).unwrap();
    assert_eq!(dvr.create_set1(&[]).unwrap_err().to_string(), "shader raycast: has no set 1");
    drop(dvr);
    assert_validation_clean(&ctx);
}

/// build.rs drops the source text, file names and line numbers from every
/// build (tools/spirv_strip.rs): each pipeline creation parses the whole
/// module, in lavapipe and again in the validation layer. The names stay
/// (reflection and validation messages use them), and the words still form
/// whole instructions.
#[test]
fn shaders_keep_their_names_and_leave_out_source_text_and_lines() {
    const OP_NAME: u32 = 5;
    let source_debug = [2, 3, 4, 7, 8, 317, 330]; // OpSourceContinued .. OpModuleProcessed
    let interfaces = [
        &ipsvi_line::INTERFACE,
        &raycast::INTERFACE,
        &ipsvi_ert_sweep::INTERFACE,
        &sweeplab::shaders::half_angle_slice::INTERFACE,
    ];
    for interface in interfaces {
        for spirv in interface.builds {
            let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
            assert_eq!(words[0], 0x0723_0203, "{}: not SPIR-V", interface.name);
            let (mut at, mut names) = (5, 0);
            while at < words.len() {
                let (count, opcode) = ((words[at] >> 16) as usize, words[at] & 0xffff);
                assert!(count > 0 && at + count <= words.len(), "{}: broken instruction at word {at}", interface.name);
                assert!(!source_debug.contains(&opcode), "{}: opcode {opcode} at word {at}", interface.name);
                names += (opcode == OP_NAME) as usize;
                at += count;
            }
            assert!(names > 0, "{}: no OpName left", interface.name);
        }
    }
}
