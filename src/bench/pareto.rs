//! The Pareto front of (time, error): the runs no other run beats on both.

use std::cmp::Ordering;

/// Indices of the non-dominated points, sorted by time (then error, then index).
///
/// Lower time and lower error are better. A point is dominated when another
/// point is no worse in both and strictly better in one. Exact duplicates do not
/// dominate each other, so all copies of a front point are on the front. Points
/// with a NaN or infinite coordinate are never on the front and never dominate.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> =
        (0..points.len()).filter(|&i| points[i].0.is_finite() && points[i].1.is_finite()).collect();
    // Adding 0.0 turns -0.0 into 0.0, so total_cmp orders equal values as equal.
    let point = |i: usize| (points[i].0 + 0.0, points[i].1 + 0.0);
    order.sort_by(|&a, &b| {
        let (pa, pb) = (point(a), point(b));
        pa.0.total_cmp(&pb.0).then(pa.1.total_cmp(&pb.1)).then(a.cmp(&b))
    });

    // Sweeping by increasing time, a point is on the front only if it improves
    // on the best error so far, or exactly repeats the last front point.
    let mut front: Vec<usize> = Vec::new();
    let mut last: Option<(f64, f64)> = None;
    for index in order {
        let (time, error) = point(index);
        let on_front = match last {
            None => true,
            Some((last_time, last_error)) => match error.partial_cmp(&last_error) {
                Some(Ordering::Less) => true,
                Some(Ordering::Equal) => time == last_time,
                _ => false,
            },
        };
        if on_front {
            front.push(index);
            last = Some((time, error));
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Straight from the definition, O(n²): an independent check of the sweep.
    fn front_by_definition(points: &[(f64, f64)]) -> Vec<usize> {
        let finite = |p: (f64, f64)| p.0.is_finite() && p.1.is_finite();
        let dominates = |q: (f64, f64), p: (f64, f64)| q.0 <= p.0 && q.1 <= p.1 && (q.0 < p.0 || q.1 < p.1);
        let mut front: Vec<usize> = (0..points.len())
            .filter(|&i| finite(points[i]))
            .filter(|&i| !points.iter().any(|&q| finite(q) && dominates(q, points[i])))
            .collect();
        front.sort_by(|&a, &b| {
            points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)).then(a.cmp(&b))
        });
        front
    }

    #[test]
    fn empty_input_has_an_empty_front() {
        assert!(pareto_front(&[]).is_empty());
    }

    #[test]
    fn a_single_point_is_its_own_front() {
        assert_eq!(pareto_front(&[(3.0, 0.2)]), vec![0]);
    }

    #[test]
    fn dominated_points_are_left_out_and_the_front_is_sorted_by_time() {
        // 0: slow and exact; 1: fast and rough; 2: in between, on the front;
        // 3: slower and worse than 2; 4: as fast as 1 but worse.
        let points = [(10.0, 0.01), (1.0, 0.5), (4.0, 0.1), (5.0, 0.2), (1.0, 0.6)];
        assert_eq!(pareto_front(&points), vec![1, 2, 0]);
    }

    #[test]
    fn exact_duplicates_are_both_on_the_front() {
        let points = [(2.0, 0.3), (1.0, 0.5), (2.0, 0.3)];
        assert_eq!(pareto_front(&points), vec![1, 0, 2]);
    }

    #[test]
    fn equal_error_at_higher_time_is_dominated() {
        let points = [(3.0, 0.2), (2.0, 0.2)];
        assert_eq!(pareto_front(&points), vec![1]);
    }

    #[test]
    fn equal_time_with_higher_error_is_dominated() {
        let points = [(2.0, 0.4), (2.0, 0.2)];
        assert_eq!(pareto_front(&points), vec![1]);
    }

    #[test]
    fn non_finite_points_never_reach_the_front() {
        let points = [(f64::NAN, 0.0), (0.5, f64::NAN), (f64::NEG_INFINITY, 1.0), (1.0, f64::NEG_INFINITY), (2.0, 1.0)];
        assert_eq!(pareto_front(&points), vec![4]);
        assert!(pareto_front(&[(f64::NAN, f64::NAN)]).is_empty());
    }

    #[test]
    fn sweep_agrees_with_the_definition_on_pseudo_random_sets() {
        // A small LCG on a coarse grid, so ties and duplicates are frequent.
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = move || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % 8
        };
        for size in 0..40 {
            let points: Vec<(f64, f64)> = (0..size).map(|_| (next() as f64, next() as f64 * 0.125)).collect();
            assert_eq!(pareto_front(&points), front_by_definition(&points), "{points:?}");
        }
    }
}
