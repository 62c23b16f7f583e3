//! Errors of the volume loaders. Every message starts with the file it is about,
//! so a user who passed a header or a data file sees which one is wrong.

use std::io;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// A volume file could not be loaded.
#[derive(Debug, Error)]
pub enum LoadError {
    #[error("{}: cannot read: {source}", .file.display())]
    Io {
        file: PathBuf,
        #[source]
        source: io::Error,
    },
    #[error(
        "{}: unknown volume file type; supported: {}",
        .file.display(),
        super::SUPPORTED_EXTENSIONS.join(", ")
    )]
    UnknownExtension { file: PathBuf },
    #[error("{}: {problem}", .file.display())]
    Format { file: PathBuf, problem: FormatProblem },
}

impl LoadError {
    /// The file the error is about (for a detached data file: its header).
    pub fn file(&self) -> &Path {
        match self {
            LoadError::Io { file, .. } | LoadError::UnknownExtension { file } | LoadError::Format { file, .. } => file,
        }
    }

    /// What is wrong, without the file name (for a message that names the
    /// file already).
    pub fn detail(&self) -> String {
        match self {
            LoadError::Io { source, .. } => format!("cannot read: {source}"),
            LoadError::UnknownExtension { .. } => {
                format!("unknown volume file type; supported: {}", super::SUPPORTED_EXTENSIONS.join(", "))
            }
            LoadError::Format { problem, .. } => problem.to_string(),
        }
    }

    /// The format problem, when the file could be read but not understood.
    pub fn problem(&self) -> Option<&FormatProblem> {
        match self {
            LoadError::Format { problem, .. } => Some(problem),
            _ => None,
        }
    }
}

/// What is wrong inside a file; [`LoadError::Format`] adds the file name.
#[derive(Debug, Error)]
pub enum FormatProblem {
    /// The header does not follow the format's syntax.
    #[error("{0}")]
    Syntax(String),
    #[error("missing required field `{0}`")]
    MissingField(String),
    #[error("field `{field}` = `{value}`: expected {expected}")]
    BadField { field: String, value: String, expected: String },
    #[error("unsupported {0}")]
    Unsupported(String),
    #[error("invalid dimensions {}: {reason}", format_dims(.dims))]
    BadDims { dims: [i64; 3], reason: String },
    #[error("invalid spacing {} {} {}: every spacing must be finite and > 0", .spacing[0], .spacing[1], .spacing[2])]
    BadSpacing { spacing: [f64; 3] },
    #[error("{what} is truncated (expected {expected} bytes, found {found})")]
    Truncated { what: String, expected: u64, found: u64 },
    #[error("{what} is too long (expected {expected} bytes, found {found})")]
    TooLong { what: String, expected: u64, found: u64 },
    #[error("{what} is not a valid compressed stream: {reason}")]
    Decompress { what: String, reason: String },
    #[error("{what} inflates to {found} bytes, expected {expected}")]
    InflatedTooShort { what: String, expected: u64, found: u64 },
    #[error("{what} inflates to more than the {expected} bytes expected")]
    InflatedTooLong { what: String, expected: u64 },
    #[error("cannot allocate {bytes} bytes for {what}")]
    OutOfMemory { what: String, bytes: u64 },
    #[error("cannot read data file {}: {source}", .path.display())]
    DataFile {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
}

fn format_dims(dims: &[i64; 3]) -> String {
    format!("{} x {} x {}", dims[0], dims[1], dims[2])
}

impl FormatProblem {
    pub(crate) fn syntax(message: impl Into<String>) -> Self {
        FormatProblem::Syntax(message.into())
    }

    pub(crate) fn unsupported(what: impl Into<String>) -> Self {
        FormatProblem::Unsupported(what.into())
    }

    pub(crate) fn bad_field(field: &str, value: &str, expected: impl Into<String>) -> Self {
        FormatProblem::BadField { field: field.to_string(), value: value.to_string(), expected: expected.into() }
    }

    /// Attaches the file name.
    pub(crate) fn in_file(self, file: &Path) -> LoadError {
        LoadError::Format { file: file.to_path_buf(), problem: self }
    }
}
