//! Chart axes: linear or logarithmic scales, the value range shown, and tick
//! positions with labels a person can read at a glance.

/// How values map onto an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisScale {
    #[default]
    Linear,
    /// Decades evenly spaced; for errors spanning orders of magnitude.
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

    fn inverse(self, position: f64) -> f64 {
        match self {
            AxisScale::Linear => position,
            AxisScale::Log10 => 10f64.powf(position),
            AxisScale::Log2 => position.exp2(),
        }
    }
}

/// One tick: where it sits (as a value) and what it says.
#[derive(Debug, Clone, PartialEq)]
pub struct Tick {
    pub value: f64,
    pub label: String,
}

/// The visible range of one axis, in transformed units (e.g. log10 of values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    pub scale: AxisScale,
    low: f64,
    high: f64,
}

impl Axis {
    /// An axis that shows every plottable value with a little room around it.
    pub fn fitting(scale: AxisScale, values: impl IntoIterator<Item = f64>) -> Axis {
        let mut low = f64::INFINITY;
        let mut high = f64::NEG_INFINITY;
        for position in values.into_iter().filter_map(|v| scale.transform(v)) {
            low = low.min(position);
            high = high.max(position);
        }
        if low > high {
            // Nothing to show: a unit range keeps ticks and labels sensible.
            return Axis { scale, low: 0.0, high: 1.0 };
        }
        let pad = if high > low {
            (high - low) * 0.05
        } else if scale == AxisScale::Linear && low != 0.0 {
            low.abs() * 0.1
        } else {
            0.5
        };
        Axis { scale, low: low - pad, high: high + pad }
    }

    /// Where `value` falls from 0 (low end) to 1 (high end); `None` when the
    /// scale cannot show it.
    pub fn fraction(&self, value: f64) -> Option<f64> {
        let position = self.scale.transform(value)?;
        Some((position - self.low) / (self.high - self.low))
    }

    /// About `target` ticks inside the visible range (at least two where the
    /// range allows).
    pub fn ticks(&self, target: usize) -> Vec<Tick> {
        let target = target.max(2);
        let ticks = match self.scale {
            AxisScale::Linear => None,
            AxisScale::Log10 => self.decade_ticks(target),
            AxisScale::Log2 => self.octave_ticks(target),
        };
        // Ranges narrower than two decades or octaves read best with even steps.
        ticks.unwrap_or_else(|| linear_ticks(self.scale.inverse(self.low), self.scale.inverse(self.high), target))
    }

    fn exponents(&self) -> std::ops::RangeInclusive<i32> {
        self.low.ceil() as i32..=self.high.floor() as i32
    }

    fn decade_ticks(&self, target: usize) -> Option<Vec<Tick>> {
        let decades: Vec<i32> = self.exponents().collect();
        if decades.len() >= 2 {
            let stride = decades.len().div_ceil(target).max(1);
            let ticks = decades
                .iter()
                .filter(|&&k| k.rem_euclid(stride as i32) == 0)
                .map(|&k| decimal_tick(1, k))
                .collect::<Vec<_>>();
            if ticks.len() >= 2 {
                return Some(ticks);
            }
            return Some(decades.iter().map(|&k| decimal_tick(1, k)).collect());
        }
        // Within about a decade: 1, 2 and 5 times powers of ten.
        let mut ticks = Vec::new();
        for k in (self.low.floor() as i32)..=(self.high.ceil() as i32) {
            for mantissa in [1, 2, 5] {
                let tick = decimal_tick(mantissa, k);
                if self.fraction(tick.value).is_some_and(|f| (0.0..=1.0).contains(&f)) {
                    ticks.push(tick);
                }
            }
        }
        (ticks.len() >= 2 && ticks.len() <= target + 2).then_some(ticks)
    }

    fn octave_ticks(&self, target: usize) -> Option<Vec<Tick>> {
        let octaves: Vec<i32> = self.exponents().collect();
        if octaves.len() < 2 {
            return None;
        }
        let stride = octaves.len().div_ceil(target).max(1);
        let chosen: Vec<i32> = octaves.iter().copied().filter(|k| k.rem_euclid(stride as i32) == 0).collect();
        let chosen = if chosen.len() >= 2 { chosen } else { octaves };
        Some(
            chosen
                .into_iter()
                .map(|k| {
                    let value = f64::from(k).exp2();
                    let label = if (-10..=30).contains(&k) { value.to_string() } else { format!("2^{k}") };
                    Tick { value, label }
                })
                .collect(),
        )
    }
}

/// mantissa × 10^exponent, parsed from its decimal spelling so the value is
/// the nearest double with no accumulated rounding.
fn decimal_tick(mantissa: i64, exponent: i32) -> Tick {
    let value: f64 = format!("{mantissa}e{exponent}").parse().unwrap_or(f64::NAN);
    let label = if (-4..=5).contains(&exponent) { value.to_string() } else { format!("{mantissa}e{exponent}") };
    Tick { value, label }
}

/// Ticks at 1, 2 or 5 times a power of ten, about `target` of them in
/// `low..=high`, all labelled with the same number of decimals.
fn linear_ticks(low: f64, high: f64, target: usize) -> Vec<Tick> {
    if !(low.is_finite() && high.is_finite()) || high <= low {
        return Vec::new();
    }
    let raw_step = (high - low) / target as f64;
    let mut exponent = raw_step.log10().floor() as i32;
    let mut mantissa =
        [1_i64, 2, 5].into_iter().find(|&m| m as f64 * 10f64.powi(exponent) >= raw_step * 0.999).unwrap_or(10);
    if mantissa == 10 {
        mantissa = 1;
        exponent += 1;
    }
    // step = mantissa × 10^exponent; tick k is at k × step. Dividing an exact
    // integer by an exact power of ten gives the nearest double to the decimal.
    let value_of = |k: i64| {
        let units = (k * mantissa) as f64;
        if exponent >= 0 {
            units * 10f64.powi(exponent)
        } else {
            units / 10f64.powi(-exponent)
        }
    };
    let step = mantissa as f64 * 10f64.powi(exponent);
    let first = (low / step).ceil();
    let last = (high / step).floor();
    // Degenerate ranges (subnormal widths, overflow) would mean absurd counts.
    if !(step > 0.0 && first.is_finite() && last.is_finite() && last - first < 1000.0) {
        return Vec::new();
    }
    let (first, last) = (first as i64, last as i64);
    let decimals = (-exponent).max(0) as usize;
    let largest = low.abs().max(high.abs());
    let scientific = largest >= 1e6 || step < 1e-4;
    (first..=last)
        .map(|k| {
            let value = value_of(k);
            let label = if k == 0 {
                "0".to_owned()
            } else if scientific {
                format!("{value:e}")
            } else {
                format!("{value:.decimals$}")
            };
            Tick { value, label }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(ticks: &[Tick]) -> Vec<&str> {
        ticks.iter().map(|t| t.label.as_str()).collect()
    }

    #[test]
    fn linear_ticks_use_round_steps_and_equal_decimals() {
        assert_eq!(labels(&linear_ticks(0.0, 1.0, 5)), ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        assert_eq!(labels(&linear_ticks(13.0, 61.0, 5)), ["20", "30", "40", "50", "60"]);
        assert_eq!(labels(&linear_ticks(-0.013, 0.012, 5)), ["-0.010", "-0.005", "0", "0.005", "0.010"]);
    }

    #[test]
    fn linear_tick_values_are_exact_decimals() {
        let ticks = linear_ticks(0.0, 0.7, 7);
        assert_eq!(ticks[3].value, 0.3);
    }

    #[test]
    fn log10_axis_over_several_decades_ticks_each_decade() {
        let axis = Axis::fitting(AxisScale::Log10, [0.001, 10.0]);
        assert_eq!(labels(&axis.ticks(8)), ["0.001", "0.01", "0.1", "1", "10"]);
    }

    #[test]
    fn log10_axis_within_a_decade_adds_twos_and_fives() {
        // The 5 % padding reaches below 1.1 to about 0.99, so 1 is inside.
        let axis = Axis::fitting(AxisScale::Log10, [1.1, 9.0]);
        assert_eq!(labels(&axis.ticks(8)), ["1", "2", "5"]);
    }

    #[test]
    fn log2_axis_ticks_powers_of_two() {
        let axis = Axis::fitting(AxisScale::Log2, [256.0, 2048.0]);
        assert_eq!(labels(&axis.ticks(8)), ["256", "512", "1024", "2048"]);
    }

    #[test]
    fn log_scales_refuse_values_they_cannot_show() {
        assert_eq!(AxisScale::Log10.transform(0.0), None);
        assert_eq!(AxisScale::Log2.transform(-1.0), None);
        assert_eq!(AxisScale::Linear.transform(f64::NAN), None);
        let axis = Axis::fitting(AxisScale::Log10, [0.0, -3.0, f64::NAN]);
        assert_eq!(axis.fraction(-3.0), None);
        assert!(!axis.ticks(5).is_empty());
    }

    #[test]
    fn a_single_value_sits_in_the_middle() {
        for scale in [AxisScale::Linear, AxisScale::Log10, AxisScale::Log2] {
            let axis = Axis::fitting(scale, [4.0]);
            let middle = axis.fraction(4.0).unwrap_or(f64::NAN);
            assert!((middle - 0.5).abs() < 1e-12, "{scale:?}: {middle}");
        }
    }
}
