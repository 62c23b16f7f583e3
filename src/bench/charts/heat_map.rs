//! A table of coloured cells (e.g. case x technique of `sweeplab bench
//! stability`): row labels on the left, column labels on top, each cell a
//! colour by its verdict and a short text; the colour scale (the four verdicts)
//! under the grid. Sized from its labels, so none is cut.

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::element::{Rectangle, Text};
use plotters::prelude::{DrawingArea, DrawingBackend};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::Color;

use super::chart::{check_size, MAX_SIDE};
use super::figure::{render, write, Figure, Target, CAPTION_HEIGHT, CAPTION_TEXT};
use super::legend::{Entry, Legend, Sample};
use super::style::{rgb, text, text_size, FRAME};
use crate::bench::BenchError;

const TEXT: f64 = 14.0;
const PAD: u32 = 8;

/// A cell's verdict, and its colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeatLevel {
    /// Within what was asked (green).
    Good,
    /// Explicit, but not a full result: a warning or a refusal (amber).
    Caution,
    /// A failure (red).
    Bad,
    /// Not run (grey).
    Empty,
}

impl HeatLevel {
    pub const ALL: [HeatLevel; 4] = [HeatLevel::Good, HeatLevel::Caution, HeatLevel::Bad, HeatLevel::Empty];

    pub fn color(self) -> [u8; 3] {
        match self {
            HeatLevel::Good => [120, 200, 120],
            HeatLevel::Caution => [245, 190, 80],
            HeatLevel::Bad => [225, 90, 80],
            HeatLevel::Empty => [220, 220, 220],
        }
    }

    pub fn legend(self) -> &'static str {
        match self {
            HeatLevel::Good => "within bound",
            HeatLevel::Caution => "warning or refusal",
            HeatLevel::Bad => "failed",
            HeatLevel::Empty => "not run",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct HeatCell {
    pub level: HeatLevel,
    pub text: String,
}

/// `cells[row][column]`, as many rows as `rows` and columns as `columns`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatMap {
    pub title: String,
    /// A line under the map naming the run ([`crate::bench::RunInfo::caption`]).
    pub caption: Option<String>,
    pub rows: Vec<String>,
    pub columns: Vec<String>,
    pub cells: Vec<Vec<HeatCell>>,
}

/// Draws the heat map and writes it as PNG at `path` and SVG beside it.
pub fn plot_heat_map(path: impl AsRef<Path>, map: &HeatMap) -> Result<(), BenchError> {
    write(path.as_ref(), &Layout::of(map)?)
}

/// Rows top to bottom, columns left to right, each cell's text centred in it.
pub fn render_heat_map(map: &HeatMap) -> Result<RgbImage, BenchError> {
    render(&Layout::of(map)?)
}

struct Layout<'a> {
    map: &'a HeatMap,
    label_width: u32,
    cell_width: u32,
    cell_height: u32,
    top: u32,
    legend: Legend,
    width: u32,
    height: u32,
}

impl<'a> Layout<'a> {
    fn of(map: &'a HeatMap) -> Result<Self, BenchError> {
        let shape_ok = map.cells.len() == map.rows.len() && map.cells.iter().all(|r| r.len() == map.columns.len());
        if !shape_ok {
            return Err(BenchError::HeatMapShape { rows: map.rows.len(), columns: map.columns.len() });
        }
        let width_of = |t: &str| text_size(t, TEXT).0;
        let label_width = map.rows.iter().map(|r| width_of(r)).max().unwrap_or(0) + 2 * PAD;
        let cell_width = map
            .columns
            .iter()
            .map(|c| width_of(c))
            .chain(map.cells.iter().flatten().map(|c| width_of(&c.text)))
            .max()
            .unwrap_or(0)
            + 2 * PAD;
        let cell_height = (TEXT * 1.9) as u32;
        let title_height = (TEXT * 1.3 * 1.8) as u32;
        let top = PAD + title_height + cell_height;
        let entries = HeatLevel::ALL
            .iter()
            .map(|l| Entry { name: l.legend().into(), sample: Sample::Swatch(l.color()) })
            .collect();
        let legend = Legend { entries, text_size: TEXT };
        let grid_width = label_width + cell_width * map.columns.len() as u32;
        let title_width = text_size(&map.title, TEXT * 1.3).0;
        let caption_width = map.caption.as_deref().map_or(0, |c| text_size(c, CAPTION_TEXT).0);
        let width = (grid_width.max(title_width).max(legend.width()).max(caption_width) + 2 * PAD).max(200);
        let caption_height = if map.caption.is_some() { CAPTION_HEIGHT } else { 0 };
        let height = top + cell_height * map.rows.len() as u32 + legend.height() + 2 * PAD + caption_height;
        check_size(width.min(MAX_SIDE + 1), height.min(MAX_SIDE + 1), 1, 1)?;
        Ok(Layout { map, label_width, cell_width, cell_height, top, legend, width, height })
    }
}

impl Figure for Layout<'_> {
    fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn caption(&self) -> Option<&str> {
        self.map.caption.as_deref()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, _: Target) -> Result<(), BenchError> {
        let map = self.map;
        let pad = PAD as i32;
        let (cell_width, cell_height) = (self.cell_width as i32, self.cell_height as i32);
        root.draw(&Text::new(map.title.clone(), (pad, pad), text(TEXT * 1.3)))?;
        let centred = text(TEXT).pos(Pos::new(HPos::Center, VPos::Center));
        let left = pad + self.label_width as i32;
        let top = self.top as i32;
        for (c, name) in map.columns.iter().enumerate() {
            let centre = (left + cell_width * c as i32 + cell_width / 2, top - cell_height / 2);
            root.draw(&Text::new(name.clone(), centre, centred.clone()))?;
        }
        for (r, name) in map.rows.iter().enumerate() {
            let y0 = top + cell_height * r as i32;
            let label = text(TEXT).pos(Pos::new(HPos::Left, VPos::Center));
            root.draw(&Text::new(name.clone(), (2 * pad, y0 + cell_height / 2), label))?;
            for (c, cell) in map.cells[r].iter().enumerate() {
                let x0 = left + cell_width * c as i32;
                let corners = [(x0, y0), (x0 + cell_width, y0 + cell_height)];
                root.draw(&Rectangle::new(corners, rgb(cell.level.color()).filled()))?;
                root.draw(&Rectangle::new(corners, FRAME.stroke_width(1)))?;
                let centre = (x0 + cell_width / 2, y0 + cell_height / 2);
                root.draw(&Text::new(cell.text.clone(), centre, centred.clone()))?;
            }
        }
        let legend_top = top + cell_height * map.rows.len() as i32;
        let area = root.clone().shrink((pad, legend_top), (self.legend.width(), self.legend.height() + 2 * PAD));
        self.legend.draw(&area, 0)
    }
}
