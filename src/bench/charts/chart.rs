//! What a chart shows besides its data: title, axis labels and scales, size.

use super::scale::AxisScale;
use crate::bench::{BenchError, RunInfo};

const MIN_WIDTH: u32 = 320;
const MIN_HEIGHT: u32 = 200;
pub(super) const MAX_SIDE: u32 = 8192;

/// Titles, axes and size of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: AxisScale,
    pub y_scale: AxisScale,
    pub width: u32,
    pub height: u32,
    /// A line under the chart naming what produced it (device, driver,
    /// commit, date: [`RunInfo::caption`](crate::bench::RunInfo::caption)).
    pub caption: Option<String>,
    /// Names of a categorical x axis: category i is drawn at x = i and its
    /// name stands under it (empty: a numeric axis).
    pub categories: Vec<String>,
    /// A linear y axis reaches 0 (costs read against nothing, their sizes
    /// to scale), not only the range of the data.
    pub y_from_zero: bool,
}

impl Chart {
    /// A 900x600 chart with linear axes.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_scale: AxisScale::Linear,
            y_scale: AxisScale::Linear,
            width: 900,
            height: 600,
            caption: None,
            categories: Vec::new(),
            y_from_zero: false,
        }
    }

    /// A categorical x axis: the points of category i at x = i (offsets within
    /// +-0.5 keep several series apart), its name under it.
    pub fn categories(mut self, names: impl IntoIterator<Item = impl Into<String>>) -> Self {
        self.categories = names.into_iter().map(Into::into).collect();
        self
    }

    pub fn x_scale(mut self, scale: AxisScale) -> Self {
        self.x_scale = scale;
        self
    }

    pub fn y_scale(mut self, scale: AxisScale) -> Self {
        self.y_scale = scale;
        self
    }

    /// A linear y axis from 0 (or below, where the data go there).
    pub fn y_from_zero(mut self) -> Self {
        self.y_from_zero = true;
        self
    }

    pub fn caption(mut self, caption: impl Into<String>) -> Self {
        self.caption = Some(caption.into());
        self
    }

    /// The caption of the run that measured what the chart shows, where known.
    pub fn run_caption(mut self, run: Option<&RunInfo>) -> Self {
        self.caption = run.map(RunInfo::caption);
        self
    }

    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    pub(super) fn check_size(&self) -> Result<(), BenchError> {
        check_size(self.width, self.height, MIN_WIDTH, MIN_HEIGHT)
    }
}

pub(super) fn check_size(width: u32, height: u32, min_width: u32, min_height: u32) -> Result<(), BenchError> {
    let fits = (min_width..=MAX_SIDE).contains(&width) && (min_height..=MAX_SIDE).contains(&height);
    if fits {
        Ok(())
    } else {
        Err(BenchError::ChartSize { width, height, min_width, min_height, max_side: MAX_SIDE })
    }
}
