//! Event-aligned statistics: mean and standard deviation of a signal against the time since
//! the last event (a reference change, a push), as in the paper's Figures 4 and 5.

use crate::report::ReportError;
use serde::{Deserialize, Serialize};

/// Mean and standard deviation per time bin after an event.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AlignedStats {
    /// Width of a bin (s); bin k covers `[k * bin, (k + 1) * bin)` after the event.
    pub bin_s: f64,
    /// Mean per bin (NaN where the bin is empty).
    pub mean: Vec<f64>,
    /// Population standard deviation per bin (NaN where the bin is empty).
    pub std: Vec<f64>,
    /// Number of samples per bin.
    pub count: Vec<usize>,
}

impl AlignedStats {
    /// Bins `samples` `(time, value)` by the time since the latest event at or before them,
    /// over `[0, horizon)`. Samples before the first event or past the horizon are ignored.
    /// `events` must be sorted. A bin or horizon that is not positive and finite, or unsorted
    /// events, is an error.
    pub fn compute(
        samples: &[(f64, f64)],
        events: &[f64],
        bin_s: f64,
        horizon: f64,
    ) -> Result<Self, ReportError> {
        if !(bin_s.is_finite() && bin_s > 0.0 && horizon.is_finite() && horizon > 0.0) {
            return Err(ReportError::invalid(format!(
                "aligned statistics need a positive finite bin and horizon, got {bin_s} and {horizon}"
            )));
        }
        check_sorted(events)?;
        let n_bins = (horizon / bin_s).ceil() as usize;
        let mut bins = vec![crate::stats::MeanStd::new(); n_bins];
        for &(t, v) in samples {
            let i = events.partition_point(|&e| e <= t);
            if i == 0 {
                continue;
            }
            let k = ((t - events[i - 1]) / bin_s) as usize;
            if k < n_bins {
                bins[k].push(v);
            }
        }
        Ok(AlignedStats::from_bins(bin_s, &bins))
    }

    /// Bins `samples` `(time, value)` by their order after the latest event at or before them:
    /// bin k holds every event's k-th sample (k = 0: the first), for samples within `horizon`
    /// (s) of their event and k < `max_index`; the result's `bin_s` is 1 (one sample). Samples
    /// and events must be sorted by time; unsorted ones, or a horizon that is not positive and
    /// finite, are an error.
    pub fn by_index(
        samples: &[(f64, f64)],
        events: &[f64],
        horizon: f64,
        max_index: usize,
    ) -> Result<Self, ReportError> {
        if !(horizon.is_finite() && horizon > 0.0) {
            return Err(ReportError::invalid(format!(
                "aligned statistics need a positive finite horizon, got {horizon}"
            )));
        }
        check_sorted(events)?;
        if samples.windows(2).any(|w| w[0].0 > w[1].0) {
            return Err(ReportError::invalid("sample times must be sorted"));
        }
        let mut bins = vec![crate::stats::MeanStd::new(); max_index];
        let (mut event, mut k) = (0usize, 0usize);
        for &(t, v) in samples {
            let i = events.partition_point(|&e| e <= t);
            if i == 0 {
                continue;
            }
            if i != event {
                (event, k) = (i, 0);
            }
            if t - events[i - 1] < horizon && k < max_index {
                bins[k].push(v);
            }
            k += 1;
        }
        Ok(AlignedStats::from_bins(1.0, &bins))
    }

    /// The statistics of filled bins of width `bin_s`.
    fn from_bins(bin_s: f64, bins: &[crate::stats::MeanStd]) -> Self {
        AlignedStats {
            bin_s,
            mean: bins.iter().map(|b| b.mean()).collect(),
            std: bins.iter().map(|b| b.population_std()).collect(),
            count: bins.iter().map(|b| b.count()).collect(),
        }
    }

    /// The bins with at least `min_count` samples, as (bin centre times, means, stds).
    pub fn populated(&self, min_count: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut out = (Vec::new(), Vec::new(), Vec::new());
        for (k, t) in self.times().into_iter().enumerate() {
            if self.count[k] >= min_count.max(1) {
                out.0.push(t);
                out.1.push(self.mean[k]);
                out.2.push(self.std[k]);
            }
        }
        out
    }

    /// Bin centre times.
    pub fn times(&self) -> Vec<f64> {
        (0..self.mean.len())
            .map(|k| (k as f64 + 0.5) * self.bin_s)
            .collect()
    }
}

/// An error unless the event times are sorted (and not NaN).
fn check_sorted(events: &[f64]) -> Result<(), ReportError> {
    if events.windows(2).any(|w| w[0] > w[1] || w[0].is_nan()) {
        return Err(ReportError::invalid("event times must be sorted"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_by_time_since_latest_event() {
        // Events at 0 and 10; values equal to the time since the event.
        let samples: Vec<(f64, f64)> = (0..200)
            .map(|i| {
                let t = i as f64 * 0.1;
                (t, t % 10.0)
            })
            .collect();
        let s = AlignedStats::compute(&samples, &[0.0, 10.0], 1.0, 5.0).unwrap();
        assert_eq!(s.mean.len(), 5);
        for k in 0..5 {
            assert_eq!(s.count[k], 20);
            assert!((s.mean[k] - (k as f64 + 0.45)).abs() < 1e-9);
            assert!(s.std[k] > 0.0 && s.std[k] < 0.3);
        }
        assert_eq!(s.times()[0], 0.5);
    }

    #[test]
    fn empty_bins_are_nan_and_early_samples_ignored() {
        let s = AlignedStats::compute(&[(-1.0, 5.0), (0.5, 2.0)], &[0.0], 1.0, 3.0).unwrap();
        assert_eq!(s.count, vec![1, 0, 0]);
        assert_eq!(s.mean[0], 2.0);
        assert_eq!(s.std[0], 0.0);
        assert!(s.mean[1].is_nan());
    }

    #[test]
    fn by_index_counts_samples_since_the_latest_event() {
        // Events at 0 and 10; a sample every 0.4 s valued by its index since the event.
        let samples: Vec<(f64, f64)> = (0..50)
            .map(|i| {
                let t = 0.1 + i as f64 * 0.4;
                let since = if t >= 10.0 { t - 10.0 } else { t };
                (t, ((since - 0.1) / 0.4).round())
            })
            .collect();
        let s = AlignedStats::by_index(&samples, &[0.0, 10.0], 2.0, 8).unwrap();
        assert_eq!(s.bin_s, 1.0);
        // Samples within 2 s of their event: indices 0-4 after either event.
        assert_eq!(s.count, vec![2, 2, 2, 2, 2, 0, 0, 0]);
        for k in 0..5 {
            assert_eq!(s.mean[k], k as f64);
        }
        assert!(AlignedStats::by_index(&samples, &[0.0], 0.0, 8).is_err());
        assert!(AlignedStats::by_index(&[(1.0, 0.0), (0.5, 0.0)], &[0.0], 1.0, 8).is_err());
    }

    #[test]
    fn bad_bins_and_unsorted_events_are_errors() {
        assert!(AlignedStats::compute(&[], &[0.0], 0.0, 1.0).is_err());
        assert!(AlignedStats::compute(&[], &[0.0], 1.0, f64::NAN).is_err());
        assert!(AlignedStats::compute(&[], &[2.0, 1.0], 1.0, 1.0).is_err());
    }

    #[test]
    fn populated_keeps_bins_with_enough_samples() {
        let s =
            AlignedStats::compute(&[(0.1, 1.0), (0.2, 3.0), (1.5, 7.0)], &[0.0], 1.0, 3.0).unwrap();
        assert_eq!(
            s.populated(1),
            (vec![0.5, 1.5], vec![2.0, 7.0], vec![1.0, 0.0])
        );
        assert_eq!(s.populated(2), (vec![0.5], vec![2.0], vec![1.0]));
        assert_eq!(s.populated(0), s.populated(1));
    }
}
