//! Which cells of an uploaded scene's volume are empty: every position a
//! march can sample there has extinction exactly 0, so its sample adds exactly
//! nothing (optical depth `+ 0 * step`, emission `* (1 - exp(0))`). The GPU
//! reference's shadow rays step over such cells (glsl/empty_cells.glsl) and
//! give the image of the brute-force march bit for bit; they spent most of
//! their time in the air of scenes such as the Cornell box.
//!
//! A cell is `CELL` voxels a side. Its samples' trilinear footprints (clamped
//! to the edge) lie in the voxels `[c CELL - 1, (c + 1) CELL]`; the test takes
//! the whole neighbouring cells, so a sample a rounding error outside the cell
//! is covered too. It is empty when the transfer LUT has zero extinction on
//! every texel a value between those voxels' least and greatest can blend,
//! with one texel more on each side: filtering of any kind (exact, 8-bit
//! weights, nearest for labels) gives a value between them.

use super::GpuScene;
use crate::scene::transfer::TransferLut;
use crate::scene::volume::Volume;
use bytemuck::{Pod, Zeroable};
use glam::UVec3;

/// Voxels per cell side: the least that the one-cell neighbourhood covers
/// (footprint and margin reach two voxels past a face). On the Cornell box's
/// quarter-step reference at 32x32 (lavapipe), 4 left the frame 13.3 s, 2 8.1 s
/// (28.8 s marching every sample).
pub const CELL: u32 = 2;

/// The header of glsl/empty_cells.glsl's buffer; the cells follow, x fastest,
/// one u32 each (1: occupied).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct EmptyCellsHeader {
    /// Cells per axis.
    pub cells: [u32; 3],
    /// Voxels per cell side.
    pub cell_voxels: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct EmptyCells {
    pub cells: UVec3,
    /// 1 where a sample may have extinction other than 0.
    pub occupied: Vec<u32>,
}

impl EmptyCells {
    /// Each voxel read once: every cell's own least and greatest value, then
    /// those of the cell and its 26 neighbours, which hold the two voxels of
    /// footprint and margin beyond each face (`CELL` >= 2).
    pub fn new(volume: &Volume, lut: &TransferLut) -> EmptyCells {
        let (dims, cells) = (volume.dims, grid(volume.dims));
        let cell_index = |c: UVec3| ((c.z * cells.y + c.y) * cells.x + c.x) as usize;
        let mut own = vec![(f32::INFINITY, f32::NEG_INFINITY); (cells.x * cells.y * cells.z) as usize];
        let mut index = 0;
        for z in 0..dims.z {
            for y in 0..dims.y {
                for x in 0..dims.x {
                    let v = volume.data.normalized(index);
                    let range = &mut own[cell_index(UVec3::new(x, y, z) / CELL)];
                    *range = (range.0.min(v), range.1.max(v));
                    index += 1;
                }
            }
        }
        let mut occupied = Vec::with_capacity(own.len());
        for cz in 0..cells.z {
            for cy in 0..cells.y {
                for cx in 0..cells.x {
                    let c = UVec3::new(cx, cy, cz);
                    let (first, last) = (c.saturating_sub(UVec3::ONE), (c + 1).min(cells - 1));
                    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                    for z in first.z..=last.z {
                        for y in first.y..=last.y {
                            for x in first.x..=last.x {
                                let range = own[cell_index(UVec3::new(x, y, z))];
                                (lo, hi) = (lo.min(range.0), hi.max(range.1));
                            }
                        }
                    }
                    occupied.push(!lut_clear(lut, lo, hi) as u32);
                }
            }
        }
        EmptyCells { cells, occupied }
    }

    /// The cells of the scene on the GPU (its volume, the LUT it uploaded),
    /// found at its first reference frame and kept with it.
    pub fn of_scene<'g>(gpu: &'g GpuScene) -> &'g EmptyCells {
        gpu.empty_cells.get_or_init(|| EmptyCells::new(&gpu.scene.volume, &gpu.scene.transfer.bake(gpu.lut_size)))
    }

    /// Every cell occupied: the brute-force march, sample by sample.
    pub fn none_empty(volume: &Volume) -> EmptyCells {
        let cells = grid(volume.dims);
        EmptyCells { cells, occupied: vec![1; (cells.x * cells.y * cells.z) as usize] }
    }

    /// Words of [`Self::buffer_words`] for `volume`.
    pub fn buffer_len(volume: &Volume) -> usize {
        let cells = grid(volume.dims);
        4 + (cells.x * cells.y * cells.z) as usize
    }

    pub fn empty_count(&self) -> usize {
        self.occupied.iter().filter(|&&o| o == 0).count()
    }

    /// The buffer glsl/empty_cells.glsl reads: the header, then the cells.
    pub fn buffer_words(&self) -> Vec<u32> {
        let header = EmptyCellsHeader { cells: self.cells.to_array(), cell_voxels: CELL };
        let mut words = bytemuck::cast_slice::<EmptyCellsHeader, u32>(&[header]).to_vec();
        words.extend_from_slice(&self.occupied);
        words
    }
}

/// Cells per axis: the last may reach past the volume.
fn grid(dims: UVec3) -> UVec3 {
    (dims + UVec3::splat(CELL - 1)) / CELL
}

/// Whether the LUT's extinction is exactly 0 wherever a value in [lo, hi]
/// reads it (transfer_lut.glsl: texels floor(t) and floor(t) + 1 of
/// t = clamp(s n - 0.5, 0, n - 1)), one texel of margin on each side. A NaN
/// anywhere counts as not clear.
fn lut_clear(lut: &TransferLut, lo: f32, hi: f32) -> bool {
    let n = lut.texels.len();
    if n == 0 || lo.is_nan() || hi.is_nan() || lo > hi {
        return false;
    }
    let texel = |s: f32| ((s as f64) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64).floor() as usize;
    let first = texel(lo).saturating_sub(1);
    let last = (texel(hi) + 2).min(n - 1);
    lut.texels[first..=last].iter().all(|t| t[3] == 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::transfer::TransferFunction;
    use crate::scene::volume::{Interpolation, VoxelData};
    use glam::Vec3;

    fn volume(dims: UVec3, at: impl Fn(u32, u32, u32) -> u8) -> Volume {
        let mut data = Vec::new();
        for z in 0..dims.z {
            for y in 0..dims.y {
                for x in 0..dims.x {
                    data.push(at(x, y, z));
                }
            }
        }
        Volume {
            name: "cells".into(),
            dims,
            spacing: Vec3::ONE,
            data: VoxelData::U8(data),
            value_range: (0.0, 255.0),
            non_finite_voxels: 0,
            interpolation: Interpolation::Trilinear,
        }
    }

    /// Clear below 0.5, opaque above.
    fn step_lut() -> TransferLut {
        let n = TransferLut::DEFAULT_SIZE;
        TransferLut {
            texels: (0..n)
                .map(|i| if (i as f32 + 0.5) / n as f32 > 0.5 { [1.0, 1.0, 1.0, 2.0] } else { [0.0; 4] })
                .collect(),
        }
    }

    #[test]
    fn a_cell_next_to_any_medium_is_not_empty() {
        // One opaque voxel in cell 4 of a row of 8 cells along x: cells 3 and 5
        // read it within their footprint and margin.
        let v = volume(UVec3::new(8 * CELL, CELL, CELL), |x, _, _| if x == 4 * CELL + 1 { 255 } else { 0 });
        let cells = EmptyCells::new(&v, &step_lut());
        assert_eq!(cells.cells, UVec3::new(8, 1, 1));
        assert_eq!(cells.occupied, vec![0, 0, 0, 1, 1, 1, 0, 0]);
        assert_eq!(cells.empty_count(), 5);
        assert!(EmptyCells::none_empty(&v).occupied.iter().all(|&o| o == 1));
    }

    #[test]
    fn a_value_whose_lut_texels_reach_the_opaque_ones_is_not_empty() {
        // The step is between texels 511 and 512. 127/255: t = 509.5, texels
        // 509 and 510 read, 508..=511 with the margin: clear. 128/255: t = 513.5.
        for (value, empty) in [(127u8, true), (128, false), (0, true), (255, false)] {
            let v = volume(UVec3::splat(CELL), |_, _, _| value);
            assert_eq!(EmptyCells::new(&v, &step_lut()).empty_count() == 1, empty, "value {value}");
        }
        // The Cornell box's air is clear.
        let tf: TransferFunction = crate::scene::presets::preset("cornell").unwrap();
        let v = volume(UVec3::splat(2 * CELL), |_, _, _| 0);
        assert_eq!(EmptyCells::new(&v, &tf.bake(TransferLut::DEFAULT_SIZE)).empty_count(), 8);
    }

    #[test]
    fn the_header_leads_the_buffer() {
        // A side that is not a whole number of cells takes one cell more.
        let v = volume(UVec3::new(2 * CELL + 1, CELL, 3 * CELL), |_, _, _| 0);
        let cells = EmptyCells::new(&v, &step_lut());
        let words = cells.buffer_words();
        assert_eq!(&words[..4], &[3, 1, 3, CELL]);
        assert_eq!(words.len(), 4 + 9);
        assert_eq!(words.len(), EmptyCells::buffer_len(&v));
    }
}
