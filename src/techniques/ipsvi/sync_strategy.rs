//! How consecutive line blocks of a sweep are synchronized: the variable the
//! synchronization study measures. Every strategy but `Racy` gives the same image.

use std::fmt;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SyncStrategy {
    /// A global memory barrier after each block: compute write -> compute read/write.
    BarrierGlobal,
    /// Image memory barriers narrowed to the cache pair and the output image.
    BarrierImage,
    /// Split barriers: `vkCmdSetEvent2` after a block, `vkCmdWaitEvents2` before
    /// the next one, with the same dependency.
    Events,
    /// Each sweep's blocks (dispatches and global barriers) recorded once into a
    /// secondary command buffer and replayed every frame while the renderer (the
    /// sweep geometry) lives; parameters come from buffers, nothing is re-recorded.
    Secondary,
    /// One queue submission per line block, ordered by a timeline semaphore: the
    /// cost of host-visible granularity.
    Submits,
    /// RACY: no synchronization between blocks at all, for cost comparison only;
    /// its image is undefined and synchronization validation reports it.
    Racy,
}

impl SyncStrategy {
    pub const ALL: [SyncStrategy; 6] = [
        SyncStrategy::BarrierGlobal,
        SyncStrategy::BarrierImage,
        SyncStrategy::Events,
        SyncStrategy::Secondary,
        SyncStrategy::Submits,
        SyncStrategy::Racy,
    ];

    pub fn name(self) -> &'static str {
        match self {
            SyncStrategy::BarrierGlobal => "barrier-global",
            SyncStrategy::BarrierImage => "barrier-image",
            SyncStrategy::Events => "events",
            SyncStrategy::Submits => "submits",
            SyncStrategy::Secondary => "secondary",
            SyncStrategy::Racy => "racy",
        }
    }

    pub fn is_racy(self) -> bool {
        self == SyncStrategy::Racy
    }
}

impl fmt::Display for SyncStrategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())?;
        if self.is_racy() {
            f.write_str(" (RACY: unsynchronized, image undefined)")?;
        }
        Ok(())
    }
}

impl FromStr for SyncStrategy {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SyncStrategy::ALL.into_iter().find(|t| t.name() == s).ok_or_else(|| {
            format!("unknown sync strategy {s:?}; known: {}", SyncStrategy::ALL.map(|t| t.name()).join(", "))
        })
    }
}
