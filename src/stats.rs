//! The crate's one place for summary statistics: running mean and standard deviation
//! (Welford's algorithm, numerically stable in one pass) and evenly spaced grids.

/// The largest count (of updates, samples, queries) a saved model may hold: every integer up
/// to it is exact as an `f64`, and no run reaches it (2^53 updates at a million a second take
/// 285 years), so a larger one can only come from a damaged file.
pub const MAX_COUNT: u64 = 1 << 53;

/// Running mean and variance of a stream of values (Welford).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeanStd {
    n: usize,
    mean: f64,
    /// Sum of squared deviations from the running mean.
    m2: f64,
}

impl MeanStd {
    /// No values yet.
    pub fn new() -> Self {
        MeanStd::default()
    }

    /// The statistics of `values`.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let mut s = MeanStd::new();
        values.into_iter().for_each(|v| s.push(v));
        s
    }

    /// Adds one value.
    pub fn push(&mut self, v: f64) {
        self.n += 1;
        let delta = v - self.mean;
        self.mean += delta / self.n as f64;
        self.m2 += delta * (v - self.mean);
    }

    /// Whether the state could have come from [`MeanStd::push`] of finite values: mean and
    /// sum of squares finite, the sum of squares not negative, both 0 without values (for
    /// checking deserialized statistics).
    pub fn is_consistent(&self) -> bool {
        self.n as u64 <= MAX_COUNT
            && self.mean.is_finite()
            && self.m2.is_finite()
            && self.m2 >= 0.0
            && (self.n > 0 || (self.mean == 0.0 && self.m2 == 0.0))
    }

    /// Number of values.
    pub fn count(&self) -> usize {
        self.n
    }

    /// The mean (NaN without values).
    pub fn mean(&self) -> f64 {
        if self.n == 0 { f64::NAN } else { self.mean }
    }

    /// The population standard deviation (divides by n; NaN without values).
    pub fn population_std(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            (self.m2 / self.n as f64).max(0.0).sqrt()
        }
    }

    /// The sample standard deviation (divides by n - 1; 0 for one value, NaN for none).
    pub fn sample_std(&self) -> f64 {
        match self.n {
            0 => f64::NAN,
            1 => 0.0,
            n => (self.m2 / (n - 1) as f64).max(0.0).sqrt(),
        }
    }

    /// Half-width of the two-sided 95% Student-t interval of the mean; `None` with fewer than
    /// two values.
    #[cfg(feature = "experiments")]
    pub fn ci95_half_width(&self) -> Option<f64> {
        (self.n >= 2)
            .then(|| t_quantile_975(self.n - 1) * self.sample_std() / (self.n as f64).sqrt())
    }
}

/// The 97.5% quantile of Student's t with `df` degrees of freedom (`df >= 1`).
#[cfg(feature = "experiments")]
fn t_quantile_975(df: usize) -> f64 {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    // df >= 1 and the location/scale are valid constants: the distribution always exists.
    StudentsT::new(0.0, 1.0, df as f64)
        .map(|t| t.inverse_cdf(0.975))
        .unwrap_or(f64::NAN)
}

/// `n` evenly spaced values from `lo` to `hi` (the midpoint when `n == 1`).
pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![0.5 * (lo + hi)],
        _ => (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(feature = "experiments")]
    #[test]
    fn t_quantiles_match_the_tables() {
        for (df, t) in [(1, 12.706), (4, 2.776), (9, 2.262), (30, 2.042)] {
            assert!((t_quantile_975(df) - t).abs() < 1e-3, "df {df}");
        }
        // Sample std 1, n 3: half width t(2) / sqrt(3) = 4.303 / 1.732; none from one value.
        let s = MeanStd::of([1.0, 2.0, 3.0]);
        assert!((s.ci95_half_width().unwrap() - 4.303 / 3f64.sqrt()).abs() < 1e-3);
        assert_eq!(MeanStd::of([1.0]).ci95_half_width(), None);
    }

    #[test]
    fn agrees_with_two_pass_formulas() {
        let v = [1.0e9 + 4.0, 1.0e9 + 7.0, 1.0e9 + 13.0, 1.0e9 + 16.0];
        let s = MeanStd::of(v);
        assert_eq!(s.count(), 4);
        assert_eq!(s.mean(), 1.0e9 + 10.0);
        // deviations -6, -3, 3, 6: sum of squares 90
        assert!((s.population_std() - (90.0f64 / 4.0).sqrt()).abs() < 1e-12);
        assert!((s.sample_std() - (90.0f64 / 3.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn empty_and_single() {
        assert!(MeanStd::new().mean().is_nan());
        assert!(MeanStd::new().population_std().is_nan());
        assert!(MeanStd::new().sample_std().is_nan());
        let one = MeanStd::of([2.5]);
        assert_eq!(
            (one.mean(), one.population_std(), one.sample_std()),
            (2.5, 0.0, 0.0)
        );
    }

    #[test]
    fn linspace_ends_and_midpoint() {
        assert_eq!(linspace(0.0, 1.0, 3), vec![0.0, 0.5, 1.0]);
        assert_eq!(linspace(-1.0, 1.0, 1), vec![0.0]);
        assert!(linspace(0.0, 1.0, 0).is_empty());
    }
}
