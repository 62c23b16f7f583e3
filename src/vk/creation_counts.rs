//! How many pipelines, descriptor pools and images a context created (its
//! lifetime so far): what the viewer logs per frame, so that a test sees a
//! frame that creates what an unchanged frame should reuse.

use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};

/// The counters a context keeps.
#[derive(Debug, Default)]
pub struct CreationCounters {
    pipelines: AtomicU64,
    pipelines_reused: AtomicU64,
    descriptor_pools: AtomicU64,
    images: AtomicU64,
}

/// A reading of [`CreationCounters`]; differences of two readings say what
/// happened between them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CreationCounts {
    /// `vkCreateComputePipelines` calls (one pipeline each).
    pub pipelines: u64,
    /// Pipelines asked for and found already created ([`super::pipeline_store`]).
    pub pipelines_reused: u64,
    /// `vkCreateDescriptorPool` calls (a reset pool taken again is not one).
    pub descriptor_pools: u64,
    /// `vkCreateImage` calls.
    pub images: u64,
}

impl CreationCounters {
    pub fn pipeline_created(&self) {
        self.pipelines.fetch_add(1, Ordering::Relaxed);
    }
    pub fn pipeline_reused(&self) {
        self.pipelines_reused.fetch_add(1, Ordering::Relaxed);
    }
    pub fn descriptor_pool_created(&self) {
        self.descriptor_pools.fetch_add(1, Ordering::Relaxed);
    }
    pub fn image_created(&self) {
        self.images.fetch_add(1, Ordering::Relaxed);
    }
    pub fn read(&self) -> CreationCounts {
        CreationCounts {
            pipelines: self.pipelines.load(Ordering::Relaxed),
            pipelines_reused: self.pipelines_reused.load(Ordering::Relaxed),
            descriptor_pools: self.descriptor_pools.load(Ordering::Relaxed),
            images: self.images.load(Ordering::Relaxed),
        }
    }
}

impl CreationCounts {
    /// What was created from `earlier` to `self`.
    pub fn since(&self, earlier: &CreationCounts) -> CreationCounts {
        CreationCounts {
            pipelines: self.pipelines - earlier.pipelines,
            pipelines_reused: self.pipelines_reused - earlier.pipelines_reused,
            descriptor_pools: self.descriptor_pools - earlier.descriptor_pools,
            images: self.images - earlier.images,
        }
    }
}
