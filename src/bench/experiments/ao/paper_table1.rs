//! Table 1 of the AO paper (Ropinski et al. 2008): preprocessing times on
//! Opteron 852 processors, 4 per process, brute force and (last row) with the
//! space sweep. `sweeplab bench ao` prints our preprocessing beside it; the
//! machines differ, so read the shape (what grows with r and n_c), not the
//! absolute times.

pub struct PaperRow {
    pub data_set: &'static str,
    pub size: &'static str,
    pub radius: u32,
    /// Local histogram generation, minutes.
    pub histograms_min: f64,
    /// Codewords / packed dimension.
    pub training: &'static str,
    /// Vector quantization training, minutes (one per codebook size where
    /// the paper lists several).
    pub training_min: &'static str,
    pub local_histograms: &'static str,
    pub codebook: &'static str,
    pub space_sweep: bool,
}

/// One row: (data set, size), r, histogram minutes, (codewords/packed,
/// training minutes), (local histogram size, codebook size), space sweep.
const fn row(
    (data_set, size): (&'static str, &'static str),
    radius: u32,
    histograms_min: f64,
    (training, training_min): (&'static str, &'static str),
    (local_histograms, codebook): (&'static str, &'static str),
    space_sweep: bool,
) -> PaperRow {
    PaperRow { data_set, size, radius, histograms_min, training, training_min, local_histograms, codebook, space_sweep }
}

pub const ROWS: [PaperRow; 9] = [
    row(
        ("Cornell box", "128x128x128"),
        32,
        236.03,
        ("256/16 512/16 1024/16", "2.10 7.08 21.90"),
        ("2048 MB", "0.01 MB"),
        false,
    ),
    row(("head", "192x192x110"), 12, 16.63, ("2048/64", "528.58"), ("3960 MB", "0.5 MB"), false),
    row(("head", "192x192x110"), 16, 38.71, ("2048/64", "484.31"), ("3960 MB", "0.5 MB"), false),
    row(("head", "192x192x110"), 24, 132.40, ("2048/64", "510.01"), ("3960 MB", "0.5 MB"), false),
    row(("head", "256x256x147"), 16, 101.60, ("2048/64", "704.21"), ("9408 MB", "0.5 MB"), false),
    row(("head", "512x512x294"), 32, 3025.38, ("-", "not calculated"), ("75264 MB", "0.5 MB"), false),
    row(("hand (4 x Xeon 2.8)", "244x124x257"), 24, 514.31, ("2048/64", "633.80"), ("7593 MB", "0.5 MB"), false),
    row(("feet (4 x Xeon 2.8)", "128x64x128"), 12, 15.98, ("2048/64", "320.81"), ("1024 MB", "0.5 MB"), false),
    row(("head", "256x256x147"), 16, 10.26, ("2048/64", "61.60"), ("9408 MB", "0.5 MB"), true),
];
