//! Histogram packing (section 3.2): the vector quantization trains on local
//! histograms of a lower dimension, packed by a scheme derived from the
//! normalized histogram H of the whole volume.
//!
//! Our reading: start with H_0 = H (2^b bins, in intensity order). H_i is H_{i-1}
//! with its smallest bin removed and that bin's content split equally between
//! its two neighbouring bins (the remaining bins just below and above it); a
//! bin at either end has one neighbour, which takes it all. Ties go to the
//! lowest bin, so empty bins (intensities the volume does not hold) go first,
//! lowest first. Repeat until `packed_dim` bins remain. The same splits, applied
//! to every local histogram, are its packing: each original bin ends up spread
//! over one or more packed bins with shares summing to 1, so packing is linear
//! and preserves a histogram's total mass.

/// Where each of the 2^b original bins goes in the packed histogram.
#[derive(Clone, Debug, PartialEq)]
pub struct PackingScheme {
    pub bins: usize,
    pub packed_dim: usize,
    /// For original bin k: (packed bin, share) pairs, shares summing to 1.
    pub shares: Vec<Vec<(u32, f32)>>,
    /// H packed by the scheme (the last H_i), for reports and tests.
    pub packed_global: Vec<f64>,
}

/// One bin of H_i: its mass and which original bins it holds, with shares.
struct Group {
    mass: f64,
    members: Vec<(u32, f64)>,
}

impl PackingScheme {
    /// The scheme for global histogram `global` (any scale; counts are fine),
    /// `2 <= packed_dim <= global.len()`.
    pub fn from_histogram(global: &[f64], packed_dim: usize) -> PackingScheme {
        let bins = global.len();
        let packed_dim = packed_dim.clamp(1, bins.max(1));
        let mut groups: Vec<Group> =
            global.iter().enumerate().map(|(k, &mass)| Group { mass, members: vec![(k as u32, 1.0)] }).collect();
        while groups.len() > packed_dim {
            let smallest = (0..groups.len())
                .min_by(|&a, &b| groups[a].mass.total_cmp(&groups[b].mass).then(a.cmp(&b)))
                .expect("more groups than packed_dim >= 1");
            let split = groups.remove(smallest);
            // After the removal, the neighbours sit at smallest - 1 and smallest.
            let below = smallest.checked_sub(1);
            let above = (smallest < groups.len()).then_some(smallest);
            let receivers: Vec<usize> = [below, above].into_iter().flatten().collect();
            let fraction = 1.0 / receivers.len() as f64;
            for r in receivers {
                let g = &mut groups[r];
                g.mass += split.mass * fraction;
                for &(k, share) in &split.members {
                    match g.members.iter_mut().find(|(m, _)| *m == k) {
                        Some(member) => member.1 += share * fraction,
                        None => g.members.push((k, share * fraction)),
                    }
                }
            }
        }
        let mut shares = vec![Vec::new(); bins];
        for (j, g) in groups.iter().enumerate() {
            for &(k, share) in &g.members {
                shares[k as usize].push((j as u32, share as f32));
            }
        }
        let packed_global = groups.iter().map(|g| g.mass).collect();
        PackingScheme { bins, packed_dim: groups.len(), shares, packed_global }
    }

    /// Packs `histogram` (`bins` values) into `packed` (`packed_dim` values).
    pub fn pack(&self, histogram: &[f32], packed: &mut [f32]) {
        packed.fill(0.0);
        for (k, &v) in histogram.iter().enumerate() {
            if v != 0.0 {
                for &(j, share) in &self.shares[k] {
                    packed[j as usize] += v * share;
                }
            }
        }
    }

    /// The scheme as a dense `bins x packed_dim` row-major matrix (for a GPU
    /// packing pass and the cache).
    pub fn matrix(&self) -> Vec<f32> {
        let mut m = vec![0.0; self.bins * self.packed_dim];
        for (k, row) in self.shares.iter().enumerate() {
            for &(j, share) in row {
                m[k * self.packed_dim + j as usize] = share;
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smallest_bin_goes_half_to_each_neighbour() {
        // [4, 1, 3, 2] -> bin 1 (1) splits: [4.5, 3.5, 2] -> bin 2 (2, at the end)
        // goes whole to bin 1: [4.5, 5.5].
        let s = PackingScheme::from_histogram(&[4.0, 1.0, 3.0, 2.0], 3);
        assert_eq!(s.packed_global, vec![4.5, 3.5, 2.0]);
        assert_eq!(s.shares[1], vec![(0, 0.5), (1, 0.5)]);
        let s = PackingScheme::from_histogram(&[4.0, 1.0, 3.0, 2.0], 2);
        assert_eq!(s.packed_global, vec![4.5, 5.5]);
        assert_eq!(s.shares[3], vec![(1, 1.0)]);
        let mut packed = [0.0; 2];
        s.pack(&[0.0, 2.0, 0.0, 1.0], &mut packed);
        assert_eq!(packed, [1.0, 2.0]);
    }

    #[test]
    fn a_split_bin_that_holds_earlier_splits_passes_their_shares_on() {
        // [1, 0, 5, 5]: bin 1 (0) splits first: [1, 5, 5] (nothing moves), then
        // bin 0 (1, at the end) goes to the 5: [6, 5] with bins 0 and 1 inside.
        let s = PackingScheme::from_histogram(&[1.0, 0.0, 5.0, 5.0], 2);
        assert_eq!(s.packed_global, vec![6.0, 5.0]);
        assert_eq!(s.shares[0], vec![(0, 1.0)]);
        assert_eq!(s.shares[1], vec![(0, 1.0)]);
        // Ties: the lowest bin first (at the end, so all of it to bin 1).
        let s = PackingScheme::from_histogram(&[2.0, 2.0, 2.0], 2);
        assert_eq!(s.packed_global, vec![4.0, 2.0]);
    }

    #[test]
    fn packing_gives_the_requested_dimension_and_preserves_mass() {
        let global: Vec<f64> =
            (0..256).map(|k| ((k * 37) % 11) as f64 + if k % 5 == 0 { 100.0 } else { 0.0 }).collect();
        for dim in [2, 16, 64, 255, 256] {
            let s = PackingScheme::from_histogram(&global, dim);
            assert_eq!(s.packed_dim, dim);
            assert_eq!(s.packed_global.len(), dim);
            let total: f64 = s.packed_global.iter().sum();
            assert!((total - global.iter().sum::<f64>()).abs() < 1e-9 * total, "dim {dim}");
            for row in &s.shares {
                let sum: f32 = row.iter().map(|&(_, share)| share).sum();
                assert!((sum - 1.0).abs() < 1e-5, "dim {dim}: {row:?}");
            }
            let hist: Vec<f32> = (0..256).map(|k| ((k * 13) % 7) as f32 * 0.01).collect();
            let mut packed = vec![0.0; dim];
            s.pack(&hist, &mut packed);
            let (a, b): (f32, f32) = (hist.iter().sum(), packed.iter().sum());
            assert!((a - b).abs() < 1e-4 * a, "dim {dim}: {a} vs {b}");
            // The matrix is the same map.
            let m = s.matrix();
            for j in 0..dim {
                let via_matrix: f32 = (0..256).map(|k| hist[k] * m[k * dim + j]).sum();
                assert!((via_matrix - packed[j]).abs() < 1e-5, "dim {dim} bin {j}");
            }
        }
    }
}
