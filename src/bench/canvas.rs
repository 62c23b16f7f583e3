//! Raster drawing primitives for charts: rectangles, thick lines, markers and
//! bitmap text on an RGB image. Everything is clipped, so no coordinate a chart
//! computes can index outside the image.

use image::RgbImage;

use super::font::{glyph_for, ADVANCE, GLYPH_HEIGHT, GLYPH_WIDTH};

pub type Rgb = [u8; 3];

/// Filled point shapes; series differ in shape as well as colour, so charts stay
/// readable in greyscale and for colour-blind readers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
}

/// A rectangle of pixels, `x0..x1` by `y0..y1` (end exclusive).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelRect {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
}

impl PixelRect {
    pub fn width(&self) -> i64 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> i64 {
        self.y1 - self.y0
    }

    fn intersect(&self, other: &PixelRect) -> PixelRect {
        PixelRect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }

    fn contains(&self, x: i64, y: i64) -> bool {
        x >= self.x0 && x < self.x1 && y >= self.y0 && y < self.y1
    }
}

pub struct Canvas {
    image: RgbImage,
    clip: PixelRect,
}

impl Canvas {
    pub fn new(width: u32, height: u32, background: Rgb) -> Self {
        let image = RgbImage::from_pixel(width, height, image::Rgb(background));
        Canvas { clip: Self::full_rect(width, height), image }
    }

    fn full_rect(width: u32, height: u32) -> PixelRect {
        PixelRect { x0: 0, y0: 0, x1: i64::from(width), y1: i64::from(height) }
    }

    pub fn into_image(self) -> RgbImage {
        self.image
    }

    /// Restricts drawing to `rect` (within the image) until [`Canvas::unclip`].
    pub fn clip_to(&mut self, rect: PixelRect) {
        self.clip = Self::full_rect(self.image.width(), self.image.height()).intersect(&rect);
    }

    pub fn unclip(&mut self) {
        self.clip = Self::full_rect(self.image.width(), self.image.height());
    }

    pub fn put(&mut self, x: i64, y: i64, color: Rgb) {
        if self.clip.contains(x, y) {
            // In range: the clip rectangle lies inside the image.
            self.image.put_pixel(x as u32, y as u32, image::Rgb(color));
        }
    }

    pub fn fill_rect(&mut self, rect: PixelRect, color: Rgb) {
        let r = rect.intersect(&self.clip);
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                self.put(x, y, color);
            }
        }
    }

    pub fn outline_rect(&mut self, rect: PixelRect, color: Rgb) {
        let (x0, y0, x1, y1) = (rect.x0, rect.y0, rect.x1 - 1, rect.y1 - 1);
        for x in x0..=x1 {
            self.put(x, y0, color);
            self.put(x, y1, color);
        }
        for y in y0..=y1 {
            self.put(x0, y, color);
            self.put(x1, y, color);
        }
    }

    /// A line `thickness` pixels wide. Ends are clipped to the clip rectangle
    /// first, so far-away or non-finite ends cost nothing.
    pub fn line(&mut self, from: (f64, f64), to: (f64, f64), thickness: u32, color: Rgb) {
        let margin = f64::from(thickness);
        let bounds = (
            self.clip.x0 as f64 - margin,
            self.clip.y0 as f64 - margin,
            self.clip.x1 as f64 + margin,
            self.clip.y1 as f64 + margin,
        );
        let Some((a, b)) = clip_segment(from, to, bounds) else {
            return;
        };
        let (mut x, mut y) = (a.0.round() as i64, a.1.round() as i64);
        let (x_end, y_end) = (b.0.round() as i64, b.1.round() as i64);
        let dx = (x_end - x).abs();
        let dy = -(y_end - y).abs();
        let step_x = if x < x_end { 1 } else { -1 };
        let step_y = if y < y_end { 1 } else { -1 };
        let mut err = dx + dy;
        let low = -(i64::from(thickness.max(1)) - 1) / 2;
        let high = i64::from(thickness.max(1)) / 2;
        // Thicken across the main direction only, so lines keep their length.
        let mostly_horizontal = dx >= -dy;
        loop {
            for offset in low..=high {
                if mostly_horizontal {
                    self.put(x, y + offset, color);
                } else {
                    self.put(x + offset, y, color);
                }
            }
            if x == x_end && y == y_end {
                break;
            }
            let doubled = 2 * err;
            if doubled >= dy {
                err += dy;
                x += step_x;
            }
            if doubled <= dx {
                err += dx;
                y += step_y;
            }
        }
    }

    /// A filled marker of about `radius` pixels centred on `center`.
    pub fn marker(&mut self, marker: Marker, center: (f64, f64), radius: f64, color: Rgb) {
        self.fill_shape(center, radius, color, |dx, dy| match marker {
            Marker::Circle => dx * dx + dy * dy <= radius * radius,
            Marker::Square => dx.abs() <= radius * 0.85 && dy.abs() <= radius * 0.85,
            Marker::Diamond => dx.abs() + dy.abs() <= radius * 1.2,
            // Apex up at -radius, base at 0.8 radius with half-width radius.
            Marker::Triangle => dy >= -radius && dy <= radius * 0.8 && dx.abs() <= (dy + radius) / 1.8,
        });
    }

    /// A circle outline between `radius - thickness` and `radius`.
    pub fn ring(&mut self, center: (f64, f64), radius: f64, thickness: f64, color: Rgb) {
        let inner = (radius - thickness).max(0.0);
        self.fill_shape(center, radius, color, |dx, dy| {
            let d2 = dx * dx + dy * dy;
            d2 <= radius * radius && d2 >= inner * inner
        });
    }

    fn fill_shape(&mut self, center: (f64, f64), radius: f64, color: Rgb, inside: impl Fn(f64, f64) -> bool) {
        if !(center.0.is_finite() && center.1.is_finite() && radius.is_finite()) {
            return;
        }
        let reach = radius.ceil() as i64 + 1;
        let (cx, cy) = (center.0.round() as i64, center.1.round() as i64);
        for y in cy - reach..=cy + reach {
            for x in cx - reach..=cx + reach {
                if inside(x as f64 - center.0, y as f64 - center.1) {
                    self.put(x, y, color);
                }
            }
        }
    }

    /// Text with its top-left corner at (x, y), each font pixel `scale` pixels.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: u32, color: Rgb) {
        self.draw_glyphs(text, scale, color, |u, v| (x + u, y + v));
    }

    /// Text turned a quarter turn counter-clockwise, read bottom to top, with
    /// what would be its top-left corner at (x, y): it spans x..x+height and
    /// y-width..y.
    pub fn text_vertical(&mut self, x: i64, y: i64, text: &str, scale: u32, color: Rgb) {
        self.draw_glyphs(text, scale, color, |u, v| (x + v, y - u));
    }

    /// Draws glyph pixels at text coordinates (u along the text, v down the
    /// glyph), placed on the image by `place`.
    fn draw_glyphs(&mut self, text: &str, scale: u32, color: Rgb, place: impl Fn(i64, i64) -> (i64, i64)) {
        let scale = i64::from(scale.max(1));
        for (index, c) in text.chars().enumerate() {
            let glyph = glyph_for(c);
            let origin = index as i64 * i64::from(ADVANCE) * scale;
            for (row, bits) in glyph.iter().enumerate().take(GLYPH_HEIGHT as usize) {
                for column in 0..GLYPH_WIDTH {
                    if bits & (1 << (GLYPH_WIDTH - 1 - column)) == 0 {
                        continue;
                    }
                    for sy in 0..scale {
                        for sx in 0..scale {
                            let u = origin + i64::from(column) * scale + sx;
                            let v = row as i64 * scale + sy;
                            let (px, py) = place(u, v);
                            self.put(px, py, color);
                        }
                    }
                }
            }
        }
    }
}

/// Liang–Barsky clipping of a segment to `(x0, y0, x1, y1)`; `None` when the
/// segment misses the box or has a non-finite end.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, y0, x1, y1): (f64, f64, f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    if ![a.0, a.1, b.0, b.1].iter().all(|v| v.is_finite()) {
        return None;
    }
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    // Each end remembers the box side that cut it and lands exactly on it:
    // a + t·(b − a) alone loses the end to cancellation for huge coordinates.
    let mut enter = (0.0_f64, None);
    let mut leave = (1.0_f64, None);
    let sides = [
        (-dx, a.0 - x0, Side::X(x0)),
        (dx, x1 - a.0, Side::X(x1)),
        (-dy, a.1 - y0, Side::Y(y0)),
        (dy, y1 - a.1, Side::Y(y1)),
    ];
    for (p, q, side) in sides {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 && t > enter.0 {
                enter = (t, Some(side));
            } else if p > 0.0 && t < leave.0 {
                leave = (t, Some(side));
            }
        }
    }
    if enter.0 > leave.0 {
        return None;
    }
    let point_at = |(t, side): (f64, Option<Side>)| {
        let mut point = (a.0 + t * dx, a.1 + t * dy);
        match side {
            Some(Side::X(x)) => point.0 = x,
            Some(Side::Y(y)) => point.1 = y,
            None => {}
        }
        point
    };
    Some((point_at(enter), point_at(leave)))
}

#[derive(Clone, Copy)]
enum Side {
    X(f64),
    Y(f64),
}

#[cfg(test)]
mod tests {
    use super::*;

    const WHITE: Rgb = [255, 255, 255];
    const RED: Rgb = [255, 0, 0];

    fn count(canvas: Canvas, color: Rgb) -> usize {
        canvas.into_image().pixels().filter(|p| p.0 == color).count()
    }

    #[test]
    fn a_horizontal_line_covers_its_length_times_its_thickness() {
        let mut canvas = Canvas::new(50, 50, WHITE);
        canvas.line((10.0, 20.0), (29.0, 20.0), 2, RED);
        assert_eq!(count(canvas, RED), 20 * 2);
    }

    #[test]
    fn lines_far_outside_or_non_finite_draw_nothing_and_do_not_hang() {
        let mut canvas = Canvas::new(20, 20, WHITE);
        canvas.line((-1e300, -5.0), (1e300, -5.0), 1, RED);
        canvas.line((f64::NAN, 3.0), (4.0, 4.0), 1, RED);
        assert_eq!(count(canvas, RED), 0);
        let mut canvas = Canvas::new(20, 20, WHITE);
        canvas.line((-1e300, 5.0), (1e300, 5.0), 1, RED);
        assert_eq!(count(canvas, RED), 20);
    }

    #[test]
    fn clipping_keeps_drawing_inside_the_clip_rectangle() {
        let mut canvas = Canvas::new(30, 30, WHITE);
        canvas.clip_to(PixelRect { x0: 10, y0: 10, x1: 20, y1: 20 });
        canvas.fill_rect(PixelRect { x0: 0, y0: 0, x1: 30, y1: 30 }, RED);
        assert_eq!(count(canvas, RED), 100);
    }

    #[test]
    fn text_and_vertical_text_draw_the_same_ink() {
        let mut horizontal = Canvas::new(80, 80, WHITE);
        horizontal.text(2, 2, "Ab1", 2, RED);
        let mut vertical = Canvas::new(80, 80, WHITE);
        vertical.text_vertical(2, 70, "Ab1", 2, RED);
        let ink = count(horizontal, RED);
        assert!(ink > 0);
        assert_eq!(ink, count(vertical, RED));
    }

    #[test]
    fn a_ring_leaves_its_centre_empty() {
        let mut canvas = Canvas::new(40, 40, WHITE);
        canvas.ring((20.0, 20.0), 10.0, 2.0, RED);
        let image = canvas.into_image();
        assert_eq!(image.get_pixel(20, 20).0, WHITE);
        assert_eq!(image.get_pixel(30, 20).0, RED);
    }
}
