//! Drops the source-level debug instructions from a SPIR-V module (build.rs
//! only): the embedded source text, file names and line numbers (OpSource,
//! OpSourceContinued, OpSourceExtension, OpString, OpLine, OpNoLine,
//! OpModuleProcessed). The names (OpName, OpMemberName) stay: build.rs reflects
//! bindings by them, and validation messages name objects by them.
//!
//! Why: the modules then hold nothing of the clone's path, so two clones
//! build the same SPIR-V and share Mesa's shader cache; and every pipeline
//! creation parses the whole module (lavapipe's translation, the Khronos
//! validation layer's uncached re-validation), of which this text was a third
//! for IPSVI's line shader (docs/testing.md, "Where the time goes": Pipelines).

const OP_SOURCE_CONTINUED: u32 = 2;
const OP_SOURCE: u32 = 3;
const OP_SOURCE_EXTENSION: u32 = 4;
const OP_STRING: u32 = 7;
const OP_LINE: u32 = 8;
const OP_NO_LINE: u32 = 317;
const OP_MODULE_PROCESSED: u32 = 330;

/// Words of the SPIR-V header (magic, version, generator, bound, schema).
const HEADER_WORDS: usize = 5;

/// `spirv` without its source-level debug instructions; `shader` names it in
/// panics (build errors).
pub fn strip_source_debug(shader: &str, spirv: &[u8]) -> Vec<u8> {
    assert!(spirv.len().is_multiple_of(4) && spirv.len() >= HEADER_WORDS * 4, "{shader}: not SPIR-V");
    let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let mut out = words[..HEADER_WORDS].to_vec();
    let mut at = HEADER_WORDS;
    while at < words.len() {
        let (count, opcode) = ((words[at] >> 16) as usize, words[at] & 0xffff);
        assert!(count > 0 && at + count <= words.len(), "{shader}: instruction at word {at} runs past the end");
        let debug = matches!(
            opcode,
            OP_SOURCE_CONTINUED
                | OP_SOURCE
                | OP_SOURCE_EXTENSION
                | OP_STRING
                | OP_LINE
                | OP_NO_LINE
                | OP_MODULE_PROCESSED
        );
        if !debug {
            out.extend_from_slice(&words[at..at + count]);
        }
        at += count;
    }
    out.iter().flat_map(|w| w.to_le_bytes()).collect()
}
