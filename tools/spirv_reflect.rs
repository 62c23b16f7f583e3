//! What a compiled compute shader declares, read from its SPIR-V words (build.rs
//! only): the descriptor bindings of set 0 (and of set 1, where a shader has a
//! second set) by name, the push-constant block's
//! size, and the member offsets of every explicitly laid out struct (uniform,
//! storage and push blocks and the structs inside them). Reads the handful of
//! instructions that carry this (OpName, OpMemberName, OpDecorate,
//! OpMemberDecorate, the type declarations, OpVariable); shaderc keeps the names
//! because build.rs compiles with debug info.

use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    UniformBuffer,
    StorageBuffer,
    StorageImage,
    SampledImage,
}

impl Kind {
    /// The variant of `crate::vk::descriptors::BindingKind`.
    pub fn rust_name(self) -> &'static str {
        match self {
            Kind::UniformBuffer => "UniformBuffer",
            Kind::StorageBuffer => "StorageBuffer",
            Kind::StorageImage => "StorageImage",
            Kind::SampledImage => "SampledImage",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Binding {
    /// The variable's name, or its block's type name for an unnamed block
    /// (`buffer Lights { ... };` is `Lights`).
    pub name: String,
    pub index: u32,
    pub kind: Kind,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Member {
    pub name: String,
    pub offset: u32,
    /// Bytes up to the end of the member (0 for a runtime array).
    pub size: u32,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StructLayout {
    pub members: Vec<Member>,
    /// Stride of an array of this struct, where the shader has one.
    pub array_stride: Option<u32>,
}

impl StructLayout {
    /// End of the last member.
    pub fn size(&self) -> u32 {
        self.members.iter().map(|m| m.offset + m.size).max().unwrap_or(0)
    }
}

#[derive(Clone, Debug, Default)]
pub struct Interface {
    pub bindings: Vec<Binding>,
    /// Bindings of set 1: a small set rebound per dispatch (the dispatch
    /// probe's small-set cases), beside set 0 bound once.
    pub set1: Vec<Binding>,
    pub push_constant_bytes: u32,
    /// By struct type name.
    pub layouts: BTreeMap<String, StructLayout>,
}

enum Type {
    Scalar(u32),
    Vector { component: u32, count: u32 },
    Array { element: u32, length: u32 },
    RuntimeArray { element: u32 },
    Struct(Vec<u32>),
    Image { storage: bool },
    SampledImage,
    Pointer { pointee: u32 },
    Other,
}

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_BOOL: u32 = 20;
const OP_TYPE_INT: u32 = 21;
const OP_TYPE_FLOAT: u32 = 22;
const OP_TYPE_VECTOR: u32 = 23;
const OP_TYPE_IMAGE: u32 = 25;
const OP_TYPE_SAMPLED_IMAGE: u32 = 27;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_RUNTIME_ARRAY: u32 = 29;
const OP_TYPE_STRUCT: u32 = 30;
const OP_TYPE_POINTER: u32 = 32;
const OP_CONSTANT: u32 = 43;
const OP_VARIABLE: u32 = 59;
const OP_DECORATE: u32 = 71;
const OP_MEMBER_DECORATE: u32 = 72;

const DECORATION_BLOCK: u32 = 2;
const DECORATION_BUFFER_BLOCK: u32 = 3;
const DECORATION_ARRAY_STRIDE: u32 = 6;
const DECORATION_BINDING: u32 = 33;
const DECORATION_DESCRIPTOR_SET: u32 = 34;
const DECORATION_OFFSET: u32 = 35;

const CLASS_UNIFORM_CONSTANT: u32 = 0;
const CLASS_UNIFORM: u32 = 2;
const CLASS_PUSH_CONSTANT: u32 = 9;
const CLASS_STORAGE_BUFFER: u32 = 12;

fn string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|b| *b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// The instructions of a module that describe its interface, by result id.
#[derive(Default)]
struct Module {
    shader: String,
    names: BTreeMap<u32, String>,
    member_names: BTreeMap<(u32, u32), String>,
    /// (id, decoration) -> its first literal: Binding, DescriptorSet, ArrayStride.
    decorations: BTreeMap<(u32, u32), u32>,
    /// (struct id, decoration): Block, BufferBlock.
    block_flags: Vec<(u32, u32)>,
    /// (struct id, member) -> Offset.
    offsets: BTreeMap<(u32, u32), u32>,
    types: BTreeMap<u32, Type>,
    constants: BTreeMap<u32, u32>,
    /// (pointer type, id, storage class).
    variables: Vec<(u32, u32, u32)>,
}

impl Module {
    fn parse(shader: &str, spirv: &[u8]) -> Module {
        assert!(spirv.len().is_multiple_of(4) && spirv.len() >= 20, "{shader}: not SPIR-V");
        let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        assert_eq!(words[0], 0x0723_0203, "{shader}: not SPIR-V (magic)");
        let mut m = Module { shader: shader.to_string(), ..Module::default() };
        let mut i = 5;
        while i < words.len() {
            let count = (words[i] >> 16) as usize;
            let op = words[i] & 0xffff;
            assert!(count > 0 && i + count <= words.len(), "{shader}: malformed SPIR-V");
            m.instruction(op, &words[i + 1..i + count]);
            i += count;
        }
        m
    }

    fn instruction(&mut self, op: u32, w: &[u32]) {
        let ty = match op {
            OP_NAME => {
                self.names.insert(w[0], string(&w[1..]));
                return;
            }
            OP_MEMBER_NAME => {
                self.member_names.insert((w[0], w[1]), string(&w[2..]));
                return;
            }
            OP_CONSTANT => {
                self.constants.insert(w[1], w[2]);
                return;
            }
            OP_VARIABLE => {
                self.variables.push((w[0], w[1], w[2]));
                return;
            }
            OP_DECORATE => {
                match w[1] {
                    DECORATION_BLOCK | DECORATION_BUFFER_BLOCK => self.block_flags.push((w[0], w[1])),
                    DECORATION_ARRAY_STRIDE | DECORATION_BINDING | DECORATION_DESCRIPTOR_SET => {
                        self.decorations.insert((w[0], w[1]), w[2]);
                    }
                    _ => {}
                }
                return;
            }
            OP_MEMBER_DECORATE => {
                if w[2] == DECORATION_OFFSET {
                    self.offsets.insert((w[0], w[1]), w[3]);
                }
                return;
            }
            OP_TYPE_BOOL => Type::Scalar(4),
            OP_TYPE_INT | OP_TYPE_FLOAT => Type::Scalar(w[1] / 8),
            OP_TYPE_VECTOR => Type::Vector { component: w[1], count: w[2] },
            OP_TYPE_IMAGE => Type::Image { storage: w[6] == 2 },
            OP_TYPE_SAMPLED_IMAGE => Type::SampledImage,
            OP_TYPE_ARRAY => Type::Array { element: w[1], length: w[2] },
            OP_TYPE_RUNTIME_ARRAY => Type::RuntimeArray { element: w[1] },
            OP_TYPE_STRUCT => Type::Struct(w[1..].to_vec()),
            OP_TYPE_POINTER => Type::Pointer { pointee: w[2] },
            // Matrices, samplers, opaque types: sized or bound nowhere here.
            _ if (OP_TYPE_BOOL..=OP_TYPE_POINTER).contains(&op) => Type::Other,
            _ => return,
        };
        self.types.insert(w[0], ty);
    }

    /// Bytes a value of type `t` spans in an explicitly laid out block.
    fn size_of(&self, t: u32) -> u32 {
        let shader = &self.shader;
        match self.types.get(&t) {
            Some(Type::Scalar(bytes)) => *bytes,
            Some(Type::Vector { component, count }) => count * self.size_of(*component),
            Some(Type::Array { length, .. }) => {
                let stride = self.decorations.get(&(t, DECORATION_ARRAY_STRIDE));
                let stride = stride.unwrap_or_else(|| panic!("{shader}: array without ArrayStride"));
                let length = self.constants.get(length);
                stride * length.unwrap_or_else(|| panic!("{shader}: array length is not a constant"))
            }
            Some(Type::RuntimeArray { .. }) => 0,
            Some(Type::Struct(members)) => members
                .iter()
                .enumerate()
                .map(|(m, mt)| self.offsets.get(&(t, m as u32)).copied().unwrap_or(0) + self.size_of(*mt))
                .max()
                .unwrap_or(0),
            _ => panic!("{shader}: a block member of a type build.rs cannot size (matrix or opaque)"),
        }
    }

    /// A descriptor's name: the variable's, or its block type's for an unnamed block.
    fn binding_name(&self, id: u32, pointee: u32, index: u32) -> String {
        match self.names.get(&id).filter(|n| !n.is_empty()) {
            Some(n) => n.clone(),
            None => self
                .names
                .get(&pointee)
                .cloned()
                .unwrap_or_else(|| panic!("{}: binding {index} has no name", self.shader)),
        }
    }

    fn interface(&self) -> Interface {
        let shader = &self.shader;
        let mut interface = Interface::default();
        for &(pointer, id, class) in &self.variables {
            let Some(Type::Pointer { pointee }) = self.types.get(&pointer) else { continue };
            let pointee = *pointee;
            if class == CLASS_PUSH_CONSTANT {
                interface.push_constant_bytes = self.size_of(pointee);
                continue;
            }
            let is_buffer_block = self.block_flags.contains(&(pointee, DECORATION_BUFFER_BLOCK));
            let kind = match (class, self.types.get(&pointee)) {
                (CLASS_UNIFORM_CONSTANT, Some(Type::Image { storage: true })) => Kind::StorageImage,
                (CLASS_UNIFORM_CONSTANT, Some(Type::SampledImage)) => Kind::SampledImage,
                (CLASS_UNIFORM, Some(Type::Struct(_))) if is_buffer_block => Kind::StorageBuffer,
                (CLASS_UNIFORM, Some(Type::Struct(_))) => Kind::UniformBuffer,
                (CLASS_STORAGE_BUFFER, Some(Type::Struct(_))) => Kind::StorageBuffer,
                (CLASS_UNIFORM_CONSTANT | CLASS_UNIFORM | CLASS_STORAGE_BUFFER, _) => panic!(
                    "{shader}: descriptor {id} is of a kind sweeplab does not bind (arrays of descriptors, separate samplers)"
                ),
                _ => continue,
            };
            let set = self.decorations.get(&(id, DECORATION_DESCRIPTOR_SET)).copied().unwrap_or(0);
            assert!(set <= 1, "{shader}: sweeplab's pipelines have at most two descriptor sets (set = 0, 1)");
            let index = self.decorations.get(&(id, DECORATION_BINDING));
            let index = *index.unwrap_or_else(|| panic!("{shader}: descriptor {id} has no binding decoration"));
            let binding = Binding { name: self.binding_name(id, pointee, index), index, kind };
            if set == 0 {
                interface.bindings.push(binding);
            } else {
                interface.set1.push(binding);
            }
        }
        interface.bindings.sort_by_key(|b| b.index);
        interface.set1.sort_by_key(|b| b.index);
        interface.layouts = self.layouts();
        interface
    }

    /// Every named struct with an Offset on each member, by name.
    fn layouts(&self) -> BTreeMap<String, StructLayout> {
        let mut strides: BTreeMap<u32, u32> = BTreeMap::new();
        for (t, ty) in &self.types {
            if let Type::Array { element, .. } | Type::RuntimeArray { element } = ty {
                if let Some(stride) = self.decorations.get(&(*t, DECORATION_ARRAY_STRIDE)) {
                    strides.insert(*element, *stride);
                }
            }
        }
        let mut layouts = BTreeMap::new();
        for (t, ty) in &self.types {
            let Type::Struct(members) = ty else { continue };
            let laid_out = (0..members.len() as u32).all(|m| self.offsets.contains_key(&(*t, m)));
            let Some(name) = self.names.get(t).filter(|n| !n.is_empty() && laid_out && !members.is_empty()) else {
                continue;
            };
            let layout = StructLayout {
                members: members
                    .iter()
                    .enumerate()
                    .map(|(m, mt)| Member {
                        name: self.member_names.get(&(*t, m as u32)).cloned().unwrap_or_default(),
                        offset: self.offsets[&(*t, m as u32)],
                        size: self.size_of(*mt),
                    })
                    .collect(),
                array_stride: strides.get(t).copied(),
            };
            if let Some(old) = layouts.get(name) {
                assert_eq!(old, &layout, "{}: struct {name} is laid out two ways (std140 and std430?)", self.shader);
            }
            layouts.insert(name.clone(), layout);
        }
        layouts
    }
}

/// Reflects one SPIR-V module; `shader` names it in panics (build errors).
pub fn reflect(shader: &str, spirv: &[u8]) -> Interface {
    Module::parse(shader, spirv).interface()
}

/// One interface for the builds of one file (build.rs `BINDING_VARIANTS`): the
/// union of their bindings, each name at one index with one kind, and the same
/// push block and struct layouts.
pub fn merge(shader: &str, builds: &[Interface]) -> Interface {
    let mut merged = builds[0].clone();
    for other in &builds[1..] {
        assert_eq!(merged.set1, other.set1, "{shader}: the builds' set 1 differ");
        assert_eq!(
            merged.push_constant_bytes, other.push_constant_bytes,
            "{shader}: the builds' push-constant blocks differ"
        );
        for b in &other.bindings {
            match merged.bindings.iter().find(|m| m.index == b.index || m.name == b.name) {
                Some(m) => assert_eq!(m, b, "{shader}: the builds disagree on a binding (same index or name)"),
                None => merged.bindings.push(b.clone()),
            }
        }
        for (name, layout) in &other.layouts {
            match merged.layouts.get(name) {
                Some(l) => assert_eq!(l, layout, "{shader}: the builds lay out struct {name} differently"),
                None => {
                    merged.layouts.insert(name.clone(), layout.clone());
                }
            }
        }
    }
    merged.bindings.sort_by_key(|b| b.index);
    merged
}
