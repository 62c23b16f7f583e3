//! Colours, marker shapes and text of every chart. Text is drawn by plotters
//! through ab_glyph from Ubuntu Light (Ubuntu Font Licence 1.0), which the
//! `epaint_default_fonts` crate ships, so no system font is needed and `l2`
//! does not read as `12`.

use std::sync::Once;

use plotters::style::{register_font, FontStyle, IntoFont, RGBColor, TextStyle};

pub(super) const FONT: &str = "sans-serif";
pub(super) const BACKGROUND: RGBColor = RGBColor(255, 255, 255);
pub(super) const INK: RGBColor = RGBColor(25, 25, 25);
pub(super) const FRAME: RGBColor = RGBColor(90, 90, 90);
pub(super) const GRID: RGBColor = RGBColor(228, 228, 228);
pub(super) const FRONT: RGBColor = RGBColor(0, 0, 0);

/// Colour-blind-safe colours (Okabe–Ito, without yellow and black, which
/// vanish on white or clash with the Pareto front), then a brown and a grey.
const PALETTE: [[u8; 3]; 8] = [
    [0, 114, 178],
    [213, 94, 0],
    [0, 158, 115],
    [204, 121, 167],
    [230, 159, 0],
    [86, 180, 233],
    [140, 86, 75],
    [127, 127, 127],
];

/// The colour of the `index`-th series when it names none.
pub fn palette_color(index: usize) -> [u8; 3] {
    PALETTE[index % PALETTE.len()]
}

pub(super) fn rgb(color: [u8; 3]) -> RGBColor {
    RGBColor(color[0], color[1], color[2])
}

/// Marker shapes: with the colour, two series differ in shape too.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
}

pub(super) fn series_marker(index: usize) -> Marker {
    [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond][index % 4]
}

/// The font, registered with plotters once per process.
pub(super) fn ensure_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType font shipped by the crate; a failure here
        // would be a broken dependency, caught by every chart test.
        if register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT).is_err() {
            panic!("the chart font (Ubuntu Light from epaint_default_fonts) does not parse");
        }
    });
}

pub(super) fn text(size: f64) -> TextStyle<'static> {
    ensure_font();
    (FONT, size).into_font().color(&INK)
}

/// Width and height of `label` in pixels at `size`.
pub(super) fn text_size(label: &str, size: f64) -> (u32, u32) {
    ensure_font();
    (FONT, size).into_font().box_size(label).unwrap_or((0, 0))
}

/// Label text size for a chart of this size: larger charts, larger text.
pub(super) fn label_size(width: u32, height: u32) -> f64 {
    if width >= 640 && height >= 400 {
        17.0
    } else {
        13.0
    }
}
