//! Percentiles of the per-step times.

/// The `p`-th percentile (0 ≤ p ≤ 100) of `sorted` (ascending), nearest-rank: the smallest
/// value with at least p % of the values at or below it; `p = 0` is the minimum, `p = 100` the
/// maximum. `None` for an empty slice.
pub fn percentile(sorted: &[f64], p: f64) -> Option<f64> {
    if sorted.is_empty() {
        return None;
    }
    let n = sorted.len();
    // p·n/100 in floating point can land just above a whole number (99.9 % of 10 000 is
    // 9990.000000000002): a relative 1e-12 below it is still that rank
    let x = p.clamp(0.0, 100.0) * n as f64 / 100.0;
    let rank = (x * (1.0 - 1e-12)).ceil() as usize;
    Some(sorted[rank.clamp(1, n) - 1])
}

/// The percentiles the harness reports, of one quantity (µs for times).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Median (p50).
    pub median: f64,
    /// p99.
    pub p99: f64,
    /// p99.9.
    pub p999: f64,
    /// p99.99.
    pub p9999: f64,
    /// Maximum.
    pub max: f64,
    /// Index (in the input order) of the maximum.
    pub argmax: usize,
}

impl Summary {
    /// The summary of `values` (any order; not empty).
    pub fn of(values: &[f64]) -> Option<Summary> {
        let argmax = values
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))?
            .0;
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let p = |q| percentile(&sorted, q).unwrap_or(f64::NAN);
        Some(Summary {
            median: p(50.0),
            p99: p(99.0),
            p999: p(99.9),
            p9999: p(99.99),
            max: p(100.0),
            argmax,
        })
    }

    /// max / median.
    pub fn max_over_median(&self) -> f64 {
        self.max / self.median
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_rank_percentiles() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(percentile(&v, 50.0), Some(50.0));
        assert_eq!(percentile(&v, 99.0), Some(99.0));
        assert_eq!(percentile(&v, 99.9), Some(100.0));
        assert_eq!(percentile(&v, 100.0), Some(100.0));
        assert_eq!(percentile(&v, 0.0), Some(1.0));
        assert_eq!(percentile(&v, 0.5), Some(1.0));
        assert_eq!(percentile(&v, 1.0), Some(1.0));
        assert_eq!(percentile(&v, 1.01), Some(2.0));
        assert_eq!(percentile(&[7.0], 99.99), Some(7.0));
        assert_eq!(percentile(&[], 50.0), None);
        // 10 000 values: p99.99 is the 9 999th, one below the maximum
        let w: Vec<f64> = (1..=10_000).map(f64::from).collect();
        assert_eq!(percentile(&w, 99.99), Some(9_999.0));
        assert_eq!(percentile(&w, 99.9), Some(9_990.0));
    }

    #[test]
    fn summary_of_unsorted_values() {
        let s = Summary::of(&[3.0, 1.0, 9.0, 2.0, 4.0]).unwrap();
        assert_eq!((s.median, s.max, s.argmax), (3.0, 9.0, 2));
        assert_eq!(s.max_over_median(), 3.0);
        assert!(Summary::of(&[]).is_none());
    }
}
