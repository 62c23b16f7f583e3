//! Drawing one marker (filled, or hollow when its interval holds 0) at a
//! point of any coordinate system.

use plotters::coord::CoordTranslate;
use plotters::element::{Circle, EmptyElement, PathElement, Polygon};
use plotters::prelude::{DrawingArea, DrawingBackend};
use plotters::style::{Color, RGBColor};

use super::style::{Marker, BACKGROUND};
use crate::bench::BenchError;

fn outline(marker: Marker, radius: i32) -> Vec<(i32, i32)> {
    let r = radius;
    match marker {
        Marker::Circle => Vec::new(),
        Marker::Square => vec![(-r + 1, -r + 1), (r - 1, -r + 1), (r - 1, r - 1), (-r + 1, r - 1)],
        Marker::Triangle => vec![(0, -r - 1), (r + 1, r - 1), (-r - 1, r - 1)],
        Marker::Diamond => vec![(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)],
    }
}

pub(super) fn draw_marker<DB: DrawingBackend, CT: CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    at: CT::From,
    marker: Marker,
    color: RGBColor,
    radius: i32,
    hollow: bool,
) -> Result<(), BenchError>
where
    CT::From: Clone,
{
    let at = || EmptyElement::at(at.clone());
    match (marker, hollow) {
        (Marker::Circle, false) => area.draw(&(at() + Circle::new((0, 0), radius, color.filled())))?,
        (Marker::Circle, true) => {
            area.draw(&(at() + Circle::new((0, 0), radius, BACKGROUND.filled())))?;
            area.draw(&(at() + Circle::new((0, 0), radius, color.stroke_width(2))))?;
        }
        (_, false) => area.draw(&(at() + Polygon::new(outline(marker, radius), color.filled())))?,
        (_, true) => {
            let mut closed = outline(marker, radius);
            area.draw(&(at() + Polygon::new(closed.clone(), BACKGROUND.filled())))?;
            closed.push(closed[0]);
            area.draw(&(at() + PathElement::new(closed, color.stroke_width(2))))?;
        }
    }
    Ok(())
}
