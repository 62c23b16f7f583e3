//! Table 1 of the IPSVI paper (Sundén et al. 2011): frame rates with piecewise
//! integration on a GeForce GTX 580, for image sizes 64^2..1024^2 and line widths
//! 1, 2, 4. `sweeplab bench table1` puts our frame rates beside these and
//! compares the ratios, not the absolute numbers.

pub const SIZES: [u32; 5] = [64, 128, 256, 512, 1024];
pub const LINE_WIDTHS: [u32; 3] = [1, 2, 4];

pub struct PaperColumn {
    pub data_set: &'static str,
    /// fps[size index][line width index]
    pub fps: [[f64; 3]; 5],
}

pub const US_BABY: PaperColumn = PaperColumn {
    data_set: "US Baby 199x159x161",
    fps: [
        [50.28, 91.58, 116.28],
        [25.94, 48.59, 62.11],
        [12.70, 25.03, 33.98],
        [5.68, 11.86, 17.60],
        [2.63, 5.44, 8.33],
    ],
};

pub const CT_ENGINE: PaperColumn = PaperColumn {
    data_set: "CT Engine 256x256x256",
    fps: [[33.7, 65.40, 82.17], [16.23, 31.74, 40.83], [7.79, 15.37, 21.16], [3.55, 7.11, 10.74], [1.61, 3.24, 5.02]],
};

pub const CT_GIRAFFE: PaperColumn = PaperColumn {
    data_set: "CT Giraffe 512x512x553 (0.977x0.977x3)",
    fps: [
        [58.28, 110.50, 152.67],
        [27.75, 52.55, 70.42],
        [13.16, 25.85, 32.54],
        [6.42, 12.69, 15.30],
        [3.05, 6.20, 7.75],
    ],
};

impl PaperColumn {
    pub fn fps_at(&self, size: u32, line_width: u32) -> Option<f64> {
        let s = SIZES.iter().position(|&x| x == size)?;
        let l = LINE_WIDTHS.iter().position(|&x| x == line_width)?;
        Some(self.fps[s][l])
    }
}
