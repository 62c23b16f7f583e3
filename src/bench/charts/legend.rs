//! A legend sized from its text (no label is cut), beside the plot when it
//! fits in a third of the width, under it otherwise.

use plotters::coord::Shift;
use plotters::element::{Circle, PathElement, Rectangle, Text};
use plotters::prelude::{DrawingArea, DrawingBackend};
use plotters::style::{Color, RGBColor};

use super::marker::draw_marker;
use super::style::{rgb, text, text_size, Marker, FRAME, FRONT, INK};
use crate::bench::BenchError;

const PAD: u32 = 10;
const SAMPLE_WIDTH: u32 = 34;
pub(super) const MARKER_RADIUS: i32 = 5;

pub(super) enum Sample {
    /// A series: its marker, with a line through it for line charts.
    Series { color: [u8; 3], marker: Marker, line: bool },
    /// The Pareto front's step line and ring.
    Front,
    /// What a hollow marker means.
    Hollow,
    /// A filled square of one colour (a bar segment, a heat-map level).
    Swatch([u8; 3]),
    /// Text only.
    Note,
}

pub(super) struct Entry {
    pub name: String,
    pub sample: Sample,
}

pub(super) struct Legend {
    pub entries: Vec<Entry>,
    pub text_size: f64,
}

impl Legend {
    fn row_height(&self) -> u32 {
        (self.text_size * 1.6) as u32
    }

    pub fn width(&self) -> u32 {
        let widest = self.entries.iter().map(|e| text_size(&e.name, self.text_size).0).max().unwrap_or(0);
        widest + SAMPLE_WIDTH + 5 * PAD
    }

    pub fn height(&self) -> u32 {
        self.entries.len() as u32 * self.row_height() + 3 * PAD
    }

    /// The plot's area, with the legend drawn beside it (when it takes at most
    /// 40 % of the width) or under it.
    pub fn place<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<DrawingArea<DB, Shift>, BenchError> {
        if self.entries.is_empty() {
            return Ok(root.clone());
        }
        let (width, height) = root.dim_in_pixel();
        if self.width() * 5 <= width * 2 {
            let (plot, legend) = root.split_horizontally(width - self.width());
            self.draw(&legend, 3 * PAD as i32)?;
            Ok(plot)
        } else {
            let (plot, legend) = root.split_vertically(height.saturating_sub(self.height()));
            self.draw(&legend.margin(0, 0, PAD, 0), 0)?;
            Ok(plot)
        }
    }

    /// Draws the legend's box from `top` pixels down `area`.
    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, top: i32) -> Result<(), BenchError> {
        let (width, _) = area.dim_in_pixel();
        let box_width = self.width().min(width) as i32 - PAD as i32;
        let top = top + PAD as i32;
        let box_bottom = top + self.height() as i32 - 2 * PAD as i32;
        area.draw(&Rectangle::new([(0, top - PAD as i32 / 2), (box_width, box_bottom)], FRAME.stroke_width(1)))?;
        for (row, entry) in self.entries.iter().enumerate() {
            let middle = top + PAD as i32 / 2 + row as i32 * self.row_height() as i32 + self.row_height() as i32 / 2;
            let (x0, x1) = (PAD as i32, (PAD + SAMPLE_WIDTH) as i32);
            let centre = (x0 + x1) / 2;
            match entry.sample {
                Sample::Series { color, marker, line } => {
                    if line {
                        area.draw(&PathElement::new(vec![(x0, middle), (x1, middle)], rgb(color).stroke_width(2)))?;
                    }
                    draw_marker(area, (centre, middle), marker, rgb(color), MARKER_RADIUS, false)?;
                }
                Sample::Front => {
                    area.draw(&PathElement::new(vec![(x0, middle), (x1, middle)], FRONT.stroke_width(2)))?;
                    area.draw(&Circle::new((centre, middle), MARKER_RADIUS + 5, FRONT.stroke_width(2)))?;
                }
                Sample::Hollow => draw_marker(area, (centre, middle), Marker::Circle, INK, MARKER_RADIUS, true)?,
                Sample::Swatch(color) => {
                    let half = (self.text_size / 2.0) as i32;
                    let corners = [(centre - half, middle - half), (centre + half, middle + half)];
                    area.draw(&Rectangle::new(corners, rgb(color).filled()))?;
                    area.draw(&Rectangle::new(corners, FRAME.stroke_width(1)))?;
                }
                Sample::Note => {}
            }
            let ink: RGBColor = if matches!(entry.sample, Sample::Note) { FRAME } else { INK };
            let label_top = middle - text_size(&entry.name, self.text_size).1 as i32 / 2;
            area.draw(&Text::new(entry.name.clone(), (x1 + PAD as i32, label_top), text(self.text_size).color(&ink)))?;
        }
        Ok(())
    }
}
