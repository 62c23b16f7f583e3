//! Runs of equal intensity bin along the x rows of a padded bin volume, as a
//! table the row walk of [`super::row_runs`] indexes instead of chasing: the
//! run holding any voxel is one load away, and a row's runs are consecutive
//! entries, so the walk's next run does not wait on the load of the last one
//! (a chain of run lengths did, which bound the walk to the load latency per
//! run at b = 8, where runs are about two voxels long).

/// Every x row of a padded bin volume cut into runs of one bin.
#[derive(Clone, Debug)]
pub struct BinRuns {
    /// x voxels per row.
    row_length: usize,
    /// Per row: the index of its first run in `end_x` and `bin`.
    first_run: Vec<u32>,
    /// Per voxel: its run's index within its row.
    run_in_row: Vec<u16>,
    /// Per run: one past its last voxel's x.
    end_x: Vec<u16>,
    /// Per run: its bin.
    bin: Vec<u16>,
}

impl BinRuns {
    /// Largest row length the table holds (x positions and run indices are
    /// u16): loaded volumes stop at 32,768 voxels per axis and the padding at
    /// twice the largest AO radius, far below it.
    const MAX_ROW_LENGTH: usize = u16::MAX as usize;

    /// `bins`: the padded volume, `row_length` voxels per x row.
    pub fn new(bins: &[u16], row_length: usize) -> BinRuns {
        assert!(
            (1..=Self::MAX_ROW_LENGTH).contains(&row_length) && bins.len().is_multiple_of(row_length),
            "a padded bin volume has rows of 1..={} voxels",
            Self::MAX_ROW_LENGTH
        );
        let mut table = BinRuns {
            row_length,
            first_run: Vec::with_capacity(bins.len() / row_length),
            run_in_row: vec![0; bins.len()],
            end_x: vec![],
            bin: vec![],
        };
        for (bins, runs) in bins.chunks(row_length).zip(table.run_in_row.chunks_mut(row_length)) {
            let first = u32::try_from(table.bin.len()).expect("fewer runs than u32 counts: the volume is bounded");
            table.first_run.push(first);
            table.bin.push(bins[0]);
            let mut run = 0u16;
            for x in 1..row_length {
                if bins[x] != bins[x - 1] {
                    table.end_x.push(x as u16);
                    table.bin.push(bins[x]);
                    run += 1;
                }
                runs[x] = run;
            }
            table.end_x.push(row_length as u16);
        }
        table
    }

    /// x voxels per row.
    #[inline]
    pub fn row_length(&self) -> usize {
        self.row_length
    }

    /// The x row holding padded voxel `index`.
    #[inline]
    pub fn row_of(&self, index: usize) -> usize {
        index / self.row_length
    }

    /// Index of the run holding padded voxel `index`, which lies in x row
    /// `row` (a walk knows its row: no division).
    #[inline]
    pub fn run_in(&self, row: usize, index: usize) -> usize {
        debug_assert_eq!(index / self.row_length, row);
        self.first_run[row] as usize + self.run_in_row[index] as usize
    }

    /// One past the last x of run `run`.
    #[inline]
    pub fn end_x(&self, run: usize) -> usize {
        self.end_x[run] as usize
    }

    #[inline]
    pub fn bin(&self, run: usize) -> u16 {
        self.bin[run]
    }

    /// Ends (one past the last x) and bins of the runs `runs`.
    #[inline]
    pub fn ends_and_bins(&self, runs: std::ops::Range<usize>) -> (&[u16], &[u16]) {
        (&self.end_x[runs.clone()], &self.bin[runs])
    }
}

#[cfg(test)]
mod tests {
    use super::BinRuns;

    #[test]
    fn runs_partition_every_row_and_hold_their_voxels_bins() {
        // Two rows of 6; a run never crosses a row's end even when the bins
        // continue (row 0 ends in 3, row 1 starts with 3).
        let bins = [1u16, 1, 2, 2, 2, 3, 3, 3, 0, 1, 1, 1];
        let runs = BinRuns::new(&bins, 6);
        assert_eq!(runs.end_x, [2, 5, 6, 2, 3, 6]);
        assert_eq!(runs.bin, [1, 2, 3, 3, 0, 1]);
        for (i, &k) in bins.iter().enumerate() {
            let r = runs.run_in(runs.row_of(i), i);
            assert_eq!(runs.bin(r), k, "voxel {i}");
            // The voxel lies in its run: before its end, and at or after the
            // end of the run before it in its row.
            assert!(i % 6 < runs.end_x(r), "voxel {i}");
            assert!(r == runs.first_run[i / 6] as usize || runs.end_x(r - 1) <= i % 6, "voxel {i}");
        }
    }
}
