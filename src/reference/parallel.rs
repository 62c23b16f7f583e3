//! Rows of an image rendered on all cores. Every pixel is a pure function of its
//! coordinates, so the result does not depend on which thread took which row.

use std::sync::{Mutex, PoisonError};

/// Row-major pixels of a `width` x `height` image, `pixel(x, y)` each.
pub fn render_rows<F>(width: u32, height: u32, pixel: F) -> Vec<[f32; 3]>
where
    F: Fn(u32, u32) -> [f32; 3] + Sync,
{
    let mut pixels = vec![[0.0; 3]; width as usize * height as usize];
    if pixels.is_empty() {
        return pixels;
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(height as usize);
    // Rows are handed out one at a time: cost varies a lot between rows that
    // miss the volume and rows through its densest part.
    let rows = Mutex::new(pixels.chunks_mut(width as usize).zip(0u32..));
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let next = rows.lock().unwrap_or_else(PoisonError::into_inner).next();
                let Some((row, y)) = next else { break };
                for (x, out) in (0u32..).zip(row.iter_mut()) {
                    *out = pixel(x, y);
                }
            });
        }
    });
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pixel_lands_at_its_own_place() {
        let (w, h) = (7u32, 13u32);
        let pixels = render_rows(w, h, |x, y| [x as f32, y as f32, (x * y) as f32]);
        assert_eq!(pixels.len(), (w * h) as usize);
        for y in 0..h {
            for x in 0..w {
                assert_eq!(pixels[(y * w + x) as usize], [x as f32, y as f32, (x * y) as f32]);
            }
        }
    }

    #[test]
    fn empty_images_have_no_pixels() {
        assert!(render_rows(0, 5, |_, _| [1.0; 3]).is_empty());
        assert!(render_rows(5, 0, |_, _| [1.0; 3]).is_empty());
    }
}
