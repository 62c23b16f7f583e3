//! The training set TS of the vector quantization (section 3.2): which voxels'
//! histograms the codebook learns from.

use std::collections::HashSet;

use super::error::AoError;
use super::gradient::central_gradient;
use super::settings::TrainingSet;
use crate::scene::Volume;

/// Linear indices of the training voxels, ascending.
pub fn select_training_voxels(volume: &Volume, rule: &TrainingSet) -> Result<Vec<usize>, AoError> {
    let n = volume.voxel_count();
    if n == 0 {
        return Err(AoError::EmptyTrainingSet(format!("volume {} has no voxels", volume.name)));
    }
    match *rule {
        TrainingSet::Random { count, seed } => Ok(sample(n, count as usize, seed)),
        TrainingSet::Gradient { eps, count, seed } => {
            let (nx, ny) = (volume.dims.x as usize, volume.dims.y as usize);
            let mut steepest = 0.0f32;
            let candidates: Vec<usize> = (0..n)
                .filter(|&i| {
                    let p = glam::UVec3::new((i % nx) as u32, ((i / nx) % ny) as u32, (i / (nx * ny)) as u32);
                    let g = central_gradient(volume, p).length();
                    steepest = steepest.max(g);
                    g > eps
                })
                .collect();
            if candidates.is_empty() {
                return Err(AoError::EmptyTrainingSet(format!(
                    "no voxel has |gradient| > ao.training.eps = {eps} (the steepest is {steepest}); lower eps"
                )));
            }
            Ok(sample(candidates.len(), count as usize, seed).into_iter().map(|i| candidates[i]).collect())
        }
    }
}

/// `count` distinct indices of `0..n` drawn uniformly (Floyd's algorithm), or
/// all of them when `count >= n`; ascending.
fn sample(n: usize, count: usize, seed: u64) -> Vec<usize> {
    if count >= n {
        return (0..n).collect();
    }
    let mut rng = SplitMix64(seed);
    let mut chosen = HashSet::with_capacity(count);
    for j in n - count..n {
        let t = (rng.next() % (j as u64 + 1)) as usize;
        if !chosen.insert(t) {
            chosen.insert(j);
        }
    }
    let mut v: Vec<usize> = chosen.into_iter().collect();
    v.sort_unstable();
    v
}

/// SplitMix64: small, fast and well mixed; enough to draw a training set.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::synthetic::cornell_box;

    #[test]
    fn random_draws_distinct_voxels_reproducibly() {
        let v = cornell_box(16);
        let rule = TrainingSet::Random { count: 300, seed: 4 };
        let a = select_training_voxels(&v, &rule).unwrap();
        assert_eq!(a.len(), 300);
        assert!(a.windows(2).all(|w| w[0] < w[1]) && *a.last().unwrap() < v.voxel_count());
        assert_eq!(a, select_training_voxels(&v, &rule).unwrap());
        assert_ne!(a, select_training_voxels(&v, &TrainingSet::Random { count: 300, seed: 5 }).unwrap());
        let all = select_training_voxels(&v, &TrainingSet::Random { count: 1 << 20, seed: 4 }).unwrap();
        assert_eq!(all.len(), v.voxel_count());
    }

    #[test]
    fn gradient_keeps_only_steep_voxels_and_an_empty_set_is_an_error() {
        let v = cornell_box(16);
        let rule = TrainingSet::Gradient { eps: 0.01, count: 1 << 20, seed: 1 };
        let steep = select_training_voxels(&v, &rule).unwrap();
        assert!(!steep.is_empty() && steep.len() < v.voxel_count());
        let (nx, ny) = (16, 16);
        for &i in &steep {
            let p = glam::UVec3::new((i % nx) as u32, ((i / nx) % ny) as u32, (i / (nx * ny)) as u32);
            assert!(central_gradient(&v, p).length() > 0.01);
        }
        let capped = select_training_voxels(&v, &TrainingSet::Gradient { eps: 0.01, count: 10, seed: 1 }).unwrap();
        assert_eq!(capped.len(), 10);
        assert!(capped.iter().all(|i| steep.contains(i)));
        let e = select_training_voxels(&v, &TrainingSet::Gradient { eps: 10.0, count: 10, seed: 1 }).unwrap_err();
        assert!(e.to_string().contains("ao.training.eps = 10"), "{e}");
        let mut empty = v.clone();
        empty.dims = glam::UVec3::ZERO;
        empty.data = crate::scene::VoxelData::U8(vec![]);
        let e = select_training_voxels(&empty, &TrainingSet::Random { count: 10, seed: 1 }).unwrap_err();
        assert!(e.to_string().contains("no voxels"), "{e}");
    }
}
