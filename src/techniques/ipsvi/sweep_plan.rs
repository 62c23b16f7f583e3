//! Sweep planning on the host (IPSVI paper, section 4.1): which image lines are
//! rendered in which order, grouped into line blocks, one dispatch per block.
//!
//! A light at infinity in image space gives one sweep of whole rows or columns,
//! whichever is closest to the light's image direction, starting at the border
//! the light comes from. A light anchored at an image point gives four sweeps,
//! one per 45-degree zone around the point (right, left, down, up), outward from
//! a source or inward toward a sink. Lines cover only the volume's projected
//! bounding box; zone lines only the zone's wedge plus the blend margin.

use super::light_anchor::LightAnchor;
use crate::render::image_space::PixelRect;
use glam::Vec2;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineAxis {
    /// Horizontal lines: line index = pixel row, swept along y.
    Rows,
    /// Vertical lines: line index = pixel column, swept along x.
    Columns,
}

/// Zone of a four-way sweep; `All` for a single sweep. The numbers are the
/// shader's zone ids (glsl/ipsvi_line.comp).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Zone {
    All = 0,
    Right = 1,
    Left = 2,
    Down = 3,
    Up = 4,
}

impl Zone {
    pub fn name(self) -> &'static str {
        match self {
            Zone::All => "all",
            Zone::Right => "right",
            Zone::Left => "left",
            Zone::Down => "down",
            Zone::Up => "up",
        }
    }
}

/// Lines `first .. first + width` (ascending indices whatever the sweep order),
/// each covering pixels `span_start .. span_start + span_len` along the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineBlock {
    pub first: u32,
    pub width: u32,
    pub span_start: u32,
    pub span_len: u32,
    /// The line of the block farthest from the light: the cache advances to it.
    pub last_line: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    pub zone: Zone,
    pub axis: LineAxis,
    /// Line indices increase as the sweep proceeds.
    pub ascending: bool,
    pub blocks: Vec<LineBlock>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SweepPlan {
    pub anchor: LightAnchor,
    pub bbox: PixelRect,
    pub sweeps: Vec<Sweep>,
    /// Width in pixels over which neighbouring zones are blended.
    pub blend_px: f32,
    /// Set when no proper sweep direction exists (light parallel to the view).
    pub fallback: Option<&'static str>,
}

impl SweepPlan {
    pub fn lines(&self) -> u32 {
        self.sweeps.iter().flat_map(|s| &s.blocks).map(|b| b.width).sum()
    }

    pub fn dispatches(&self) -> u32 {
        self.sweeps.iter().map(|s| s.blocks.len() as u32).sum()
    }
}

/// Below this image-space speed the light is taken as parallel to the view.
const PARALLEL_EPS: f32 = 1e-4;

pub const PARALLEL_FALLBACK: &str = "light parallel to the view direction: no image-space sweep direction exists, so rows are swept top to bottom and piecewise integration carries each sample's whole path to the light";

pub fn plan(bbox: PixelRect, anchor: LightAnchor, line_width: u32, blend_px: f32) -> SweepPlan {
    let lw = line_width.clamp(1, super::settings::MAX_LINE_WIDTH);
    let mut out = SweepPlan { anchor, bbox, sweeps: Vec::new(), blend_px, fallback: None };
    if bbox.is_empty() {
        return out;
    }
    match anchor {
        LightAnchor::AtInfinity(d) => {
            let (axis, ascending) = if d.length() < PARALLEL_EPS {
                out.fallback = Some(PARALLEL_FALLBACK);
                (LineAxis::Rows, true)
            } else if d.x.abs() >= d.y.abs() {
                (LineAxis::Columns, d.x > 0.0)
            } else {
                (LineAxis::Rows, d.y > 0.0)
            };
            let (lines, span) = match axis {
                LineAxis::Columns => (bbox.x0..bbox.x1, (bbox.y0, bbox.y1)),
                LineAxis::Rows => (bbox.y0..bbox.y1, (bbox.x0, bbox.x1)),
            };
            let mut order: Vec<(u32, (u32, u32))> = lines.map(|l| (l, span)).collect();
            if !ascending {
                order.reverse();
            }
            out.sweeps.push(Sweep { zone: Zone::All, axis, ascending, blocks: blocks(&order, lw) });
        }
        LightAnchor::Source(p) | LightAnchor::Sink(p) => {
            let outward = matches!(anchor, LightAnchor::Source(_));
            for zone in [Zone::Right, Zone::Left, Zone::Down, Zone::Up] {
                let mut order = zone_lines(bbox, p, zone, blend_px);
                // Zone lines come out ordered from the anchor outward.
                if !outward {
                    order.reverse();
                }
                if order.is_empty() {
                    continue;
                }
                let axis = if matches!(zone, Zone::Right | Zone::Left) { LineAxis::Columns } else { LineAxis::Rows };
                let away_ascending = matches!(zone, Zone::Right | Zone::Down);
                out.sweeps.push(Sweep { zone, axis, ascending: away_ascending == outward, blocks: blocks(&order, lw) });
            }
        }
    }
    out
}

/// The lines of one zone, from the anchor outward, each with its pixel span.
fn zone_lines(bbox: PixelRect, p: Vec2, zone: Zone, blend: f32) -> Vec<(u32, (u32, u32))> {
    // Along the zone's axis: the line index range and the distance of a line from
    // the anchor; across it: which pixels of the line lie in the zone's wedge
    // |across| <= along + blend.
    let (lo, hi, centre_along, centre_across, across_lo, across_hi) = match zone {
        Zone::Right | Zone::Left => (bbox.x0, bbox.x1, p.x, p.y, bbox.y0, bbox.y1),
        _ => (bbox.y0, bbox.y1, p.y, p.x, bbox.x0, bbox.x1),
    };
    let positive = matches!(zone, Zone::Right | Zone::Down);
    let mut lines = Vec::new();
    for l in lo..hi {
        let along = (l as f32 + 0.5 - centre_along) * if positive { 1.0 } else { -1.0 };
        let reach = along + blend;
        if reach < 0.0 {
            continue;
        }
        let a = (centre_across - reach - 0.5).ceil().max(across_lo as f32);
        let b = (centre_across + reach - 0.5).floor().min(across_hi as f32 - 1.0);
        if a > b {
            continue;
        }
        lines.push((l, (a as u32, b as u32 + 1)));
    }
    if !positive {
        lines.reverse();
    }
    lines
}

/// Groups lines (in sweep order) into blocks of `lw` lines; the first block is a
/// single line (it starts the piecewise integration, section 4.4).
fn blocks(order: &[(u32, (u32, u32))], lw: u32) -> Vec<LineBlock> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < order.len() {
        let width = if out.is_empty() { 1 } else { lw as usize }.min(order.len() - i);
        let chunk = &order[i..i + width];
        let first = chunk.iter().map(|c| c.0).min().unwrap_or(0);
        let start = chunk.iter().map(|c| c.1 .0).min().unwrap_or(0);
        let end = chunk.iter().map(|c| c.1 .1).max().unwrap_or(0);
        out.push(LineBlock {
            first,
            width: width as u32,
            span_start: start,
            span_len: end - start,
            last_line: chunk[width - 1].0,
        });
        i += width;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> PixelRect {
        PixelRect { x0, y0, x1, y1 }
    }

    #[test]
    fn directional_light_sweeps_whole_lines_from_the_lit_border() {
        let p = plan(rect(10, 20, 50, 40), LightAnchor::AtInfinity(Vec2::new(-3.0, 1.0)), 4, 2.0);
        assert_eq!(p.sweeps.len(), 1);
        let s = &p.sweeps[0];
        assert_eq!(s.axis, LineAxis::Columns);
        assert!(!s.ascending, "light travels toward -x: start at the right border");
        assert_eq!(s.blocks[0], LineBlock { first: 49, width: 1, span_start: 20, span_len: 20, last_line: 49 });
        assert_eq!(s.blocks[1].first, 45);
        assert_eq!(s.blocks[1].width, 4);
        assert_eq!(s.blocks[1].last_line, 45);
        assert_eq!(p.lines(), 40);
        assert_eq!(p.dispatches(), 1 + 39usize.div_ceil(4) as u32);
    }

    #[test]
    fn rows_when_the_light_is_mostly_vertical() {
        let p = plan(rect(0, 0, 8, 8), LightAnchor::AtInfinity(Vec2::new(0.5, 2.0)), 1, 2.0);
        assert_eq!(p.sweeps[0].axis, LineAxis::Rows);
        assert!(p.sweeps[0].ascending);
        assert_eq!(p.sweeps[0].blocks.iter().map(|b| b.first).collect::<Vec<_>>(), (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn parallel_light_falls_back_and_still_covers_the_box() {
        let p = plan(rect(0, 0, 8, 8), LightAnchor::AtInfinity(Vec2::ZERO), 2, 2.0);
        assert!(p.fallback.is_some());
        assert_eq!(p.lines(), 8);
    }

    #[test]
    fn source_in_the_middle_gives_four_zones_covering_every_pixel() {
        let bbox = rect(0, 0, 32, 24);
        let p = plan(bbox, LightAnchor::Source(Vec2::new(13.3, 9.7)), 3, 1.5);
        assert_eq!(p.sweeps.len(), 4);
        let mut covered = vec![0u32; 32 * 24];
        for s in &p.sweeps {
            for b in &s.blocks {
                for l in b.first..b.first + b.width {
                    for t in b.span_start..b.span_start + b.span_len {
                        let (x, y) = if s.axis == LineAxis::Columns { (l, t) } else { (t, l) };
                        covered[(y * 32 + x) as usize] += 1;
                    }
                }
            }
            // Outward: the first block is next to the anchor.
            let first = s.blocks[0].first as f32 + 0.5;
            let anchor = if s.axis == LineAxis::Columns { 13.3 } else { 9.7 };
            assert!((first - anchor).abs() <= 1.0 + 1.5, "{:?} starts at {first}", s.zone);
        }
        assert!(covered.iter().all(|&c| c >= 1), "some pixel is in no zone");
    }

    #[test]
    fn sink_sweeps_run_toward_the_anchor() {
        let p = plan(rect(0, 0, 32, 32), LightAnchor::Sink(Vec2::new(16.0, 16.0)), 1, 1.0);
        for s in &p.sweeps {
            let first = s.blocks[0].first as f32 + 0.5;
            let last = s.blocks.last().unwrap().first as f32 + 0.5;
            assert!((first - 16.0).abs() > (last - 16.0).abs(), "{:?}", s.zone);
        }
    }

    #[test]
    fn anchor_outside_the_box_uses_only_the_zones_that_reach_it() {
        let p = plan(rect(40, 0, 60, 10), LightAnchor::Source(Vec2::new(10.0, 5.0)), 1, 1.0);
        assert!(p.sweeps.iter().all(|s| s.zone == Zone::Right || s.blocks.iter().all(|b| b.span_len > 0)));
        assert!(p.sweeps.iter().any(|s| s.zone == Zone::Right));
        assert!(!p.sweeps.iter().any(|s| s.zone == Zone::Left));
    }

    #[test]
    fn empty_box_plans_nothing() {
        assert_eq!(plan(rect(5, 5, 5, 9), LightAnchor::AtInfinity(Vec2::X), 1, 1.0).dispatches(), 0);
    }
}
