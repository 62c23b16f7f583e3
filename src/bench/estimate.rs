//! Estimates with their 95 % intervals: the median of repeated timings, the
//! median of paired differences (an overhead against its baseline, round by
//! round), the slope of a line fitted round by round, and the shift between
//! two such slopes (a Hodges-Lehmann estimate, [`super::shift`]).
//!
//! The interval of a median is the exact order-statistics (sign-test)
//! interval: for n samples it is [x(k), x(n+1-k)] with the largest k whose
//! coverage 1 - 2 P(Binomial(n, 1/2) < k) is still at least 95 %. It assumes
//! nothing about the shape of the noise (timings are skewed: a machine adds
//! time, it never takes it away) and needs at least [`MIN_SAMPLES`] samples.

use serde::{Deserialize, Serialize};

/// The confidence of every interval the benches report.
pub const CONFIDENCE: f64 = 0.95;

/// The fewest samples whose order-statistics interval of the median reaches
/// 95 % (with 5, even [min, max] covers only 93.75 %).
pub const MIN_SAMPLES: usize = 6;

/// Why an estimate cannot be made.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EstimateError {
    #[error("{} cannot give a 95 % interval of a median: it needs at least {needed}", crate::plural::count(*.got as u64, "sample", "samples"))]
    TooFewSamples { got: usize, needed: usize },
    #[error("a sample is not a finite number")]
    NotFinite,
    #[error("the paired series have {a} and {b} rounds; pairs need the same rounds")]
    Unpaired { a: usize, b: usize },
    #[error("a slope needs at least two distinct x values in every round")]
    NoSlope,
}

/// A point estimate and its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
    /// Samples (or rounds) behind it.
    pub n: usize,
}

/// How an estimate of a cost reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The interval lies above 0: a cost.
    Cost,
    /// The interval holds 0: no difference can be told from noise.
    WithinNoise,
    /// The interval lies below 0: cheaper than the baseline, which is not a
    /// cost (reported as such, never as a negative cost).
    BelowBaseline,
}

impl Verdict {
    /// How a report reads it: `cost`, `within noise`, `below baseline`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Cost => "cost",
            Verdict::WithinNoise => "within noise",
            Verdict::BelowBaseline => "below baseline",
        }
    }
}

impl Estimate {
    pub fn half_width(&self) -> f64 {
        (self.hi - self.lo) / 2.0
    }

    /// Whether the interval holds 0.
    pub fn within_noise(&self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }

    pub fn verdict(&self) -> Verdict {
        if self.within_noise() {
            Verdict::WithinNoise
        } else if self.lo > 0.0 {
            Verdict::Cost
        } else {
            Verdict::BelowBaseline
        }
    }

    /// Whether the interval is as narrow as asked: a half-width of at most
    /// `relative` times the estimate, or at most `absolute` (in its unit).
    pub fn precise_to(&self, relative: f64, absolute: f64) -> bool {
        let h = self.half_width();
        h <= absolute || h <= relative * self.value.abs()
    }

    /// About how many samples would make the interval as narrow as
    /// [`Estimate::precise_to`] asks, from its width now (an interval of a
    /// median narrows as one over the square root of the samples): an
    /// extrapolation for planning, not a promise. None without a width.
    pub fn samples_for(&self, relative: f64, absolute: f64) -> Option<usize> {
        let h = self.half_width();
        let target = absolute.max(relative * self.value.abs());
        (h > 0.0 && target > 0.0 && self.n > 0).then(|| (self.n as f64 * (h / target).powi(2)).ceil() as usize)
    }

    /// The same estimate in another unit (e.g. ms -> us).
    pub fn scaled(&self, factor: f64) -> Estimate {
        let (a, b) = (self.lo * factor, self.hi * factor);
        Estimate { value: self.value * factor, lo: a.min(b), hi: a.max(b), n: self.n }
    }

    /// `12.3 (95 % CI 11.0-13.9)`, or `within noise (95 % CI -1.2-0.8)`.
    pub fn describe(&self, unit: &str) -> String {
        let ci = format!("95 % CI {}-{}", readable(self.lo), readable(self.hi));
        match self.verdict() {
            Verdict::Cost => format!("+{} {unit} ({ci})", readable(self.value)),
            Verdict::WithinNoise => format!("within noise ({ci} {unit})"),
            Verdict::BelowBaseline => format!("below the baseline by {} {unit} ({ci})", readable(-self.value)),
        }
    }
}

/// Three significant digits, enough to compare runs.
pub fn readable(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if a >= 100.0 || a == 0.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

/// The median of `values` in any order: the one median every bench reports
/// (see [`median_of`]); NaN for none.
pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    median_of(&sorted)
}

/// The median of sorted values: the middle value, or for an even count the
/// mean of the two middle values. The sample median, symmetric in the two
/// middle order statistics, so it lies at the centre of the sign-test
/// interval's ranks and agrees with [`median_estimate`]'s value (an upper
/// median would sit half a gap above it on even counts). NaN for none.
pub fn median_of(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0
    }
}

/// P(Binomial(n, 1/2) <= k), summed in the log domain so large n do not underflow.
fn binomial_half_cdf(n: usize, k: usize) -> f64 {
    let ln_half_n = n as f64 * 0.5f64.ln();
    let mut ln_choose = 0.0f64; // ln C(n, 0)
    let mut sum = 0.0;
    for i in 0..=k.min(n) {
        if i > 0 {
            ln_choose += ((n - i + 1) as f64).ln() - (i as f64).ln();
        }
        sum += (ln_choose + ln_half_n).exp();
    }
    sum.min(1.0)
}

/// The 1-based rank k of the interval [x(k), x(n+1-k)]: the largest k whose
/// coverage is at least [`CONFIDENCE`]; `None` when even k = 1 falls short.
pub fn median_interval_rank(n: usize) -> Option<usize> {
    let alpha = 1.0 - CONFIDENCE;
    // Coverage of rank k: 1 - 2 P(B <= k - 1).
    let mut best = None;
    for k in 1..=n.div_ceil(2) {
        if 2.0 * binomial_half_cdf(n, k - 1) <= alpha + 1e-12 {
            best = Some(k);
        } else {
            break;
        }
    }
    best
}

/// The median of `samples` with its exact 95 % order-statistics interval.
pub fn median_estimate(samples: &[f64]) -> Result<Estimate, EstimateError> {
    if samples.iter().any(|v| !v.is_finite()) {
        return Err(EstimateError::NotFinite);
    }
    let n = samples.len();
    let k = median_interval_rank(n).ok_or(EstimateError::TooFewSamples { got: n, needed: MIN_SAMPLES })?;
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    Ok(Estimate { value: median_of(&sorted), lo: sorted[k - 1], hi: sorted[n - k], n })
}

/// `treatment - baseline`, round by round: the median of the paired
/// differences and its interval. Pairing by round cancels what the machine
/// did during that round to both.
pub fn paired_difference(baseline: &[f64], treatment: &[f64]) -> Result<Estimate, EstimateError> {
    if baseline.len() != treatment.len() {
        return Err(EstimateError::Unpaired { a: baseline.len(), b: treatment.len() });
    }
    let d: Vec<f64> = baseline.iter().zip(treatment).map(|(a, b)| b - a).collect();
    median_estimate(&d)
}

/// The lower and upper quartiles (linear interpolation between order statistics).
pub fn quartiles(values: &[f64]) -> (f64, f64) {
    let mut s: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if s.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    s.sort_by(f64::total_cmp);
    let at = |q: f64| {
        let pos = q * (s.len() - 1) as f64;
        let (i, f) = (pos.floor() as usize, pos.fract());
        if i + 1 < s.len() {
            s[i] * (1.0 - f) + s[i + 1] * f
        } else {
            s[i]
        }
    };
    (at(0.25), at(0.75))
}

/// Least-squares slope of one round's (x, y) points.
fn slope_of(points: &[(f64, f64)]) -> Option<f64> {
    super::stats::fit_line(points).map(|f| f.slope)
}

/// A slope fitted round by round.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopeEstimate {
    /// The median of the per-round slopes, with its interval.
    pub slope: Estimate,
    /// The line through the per-x medians: its intercept and r^2 (how well a
    /// straight line explains the medians).
    pub intercept: f64,
    pub r_squared: f64,
}

/// One slope per round (the least-squares line through that round's points),
/// then their median and interval: each round's slope sees one state of the
/// machine, and rounds that went wrong only move the tails.
pub fn slope_per_round(rounds: &[Vec<(f64, f64)>]) -> Result<SlopeEstimate, EstimateError> {
    let slopes: Vec<f64> = rounds.iter().map(|r| slope_of(r)).collect::<Option<_>>().ok_or(EstimateError::NoSlope)?;
    let slope = median_estimate(&slopes)?;
    let medians = per_x_medians(rounds);
    let fit = super::stats::fit_line(&medians).ok_or(EstimateError::NoSlope)?;
    Ok(SlopeEstimate { slope, intercept: fit.intercept, r_squared: fit.r_squared })
}

/// Each round's least-squares slope.
pub fn round_slopes(rounds: &[Vec<(f64, f64)>]) -> Result<Vec<f64>, EstimateError> {
    rounds.iter().map(|r| slope_of(r).ok_or(EstimateError::NoSlope)).collect()
}

/// `treatment`'s slope minus the baseline's, round by round (all fitted on
/// the same x values), as a Hodges-Lehmann shift with its signed-rank
/// interval ([`super::shift`]): a difference of two lines measured alike has
/// noise symmetric about it. Where the baseline is measured more than once a
/// round (the A/A control's two copies), each round's baseline slope is their
/// mean, which halves the baseline's share of the difference's noise.
pub fn paired_slope_difference(
    baselines: &[&[Vec<(f64, f64)>]],
    treatment: &[Vec<(f64, f64)>],
) -> Result<Estimate, EstimateError> {
    let treated = round_slopes(treatment)?;
    if baselines.is_empty() {
        return Err(EstimateError::Unpaired { a: 0, b: treated.len() });
    }
    let mut base = vec![0.0; treated.len()];
    for b in baselines {
        let slopes = round_slopes(b)?;
        if slopes.len() != treated.len() {
            return Err(EstimateError::Unpaired { a: slopes.len(), b: treated.len() });
        }
        for (sum, s) in base.iter_mut().zip(slopes) {
            *sum += s / baselines.len() as f64;
        }
    }
    let d: Vec<f64> = base.iter().zip(&treated).map(|(b, t)| t - b).collect();
    super::shift::shift_estimate(&d)
}

/// (x, median of y at x) over all rounds, sorted by x.
fn per_x_medians(rounds: &[Vec<(f64, f64)>]) -> Vec<(f64, f64)> {
    let mut xs: Vec<f64> = rounds.iter().flatten().map(|p| p.0).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs.into_iter()
        .map(|x| {
            let mut ys: Vec<f64> = rounds.iter().flatten().filter(|p| p.0 == x).map(|p| p.1).collect();
            ys.sort_by(f64::total_cmp);
            (x, median_of(&ys))
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn the_samples_asked_for_give_about_the_interval_asked_for() {
        let mut n = noise(11);
        let mut draw = |k: usize| -> Vec<f64> { (0..k).map(|_| 10.0 + (0..4).map(|_| n()).sum::<f64>()).collect() };
        let first = median_estimate(&draw(40)).unwrap();
        let target = first.half_width() / 2.0;
        let needed = first.samples_for(0.0, target).unwrap();
        assert!((100..=260).contains(&needed), "half the width needs about four times the samples: {needed}");
        let widths: Vec<f64> = (0..5).map(|_| median_estimate(&draw(needed)).unwrap().half_width() / target).collect();
        let mut widths = widths;
        widths.sort_by(f64::total_cmp);
        let typical = median_of(&widths);
        assert!((0.7..=1.4).contains(&typical), "with that many samples the half-width is {typical} x the target");
        // Already narrow enough: no more than it has; no width: no answer.
        assert!(first.samples_for(0.0, first.half_width() * 2.0).unwrap() <= first.n);
        let point = Estimate { value: 1.0, lo: 1.0, hi: 1.0, n: 6 };
        assert_eq!(point.samples_for(0.25, 3.0), None);
        // The relative target counts where it is the wider.
        let e = Estimate { value: 100.0, lo: 90.0, hi: 110.0, n: 10 };
        assert_eq!(e.samples_for(0.05, 1.0), Some(40));
    }

    /// A deterministic stream of noise (splitmix64) in [-1, 1).
    pub(crate) fn noise(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    #[test]
    fn the_interval_rank_matches_the_binomial_table() {
        // Known exact ranks of the 95 % sign-test interval of the median.
        assert_eq!(median_interval_rank(5), None);
        assert_eq!(median_interval_rank(6), Some(1));
        assert_eq!(median_interval_rank(8), Some(1));
        assert_eq!(median_interval_rank(9), Some(2));
        assert_eq!(median_interval_rank(10), Some(2));
        assert_eq!(median_interval_rank(20), Some(6));
        assert_eq!(median_interval_rank(50), Some(18));
        // Coverage of the chosen rank is at least 95 %, of the next one less.
        for n in 6..200 {
            let k = median_interval_rank(n).unwrap();
            assert!(1.0 - 2.0 * binomial_half_cdf(n, k - 1) >= CONFIDENCE - 1e-12, "n {n}");
            assert!(1.0 - 2.0 * binomial_half_cdf(n, k) < CONFIDENCE, "n {n}");
        }
    }

    #[test]
    fn too_few_samples_are_refused() {
        let e = median_estimate(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap_err();
        assert_eq!(e, EstimateError::TooFewSamples { got: 5, needed: MIN_SAMPLES });
        assert!(median_estimate(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).is_ok());
        assert_eq!(median_estimate(&[1.0, f64::NAN, 3.0, 4.0, 5.0, 6.0]).unwrap_err(), EstimateError::NotFinite);
    }

    #[test]
    fn median_and_interval_of_known_samples() {
        let e = median_estimate(&[9.0, 1.0, 8.0, 2.0, 7.0, 3.0, 6.0, 4.0, 5.0, 10.0]).unwrap();
        // n = 10: rank 2, so [x(2), x(9)].
        assert_eq!((e.value, e.lo, e.hi, e.n), (5.5, 2.0, 9.0, 10));
    }

    #[test]
    fn a_known_difference_is_found_and_an_a_a_control_is_within_noise() {
        // 30 rounds; every round moves both configurations by the same load
        // (up to +50 %), and each run adds its own jitter of +-2 %.
        let mut rng = noise(7);
        let (mut a, mut a_again, mut b) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..30 {
            let load = 1.0 + 0.25 * (rng() + 1.0);
            let jitter = |r: &mut dyn FnMut() -> f64| 1.0 + 0.02 * r();
            a.push(100.0 * load * jitter(&mut rng));
            a_again.push(100.0 * load * jitter(&mut rng));
            b.push((100.0 * load + 5.0) * jitter(&mut rng));
        }
        let real = paired_difference(&a, &b).unwrap();
        assert_eq!(real.verdict(), Verdict::Cost, "{real:?}");
        assert!(real.lo < 5.0 && real.hi > 5.0, "{real:?} holds the true +5");
        let control = paired_difference(&a, &a_again).unwrap();
        assert!(control.within_noise(), "{control:?}");
        assert_eq!(control.verdict(), Verdict::WithinNoise);
        // The unpaired medians would not see the +5: their intervals overlap widely.
        let (ma, mb) = (median_estimate(&a).unwrap(), median_estimate(&b).unwrap());
        assert!(ma.hi > mb.lo, "the load swamps the difference between unpaired medians");
    }

    #[test]
    fn a_cost_below_the_baseline_is_not_a_negative_cost() {
        let a = [10.0, 10.1, 10.2, 10.0, 10.1, 10.3, 10.2, 10.0];
        let b: Vec<f64> = a.iter().map(|v| v - 1.0).collect();
        let d = paired_difference(&a, &b).unwrap();
        assert_eq!(d.verdict(), Verdict::BelowBaseline);
        assert!(d.describe("us").starts_with("below the baseline by 1.00 us"), "{}", d.describe("us"));
        let noisy = Estimate { value: -0.5, lo: -2.0, hi: 1.0, n: 8 };
        assert!(noisy.describe("us").starts_with("within noise"), "{}", noisy.describe("us"));
        let cost = Estimate { value: 2.1, lo: 0.8, hi: 3.4, n: 8 };
        assert_eq!(cost.describe("us"), "+2.10 us (95 % CI 0.800-3.40)");
        assert_eq!(paired_difference(&a, &b[..7]).unwrap_err(), EstimateError::Unpaired { a: 8, b: 7 });
    }

    #[test]
    fn slopes_on_exact_data_and_on_noisy_data() {
        let xs = [8.0, 16.0, 32.0, 64.0, 128.0, 256.0];
        let exact: Vec<Vec<(f64, f64)>> = (0..6).map(|_| xs.iter().map(|&x| (x, 3.0 + 0.04 * x)).collect()).collect();
        let s = slope_per_round(&exact).unwrap();
        assert!((s.slope.value - 0.04).abs() < 1e-12 && s.slope.half_width() < 1e-12);
        assert!((s.intercept - 3.0).abs() < 1e-9 && (s.r_squared - 1.0).abs() < 1e-12);
        // Noisy rounds (each round its own offset and +-1 % jitter): the known
        // slope lies inside the interval, and a second line with 0.01 more per
        // block is told apart, round by round.
        let mut rng = noise(11);
        let mut base = Vec::new();
        let mut more = Vec::new();
        for _ in 0..20 {
            let offset = 2.0 * (rng() + 1.0);
            base.push(xs.iter().map(|&x| (x, (offset + 3.0 + 0.04 * x) * (1.0 + 0.01 * rng()))).collect::<Vec<_>>());
            more.push(xs.iter().map(|&x| (x, (offset + 3.0 + 0.05 * x) * (1.0 + 0.01 * rng()))).collect::<Vec<_>>());
        }
        let s = slope_per_round(&base).unwrap();
        assert!(s.slope.lo <= 0.04 && 0.04 <= s.slope.hi, "{s:?}");
        let d = paired_slope_difference(&[&base], &more).unwrap();
        assert!(d.lo > 0.0 && d.lo <= 0.01 && 0.01 <= d.hi, "{d:?}");
        let flat: Vec<Vec<(f64, f64)>> = (0..6).map(|_| vec![(1.0, 1.0), (1.0, 2.0)]).collect();
        assert_eq!(slope_per_round(&flat).unwrap_err(), EstimateError::NoSlope);
    }

    #[test]
    fn two_copies_of_the_baseline_narrow_a_slope_difference() {
        // Every line's points have independent noise; the baseline measured
        // twice a round gives, against the copies' mean, intervals narrower
        // than against one copy (in most of 20 trials), and a 95 % interval
        // still holds the known 0.01 per block (in all but a few).
        let xs = [8.0, 16.0, 32.0, 64.0, 128.0, 256.0];
        let mut rng = noise(23);
        let mut line = |slope: f64| -> Vec<Vec<(f64, f64)>> {
            (0..40).map(|_| xs.iter().map(|&x| (x, 3.0 + slope * x + 0.5 * rng())).collect()).collect()
        };
        let (mut narrower, mut covered) = (0, 0);
        for _ in 0..20 {
            let (base, again, more) = (line(0.04), line(0.04), line(0.05));
            let one = paired_slope_difference(&[&base], &more).unwrap();
            let two = paired_slope_difference(&[&base, &again], &more).unwrap();
            covered += usize::from(two.lo <= 0.01 && 0.01 <= two.hi);
            narrower += usize::from(two.half_width() < one.half_width());
        }
        assert!(narrower >= 15, "narrower in {narrower} of 20");
        assert!(covered >= 17, "the known difference in {covered} of 20 intervals");
        let (base, more) = (line(0.04), line(0.05));
        assert_eq!(
            paired_slope_difference(&[&base[..39]], &more).unwrap_err(),
            EstimateError::Unpaired { a: 39, b: 40 }
        );
    }

    #[test]
    fn quartiles_interpolate() {
        assert_eq!(quartiles(&[1.0, 2.0, 3.0, 4.0, 5.0]), (2.0, 4.0));
        let (q1, q3) = quartiles(&[4.0, 1.0, 3.0, 2.0]);
        assert!((q1 - 1.75).abs() < 1e-12 && (q3 - 3.25).abs() < 1e-12);
        assert!(quartiles(&[]).0.is_nan());
    }
}
