//! Pipelines the context keeps once created: a pass that asks again for the
//! pipeline of the same shader build, name and specialization constants (the
//! next frame of the viewer, the next render of a benchmark) gets the one
//! already compiled instead of a new `vkCreateComputePipelines`. A new shader
//! variant (another constant) is a new pipeline. The store keeps the
//! [`KEPT`] most recently asked for; an entry dropped from it lives on in the
//! [`super::ComputePipeline`]s that still hold it.

use super::error::VkError;
use ash::vk;
use std::sync::{Arc, Mutex};

/// Pipelines the store keeps (every technique's variants of one session fit many times).
pub const KEPT: usize = 256;

/// A pipeline with its layouts, destroyed when the last holder lets go.
pub struct PipelineObjects {
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    /// Set 1 (the small ping-pong set), null where the shader has none.
    pub set1_layout: vk::DescriptorSetLayout,
    pub device: ash::Device,
}

impl Drop for PipelineObjects {
    fn drop(&mut self) {
        // SAFETY: the last holder is gone: a ComputePipeline is dropped after
        // the GPU work using it completed, the store only at context drop
        // after the device is idle.
        unsafe {
            self.device.destroy_pipeline(self.raw, None);
            self.device.destroy_pipeline_layout(self.layout, None);
            self.device.destroy_descriptor_set_layout(self.set_layout, None);
            self.device.destroy_descriptor_set_layout(self.set1_layout, None);
        }
    }
}

/// What makes two pipelines the same.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PipelineKey {
    /// The SPIR-V build (its static bytes' address: one per build of a shader).
    pub spirv: usize,
    /// Debug name (kept right on the shared object).
    pub name: String,
    /// Every specialization constant, the context's shared ones included.
    pub constants: Vec<(u32, u32)>,
}

#[derive(Default)]
pub struct PipelineStore {
    /// Most recently asked for last.
    entries: Mutex<Vec<(PipelineKey, Arc<PipelineObjects>)>>,
}

impl PipelineStore {
    /// The pipeline of `key`, kept or made by `create`; true: it was created now.
    pub fn get_or_create(
        &self,
        key: PipelineKey,
        create: impl FnOnce() -> Result<PipelineObjects, VkError>,
    ) -> Result<(Arc<PipelineObjects>, bool), VkError> {
        if let Some(found) = self.take(&key) {
            return Ok((found, false));
        }
        // Created outside the lock: a compile may take long.
        let created = Arc::new(create()?);
        let mut entries = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        entries.push((key, created.clone()));
        if entries.len() > KEPT {
            entries.remove(0);
        }
        Ok((created, true))
    }

    /// The kept pipeline of `key`, moved to the most recent end.
    fn take(&self, key: &PipelineKey) -> Option<Arc<PipelineObjects>> {
        let mut entries = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        let i = entries.iter().position(|(k, _)| k == key)?;
        let entry = entries.remove(i);
        let found = entry.1.clone();
        entries.push(entry);
        Some(found)
    }

    /// How many pipelines are kept.
    pub fn len(&self) -> usize {
        self.entries.lock().unwrap_or_else(|p| p.into_inner()).len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Lets go of every kept pipeline (context drop, device idle).
    pub fn clear(&self) {
        self.entries.lock().unwrap_or_else(|p| p.into_inner()).clear();
    }
}
