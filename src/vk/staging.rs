//! Device-local buffers filled and read through host-visible staging buffers.
//!
//! Buffers that shaders read or write belong in device-local memory
//! (`MemoryLocation::GpuOnly`): on a discrete GPU, host memory is across the
//! bus. [`Uploads`] creates such buffers and fills them with one submission of
//! copies; [`Readback`] is the host-visible copy target for results the CPU
//! reads. The barriers around a read-back copy are the caller's, written where
//! the reader sees what they protect.

use super::barriers::{Access, Barrier};
use super::commands::{submit_and_wait, Recorder};
use super::context::Context;
use super::error::VkError;
use super::resources::Buffer;
use ash::vk;
use bytemuck::Pod;
use gpu_allocator::MemoryLocation;

/// Device-local buffers created now and filled by [`Uploads::finish`].
pub struct Uploads<'c> {
    ctx: &'c Context,
    /// Staging buffer, destination, bytes.
    pending: Vec<(Buffer, vk::Buffer, u64)>,
}

impl<'c> Uploads<'c> {
    pub fn new(ctx: &'c Context) -> Uploads<'c> {
        Uploads { ctx, pending: Vec::new() }
    }

    /// A device-local buffer of `usage` that holds `data` once [`Self::finish`]
    /// has run (before that its contents are undefined).
    pub fn buffer<T: Pod>(&mut self, name: &str, data: &[T], usage: vk::BufferUsageFlags) -> Result<Buffer, VkError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let size = bytes.len().max(4) as u64;
        let usage = usage | vk::BufferUsageFlags::TRANSFER_DST;
        let buffer = Buffer::new(self.ctx, name, size, usage, MemoryLocation::GpuOnly)?;
        if !bytes.is_empty() {
            let staging_name = format!("{name} staging");
            let mut staging = Buffer::staging(
                self.ctx,
                &staging_name,
                bytes.len() as u64,
                vk::BufferUsageFlags::TRANSFER_SRC,
                MemoryLocation::CpuToGpu,
            )?;
            staging.write_bytes(0, bytes)?;
            self.pending.push((staging, buffer.raw, bytes.len() as u64));
        }
        Ok(buffer)
    }

    /// Copies every staged buffer in one submission and waits; the staging
    /// buffers go. Later submissions' shaders read the copies: the barrier
    /// `staged_upload_to_shader_read` orders them (a barrier's second scope
    /// covers every later command in submission order).
    pub fn finish(self) -> Result<(), VkError> {
        if self.pending.is_empty() {
            return Ok(());
        }
        submit_and_wait(self.ctx, "staged_upload", |rec| {
            for (staging, dst, bytes) in &self.pending {
                copy_raw(rec, staging.raw, *dst, *bytes);
            }
            rec.barrier(&Barrier::memory("staged_upload_to_shader_read", Access::TRANSFER_WRITE, Access::COMPUTE_READ));
            Ok(())
        })
    }
}

/// A host-visible buffer the device copies results into for the CPU to read
/// ([`Buffer::read`], [`Buffer::mapped`]).
pub fn readback_buffer(ctx: &Context, name: &str, bytes: u64) -> Result<Buffer, VkError> {
    Buffer::staging(ctx, name, bytes.max(4), vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)
}

/// Records a copy of the first `bytes` of `src` into `dst` (src needs
/// TRANSFER_SRC usage, dst TRANSFER_DST).
pub fn copy_buffer(rec: &Recorder, src: &Buffer, dst: &Buffer, bytes: u64) {
    copy_raw(rec, src.raw, dst.raw, bytes.min(src.size).min(dst.size));
}

fn copy_raw(rec: &Recorder, src: vk::Buffer, dst: vk::Buffer, bytes: u64) {
    if bytes == 0 {
        return;
    }
    let region = [vk::BufferCopy { src_offset: 0, dst_offset: 0, size: bytes }];
    // SAFETY: both buffers are alive until the submission completes (the
    // callers wait on it), were created with the transfer usages, and hold at
    // least `bytes`.
    unsafe { rec.device().cmd_copy_buffer(rec.cb, src, dst, &region) };
}

/// A device-local buffer holding `data`, uploaded by its own submission.
pub fn device_buffer_with_data<T: Pod>(
    ctx: &Context,
    name: &str,
    data: &[T],
    usage: vk::BufferUsageFlags,
) -> Result<Buffer, VkError> {
    let mut uploads = Uploads::new(ctx);
    let buffer = uploads.buffer(name, data, usage)?;
    uploads.finish()?;
    Ok(buffer)
}

/// Copies the first `count` values of a device-local buffer (TRANSFER_SRC
/// usage) written by earlier submissions to the host, in a submission of its
/// own: `shader_write_to_readback_copy` orders the copy after those writes.
pub fn read_device_buffer<T: Pod>(ctx: &Context, src: &Buffer, count: usize) -> Result<Vec<T>, VkError> {
    let bytes = (count * std::mem::size_of::<T>()) as u64;
    let staging = readback_buffer(ctx, "device buffer readback", bytes)?;
    submit_and_wait(ctx, "device_buffer_readback", |rec| {
        rec.barrier(&Barrier::memory("shader_write_to_readback_copy", Access::COMPUTE_WRITE, Access::TRANSFER_READ));
        copy_buffer(rec, src, &staging, bytes);
        rec.barrier(&Barrier::memory("readback_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
        Ok(())
    })?;
    staging.read(count)
}
