//! Axis scales (linear, log10, log2) as one plotters coordinate type, so every
//! chart kind takes any scale on either axis; ticks fall on round values (decades
//! on log10, powers of two on log2) and their labels are short.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

/// How values map onto an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisScale {
    #[default]
    Linear,
    /// Decades evenly spaced; for values spanning orders of magnitude.
    Log10,
    /// Octaves evenly spaced; for sizes that double (image sizes, cache sizes).
    Log2,
}

impl AxisScale {
    /// Position of `value` on the axis; `None` for values this scale cannot show
    /// (NaN, infinities, and zero or negative values on a log scale).
    pub fn transform(self, value: f64) -> Option<f64> {
        if !value.is_finite() {
            return None;
        }
        match self {
            AxisScale::Linear => Some(value),
            AxisScale::Log10 => (value > 0.0).then(|| value.log10()),
            AxisScale::Log2 => (value > 0.0).then(|| value.log2()),
        }
    }

    pub(super) fn inverse(self, position: f64) -> f64 {
        match self {
            AxisScale::Linear => position,
            AxisScale::Log10 => 10f64.powf(position),
            AxisScale::Log2 => position.exp2(),
        }
    }
}

/// The range one axis shows, in transformed units (e.g. log10 of values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ScaledAxis {
    pub scale: AxisScale,
    low: f64,
    high: f64,
}

impl ScaledAxis {
    /// An axis that shows every value the scale can show, with a little room
    /// around them; a unit range when there is none.
    pub fn fitting(scale: AxisScale, values: impl IntoIterator<Item = f64>) -> ScaledAxis {
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for position in values.into_iter().filter_map(|v| scale.transform(v)) {
            low = low.min(position);
            high = high.max(position);
        }
        if low > high {
            return ScaledAxis { scale, low: 0.0, high: 1.0 };
        }
        let pad = if high > low {
            (high - low) * 0.05
        } else if scale == AxisScale::Linear && low != 0.0 {
            low.abs() * 0.1
        } else {
            0.5
        };
        ScaledAxis { scale, low: low - pad, high: high + pad }
    }

    /// An axis from `low` to `high` in values (both showable on the scale).
    pub fn between(scale: AxisScale, low: f64, high: f64) -> ScaledAxis {
        let (low, high) = (scale.transform(low).unwrap_or(0.0), scale.transform(high).unwrap_or(1.0));
        ScaledAxis { scale, low, high: if high > low { high } else { low + 1.0 } }
    }

    /// Whether `value` can be drawn on this axis.
    pub fn shows(&self, value: f64) -> bool {
        self.scale.transform(value).is_some()
    }

    /// The lowest value on the axis (where a bar or an open error bar starts).
    pub fn low_value(&self) -> f64 {
        self.scale.inverse(self.low)
    }

    /// The tick values for at most about `max_points` ticks.
    pub fn key_values(&self, max_points: usize) -> Vec<f64> {
        self.tick_values(max_points)
    }

    fn tick_values(&self, max_points: usize) -> Vec<f64> {
        let max_points = max_points.max(2);
        let inside = |v: &f64| {
            let p = self.scale.transform(*v).unwrap_or(f64::NAN);
            p >= self.low - 1e-9 && p <= self.high + 1e-9
        };
        let powers = |base: f64, multiples: &[f64]| -> Vec<f64> {
            let (first, last) = (self.low.floor() as i64, self.high.ceil() as i64);
            let mut values = Vec::new();
            for exponent in first..=last {
                for m in multiples {
                    values.push(m * base.powi(exponent as i32));
                }
            }
            values.retain(inside);
            values
        };
        let thin = |values: Vec<f64>| -> Vec<f64> {
            let step = values.len().div_ceil(max_points).max(1);
            values.into_iter().step_by(step).collect()
        };
        let ticks = match self.scale {
            AxisScale::Linear => linear_ticks(self.low, self.high, max_points),
            AxisScale::Log10 => {
                let decades = powers(10.0, &[1.0]);
                if decades.len() >= 3 {
                    thin(decades)
                } else {
                    let finer = powers(10.0, &[1.0, 2.0, 5.0]);
                    if finer.len() >= 3 {
                        thin(finer)
                    } else {
                        linear_ticks(self.low_value(), self.scale.inverse(self.high), max_points)
                    }
                }
            }
            AxisScale::Log2 => {
                let octaves = powers(2.0, &[1.0]);
                if octaves.len() >= 2 {
                    thin(octaves)
                } else {
                    linear_ticks(self.low_value(), self.scale.inverse(self.high), max_points)
                }
            }
        };
        ticks.into_iter().filter(inside).collect()
    }
}

/// Round steps (1, 2 or 5 times a power of ten) from `low` to `high`.
fn linear_ticks(low: f64, high: f64, max_points: usize) -> Vec<f64> {
    let span = (high - low).abs();
    if span <= 0.0 || !span.is_finite() {
        return vec![low];
    }
    let rough = span / max_points as f64;
    let magnitude = 10f64.powf(rough.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| span / s <= max_points as f64)
        .unwrap_or(10.0 * magnitude);
    let first = (low / step).ceil() as i64;
    let last = (high / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// A tick label: no trailing zeros, powers of ten as `1e-5` outside 0.001..10000.
pub(super) fn tick_label(value: f64) -> String {
    if value == 0.0 {
        return "0".into();
    }
    let magnitude = value.abs();
    if !(1e-3..1e4).contains(&magnitude) {
        let text = format!("{value:.1e}");
        return text.replace(".0e", "e");
    }
    let text = format!("{value:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    text.to_string()
}

impl Ranged for ScaledAxis {
    // Every chart passes its own label formatter ([`tick_label`]).
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        // Callers draw only values the axis shows; anything else lands far outside.
        let Some(position) = self.scale.transform(*value) else {
            return limit.0.saturating_sub(1 << 20);
        };
        let fraction = (position - self.low) / (self.high - self.low);
        let pixel = f64::from(limit.0) + fraction * f64::from(limit.1 - limit.0);
        pixel.round().clamp(-1e7, 1e7) as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        self.tick_values(hint.max_num_points())
    }

    fn range(&self) -> Range<f64> {
        self.scale.inverse(self.low)..self.scale.inverse(self.high)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axes_tick_on_decades_and_octaves() {
        let axis = ScaledAxis::fitting(AxisScale::Log10, [1e-5, 0.3]);
        assert_eq!(axis.tick_values(10), vec![1e-5, 1e-4, 1e-3, 1e-2, 1e-1]);
        let axis = ScaledAxis::fitting(AxisScale::Log2, [32.0, 512.0]);
        assert_eq!(axis.tick_values(10), vec![32.0, 64.0, 128.0, 256.0, 512.0]);
    }

    #[test]
    fn linear_ticks_are_round_and_within_the_range() {
        let axis = ScaledAxis::fitting(AxisScale::Linear, [0.0, 9.3]);
        assert_eq!(axis.tick_values(6), vec![0.0, 2.0, 4.0, 6.0, 8.0]);
    }

    #[test]
    fn labels_are_short() {
        assert_eq!(tick_label(0.25), "0.25");
        assert_eq!(tick_label(1e-5), "1e-5");
        assert_eq!(tick_label(512.0), "512");
        assert_eq!(tick_label(0.0), "0");
    }
}
