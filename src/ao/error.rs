//! What can go wrong in AO preprocessing: bad settings, an unusable training
//! set, and cache file I/O.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum AoError {
    /// A setting out of range or misspelt; the message names `ao.key = value`
    /// and what is allowed.
    #[error("{0}")]
    Invalid(String),
    /// The training set rule selects no voxel of this volume.
    #[error("ao training set is empty: {0}")]
    EmptyTrainingSet(String),
    #[error("ao cache {path}: {source}")]
    CacheIo {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}
