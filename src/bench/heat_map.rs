//! A table of coloured cells for benchmark reports (e.g. case x technique of
//! `sweeplab bench stability`): one row label per row, one column label per
//! column, each cell a colour by its verdict and a short text. Drawn with the
//! embedded font, sized from its labels.

use std::path::Path;

use image::RgbImage;

use super::canvas::{Canvas, PixelRect, Rgb};
use super::error::BenchError;
use super::font::{text_width, GLYPH_HEIGHT};
use super::plot::save_png;

const BACKGROUND: Rgb = [255, 255, 255];
const INK: Rgb = [25, 25, 25];
const FRAME: Rgb = [90, 90, 90];
const PAD: i64 = 6;
const TEXT_SCALE: u32 = 1;
const CELL_HEIGHT: i64 = GLYPH_HEIGHT as i64 + 2 * PAD;
const LARGEST_SIDE: i64 = 8192;

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
    pub fn color(self) -> [u8; 3] {
        match self {
            HeatLevel::Good => [120, 200, 120],
            HeatLevel::Caution => [245, 190, 80],
            HeatLevel::Bad => [225, 90, 80],
            HeatLevel::Empty => [220, 220, 220],
        }
    }

    fn legend(self) -> &'static str {
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
    pub rows: Vec<String>,
    pub columns: Vec<String>,
    pub cells: Vec<Vec<HeatCell>>,
}

/// Draws the heat map and writes it as PNG.
pub fn plot_heat_map(path: impl AsRef<Path>, map: &HeatMap) -> Result<(), BenchError> {
    save_png(path.as_ref(), &render_heat_map(map)?)
}

/// Rows top to bottom, columns left to right, each cell's text centred in it;
/// the legend of the four colours under the grid.
pub fn render_heat_map(map: &HeatMap) -> Result<RgbImage, BenchError> {
    let shape_ok = map.cells.len() == map.rows.len() && map.cells.iter().all(|r| r.len() == map.columns.len());
    if !shape_ok {
        return Err(BenchError::HeatMapShape { rows: map.rows.len(), columns: map.columns.len() });
    }
    let width_of = |t: &str| text_width(t, TEXT_SCALE);
    let label_width = map.rows.iter().map(|r| width_of(r)).max().unwrap_or(0) + 2 * PAD;
    let cell_width = map
        .columns
        .iter()
        .map(|c| width_of(c))
        .chain(map.cells.iter().flatten().map(|c| width_of(&c.text)))
        .max()
        .unwrap_or(0)
        + 2 * PAD;
    let levels = [HeatLevel::Good, HeatLevel::Caution, HeatLevel::Bad, HeatLevel::Empty];
    let legend_width: i64 = levels.iter().map(|l| CELL_HEIGHT + width_of(l.legend()) + 3 * PAD).sum();
    let grid_width = label_width + cell_width * map.columns.len() as i64;
    let width = (grid_width.max(legend_width).max(width_of(&map.title)) + 2 * PAD).max(1);
    let top = 2 * CELL_HEIGHT;
    let height = top + CELL_HEIGHT * (map.rows.len() as i64 + 2);
    if width > LARGEST_SIDE || height > LARGEST_SIDE {
        return Err(BenchError::ChartSize {
            width: width as u32,
            height: height as u32,
            min_width: 1,
            min_height: 1,
            max_side: LARGEST_SIDE as u32,
        });
    }
    let mut canvas = Canvas::new(width as u32, height as u32, BACKGROUND);
    canvas.text(PAD, PAD, &map.title, TEXT_SCALE, INK);
    let text_y = |row_top: i64| row_top + PAD;
    for (c, name) in map.columns.iter().enumerate() {
        let x0 = PAD + label_width + cell_width * c as i64;
        canvas.text(x0 + (cell_width - width_of(name)) / 2, text_y(CELL_HEIGHT), name, TEXT_SCALE, INK);
    }
    for (r, name) in map.rows.iter().enumerate() {
        let y0 = top + CELL_HEIGHT * r as i64;
        canvas.text(PAD + PAD, text_y(y0), name, TEXT_SCALE, INK);
        for (c, cell) in map.cells[r].iter().enumerate() {
            let x0 = PAD + label_width + cell_width * c as i64;
            let rect = PixelRect { x0, y0, x1: x0 + cell_width, y1: y0 + CELL_HEIGHT };
            canvas.fill_rect(rect, cell.level.color());
            canvas.outline_rect(rect, FRAME);
            canvas.text(x0 + (cell_width - width_of(&cell.text)) / 2, text_y(y0), &cell.text, TEXT_SCALE, INK);
        }
    }
    let mut x = PAD;
    let y = top + CELL_HEIGHT * (map.rows.len() as i64 + 1);
    for level in levels {
        let swatch = PixelRect { x0: x, y0: y + PAD / 2, x1: x + CELL_HEIGHT - PAD, y1: y + CELL_HEIGHT - PAD / 2 };
        canvas.fill_rect(swatch, level.color());
        canvas.outline_rect(swatch, FRAME);
        canvas.text(x + CELL_HEIGHT, text_y(y), level.legend(), TEXT_SCALE, INK);
        x += CELL_HEIGHT + width_of(level.legend()) + 3 * PAD;
    }
    Ok(canvas.into_image())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cell(level: HeatLevel, text: &str) -> HeatCell {
        HeatCell { level, text: text.into() }
    }

    #[test]
    fn each_cell_is_drawn_in_its_level_colour_in_its_row_and_column() {
        let map = HeatMap {
            title: "t".into(),
            rows: vec!["first case".into(), "second".into()],
            columns: vec!["dvr".into(), "ipsvi".into()],
            cells: vec![
                vec![cell(HeatLevel::Good, "60 dB"), cell(HeatLevel::Bad, "FAILED")],
                vec![cell(HeatLevel::Caution, "refused"), cell(HeatLevel::Good, "50 dB")],
            ],
        };
        let image = render_heat_map(&map).unwrap();
        let count = |level: HeatLevel| image.pixels().filter(|p| p.0 == level.color()).count();
        // Two good cells against one bad and one caution (each legend swatch adds the same few pixels).
        let (good, bad, caution) = (count(HeatLevel::Good), count(HeatLevel::Bad), count(HeatLevel::Caution));
        assert!(bad > 0 && caution > 0, "{bad} {caution}");
        assert!(good > bad * 3 / 2 && good < bad * 5 / 2, "good {good} bad {bad}");
        // The bad cell is right of the good one on the first row: where the
        // leftmost bad pixel is, the row's good pixels are all to its left.
        let first_bad = image.enumerate_pixels().find(|(_, _, p)| p.0 == HeatLevel::Bad.color()).unwrap();
        let row_good = image
            .enumerate_pixels()
            .filter(|(x, y, p)| *y == first_bad.1 && p.0 == HeatLevel::Good.color() && *x < first_bad.0)
            .count();
        assert!(row_good > 0, "the good cell sits left of the bad one on its row");
    }

    #[test]
    fn a_grid_that_does_not_match_its_labels_is_refused() {
        let map = HeatMap {
            title: "t".into(),
            rows: vec!["a".into(), "b".into()],
            columns: vec!["x".into()],
            cells: vec![vec![cell(HeatLevel::Good, "")]],
        };
        assert!(matches!(render_heat_map(&map), Err(BenchError::HeatMapShape { rows: 2, columns: 1 })));
    }
}
