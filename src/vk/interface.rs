//! A shader's interface as build.rs reflects it from the SPIR-V (`crate::shaders`):
//! descriptor bindings by name, the push-constant block's size, and the member
//! offsets of its explicitly laid out structs, which [`assert_gpu_layout!`]
//! compares with the Rust mirrors at compile time.

use super::descriptors::BindingKind;

/// One descriptor binding of set 0, named after its GLSL variable (or its
/// block's type name where the block has no instance name).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Binding {
    pub name: &'static str,
    pub index: u32,
    pub kind: BindingKind,
}

/// Everything a compute pipeline needs to know about its shader.
#[derive(Clone, Copy, Debug)]
pub struct ShaderInterface {
    /// The file stem in glsl/.
    pub name: &'static str,
    /// SPIR-V of each build: one, or the two sides of a ping-pong pair (build.rs
    /// `BINDING_VARIANTS`; index 0 is `PARITY` 0).
    pub builds: &'static [&'static [u8]],
    /// Every binding of set 0 any build declares, by index.
    pub bindings: &'static [Binding],
    /// Bindings of set 1, by index: empty but for the dispatch probe's
    /// small-set shader (pipelines of [`super::pipeline::ComputePipeline`]
    /// have set 0 only and refuse a shader with a set 1).
    pub set1: &'static [Binding],
    pub push_constant_bytes: u32,
}

/// One member of a reflected struct.
#[derive(Clone, Copy, Debug)]
pub struct Member {
    pub name: &'static str,
    pub offset: u32,
    /// Bytes the member spans (0 for a runtime array).
    pub size: u32,
}

/// A struct as the shader lays it out (std140 or std430, from the SPIR-V).
#[derive(Clone, Copy, Debug)]
pub struct StructLayout {
    pub name: &'static str,
    /// End of the last member.
    pub size: u32,
    /// Stride of an array of this struct, where the shader has one.
    pub array_stride: Option<u32>,
    pub members: &'static [Member],
}

const fn same_name(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

impl StructLayout {
    /// Offset of member `name`, or `None` when the struct has no such member.
    pub const fn offset_of(&self, name: &str) -> Option<usize> {
        let mut i = 0;
        while i < self.members.len() {
            if same_name(self.members[i].name, name) {
                return Some(self.members[i].offset as usize);
            }
            i += 1;
        }
        None
    }

    /// Bytes one element takes in an array, or the whole struct outside one.
    pub const fn rust_size(&self) -> usize {
        match self.array_stride {
            Some(stride) => stride as usize,
            None => self.size as usize,
        }
    }
}

/// Fails the build unless the `#[repr(C)]` struct `$rust` mirrors the shader's
/// reflected struct `$layout`: the listed fields are all the members, each at
/// the shader's offset under the same name, and the sizes agree (the array
/// stride where the shader reads an array of it).
///
/// ```
/// #[repr(C)]
/// struct ChunkPush {
///     first_sample: u32,
///     sample_count: u32,
///     is_first: u32,
///     is_last: u32,
/// }
/// sweeplab::assert_gpu_layout!(
///     ChunkPush,
///     sweeplab::shaders::reference::layout::CHUNK,
///     [first_sample, sample_count, is_first, is_last]
/// );
/// ```
///
/// Two fields swapped do not compile:
///
/// ```compile_fail
/// #[repr(C)]
/// struct ChunkPush {
///     sample_count: u32,
///     first_sample: u32,
///     is_first: u32,
///     is_last: u32,
/// }
/// sweeplab::assert_gpu_layout!(
///     ChunkPush,
///     sweeplab::shaders::reference::layout::CHUNK,
///     [first_sample, sample_count, is_first, is_last]
/// );
/// ```
///
/// Nor does a member left out (the sizes differ too):
///
/// ```compile_fail
/// #[repr(C)]
/// struct ChunkPush {
///     first_sample: u32,
///     sample_count: u32,
///     is_first: u32,
/// }
/// sweeplab::assert_gpu_layout!(ChunkPush, sweeplab::shaders::reference::layout::CHUNK, [first_sample, sample_count, is_first]);
/// ```
///
/// Nor a float where the shader has a vec4 (the next offset moves):
///
/// ```compile_fail
/// #[repr(C)]
/// struct LightRecord {
///     pos_type: f32,
///     spot_dir: [f32; 4],
///     radiance: [f32; 4],
///     params: [f32; 4],
/// }
/// sweeplab::assert_gpu_layout!(
///     LightRecord,
///     sweeplab::shaders::raycast::layout::LIGHT,
///     [pos_type, spot_dir, radiance, params]
/// );
/// ```
#[macro_export]
macro_rules! assert_gpu_layout {
    ($rust:ty, $layout:expr, [$($field:ident),+ $(,)?]) => {
        const _: () = {
            let layout: $crate::vk::interface::StructLayout = $layout;
            let fields: &[&str] = &[$(stringify!($field)),+];
            assert!(
                fields.len() == layout.members.len(),
                concat!(stringify!($rust), ": the field list does not name every member of the shader's struct")
            );
            $(
                assert!(
                    matches!(layout.offset_of(stringify!($field)), Some(o) if o == ::core::mem::offset_of!($rust, $field)),
                    concat!(stringify!($rust), ".", stringify!($field), ": no shader member of this name at this offset")
                );
            )+
            assert!(
                layout.rust_size() == ::core::mem::size_of::<$rust>(),
                concat!(stringify!($rust), ": size differs from the shader's struct (or its array stride)")
            );
        };
    };
}
