//! Statistics of a signal aligned at events (reference changes, pushes): the mean and standard
//! deviation per time bin after the event (Figs. 4, 5) and the settling time after an event.

use super::ReportError;
use serde::{Deserialize, Serialize};

/// A time-stamped value, e.g. (touch-down time, step size error).
pub type Sample = (f64, f64);

/// Per-bin statistics over all events: bin `k` covers [k bin_s, (k + 1) bin_s) after an event.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AlignedStats {
    /// Bin width (s).
    pub bin_s: f64,
    /// Bin centres (s after the event).
    pub t: Vec<f64>,
    /// Mean per bin (NaN for an empty bin).
    pub mean: Vec<f64>,
    /// Sample standard deviation per bin (0 for one value, NaN for an empty bin).
    pub std: Vec<f64>,
    /// Number of values per bin.
    pub count: Vec<usize>,
}

fn check(samples: &[Sample], events: &[f64]) -> Result<(), ReportError> {
    if let Some(s) = samples
        .iter()
        .find(|s| !(s.0.is_finite() && s.1.is_finite()))
    {
        return Err(ReportError::invalid(format!("sample {s:?} is not finite")));
    }
    if let Some(e) = events.iter().find(|e| !e.is_finite()) {
        return Err(ReportError::invalid(format!(
            "event time {e} is not finite"
        )));
    }
    if samples.windows(2).any(|w| w[0].0 > w[1].0) || events.windows(2).any(|w| w[0] > w[1]) {
        return Err(ReportError::invalid(
            "samples and events must be sorted by time",
        ));
    }
    Ok(())
}

/// Aligns `samples` at each of `events` and computes mean and std per bin over
/// [0, window_s) after the event. With `stop_at_next_event`, samples at or after the next
/// event are not counted for the previous one (tracking: a new reference change starts a new
/// trace). Samples and events must be sorted by time.
pub fn align_at_events(
    samples: &[Sample],
    events: &[f64],
    window_s: f64,
    bin_s: f64,
    stop_at_next_event: bool,
) -> Result<AlignedStats, ReportError> {
    check(samples, events)?;
    if !(bin_s.is_finite() && bin_s > 0.0 && window_s.is_finite() && window_s >= bin_s) {
        return Err(ReportError::invalid(format!(
            "need 0 < bin_s <= window_s, got bin_s {bin_s}, window_s {window_s}"
        )));
    }
    let bins = (window_s / bin_s).ceil() as usize;
    let mut sum = vec![0.0; bins];
    let mut sum_sq = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for (i, &e) in events.iter().enumerate() {
        let mut end = e + window_s;
        if stop_at_next_event && let Some(&next) = events.get(i + 1) {
            end = end.min(next);
        }
        let first = samples.partition_point(|s| s.0 < e);
        for &(t, v) in samples[first..].iter().take_while(|s| s.0 < end) {
            let k = (((t - e) / bin_s).floor() as usize).min(bins - 1);
            sum[k] += v;
            sum_sq[k] += v * v;
            count[k] += 1;
        }
    }
    let mut stats = AlignedStats {
        bin_s,
        t: (0..bins).map(|k| (k as f64 + 0.5) * bin_s).collect(),
        mean: Vec::with_capacity(bins),
        std: Vec::with_capacity(bins),
        count,
    };
    for k in 0..bins {
        let n = stats.count[k] as f64;
        let (mean, std) = match stats.count[k] {
            0 => (f64::NAN, f64::NAN),
            1 => (sum[k], 0.0),
            _ => {
                let mean = sum[k] / n;
                let var = ((sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
                (mean, var.sqrt())
            }
        };
        stats.mean.push(mean);
        stats.std.push(std);
    }
    Ok(stats)
}

/// Time from `event` until the signal has settled: the first sample time after which every
/// sample up to `event + window_s` satisfies |value - target| <= tolerance, minus the event
/// time. `Some(0.0)` if no sample in the window is out of tolerance; `None` if the last sample
/// of the window is still out of tolerance (never settled) or the window holds no sample.
pub fn settling_time(
    samples: &[Sample],
    event: f64,
    window_s: f64,
    target: f64,
    tolerance: f64,
) -> Result<Option<f64>, ReportError> {
    check(samples, &[event])?;
    let valid = window_s.is_finite()
        && window_s > 0.0
        && tolerance.is_finite()
        && tolerance >= 0.0
        && target.is_finite();
    if !valid {
        return Err(ReportError::invalid(format!(
            "need window_s > 0, tolerance >= 0 and a finite target, got {window_s}, {tolerance}, {target}"
        )));
    }
    let first = samples.partition_point(|s| s.0 < event);
    let window: Vec<Sample> = samples[first..]
        .iter()
        .take_while(|s| s.0 < event + window_s)
        .copied()
        .collect();
    let Some(&(last_t, last_v)) = window.last() else {
        return Ok(None);
    };
    if (last_v - target).abs() > tolerance {
        return Ok(None);
    }
    match window
        .iter()
        .rposition(|s| (s.1 - target).abs() > tolerance)
    {
        None => Ok(Some(0.0)),
        Some(i) => {
            let settled_at = window.get(i + 1).map_or(last_t, |s| s.0);
            Ok(Some(settled_at - event))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aligned_statistics_by_hand() {
        // two events at 0 and 10; samples at 0.25 and 1.25 s after each
        let samples = [
            (0.25, 1.0),
            (1.25, 2.0),
            (10.25, 3.0),
            (11.25, 6.0),
            (25.0, 100.0),
        ];
        let s = align_at_events(&samples, &[0.0, 10.0], 2.0, 1.0, true).unwrap();
        assert_eq!(s.t, vec![0.5, 1.5]);
        assert_eq!(s.count, vec![2, 2]);
        assert_eq!(s.mean, vec![2.0, 4.0]);
        assert!((s.std[0] - 2f64.sqrt()).abs() < 1e-12);
        assert!((s.std[1] - 8f64.sqrt()).abs() < 1e-12);
        // a long window: without stopping, event 0 also sees event 10's samples
        let long = align_at_events(&samples, &[0.0, 10.0], 12.0, 1.0, false).unwrap();
        assert_eq!(long.count.iter().sum::<usize>(), 6);
        let stop = align_at_events(&samples, &[0.0, 10.0], 12.0, 1.0, true).unwrap();
        assert_eq!(stop.count.iter().sum::<usize>(), 4);
        assert!(stop.mean[5].is_nan());
        assert!(align_at_events(&samples, &[10.0, 0.0], 2.0, 1.0, true).is_err());
        assert!(align_at_events(&samples, &[0.0], 2.0, 0.0, true).is_err());
        assert!(align_at_events(&[(f64::NAN, 0.0)], &[0.0], 2.0, 1.0, true).is_err());
    }

    #[test]
    fn settling_time_by_hand() {
        let s = [
            (0.5, 0.3),
            (1.0, 0.25),
            (1.5, 0.21),
            (2.0, 0.19),
            (2.5, 0.2),
            (3.0, 0.35),
        ];
        // after a push at 0.4: out of tolerance until 1.0, within from 1.5 on (window to 2.9)
        assert_eq!(
            settling_time(&s, 0.4, 2.5, 0.2, 0.02).unwrap(),
            Some(1.5 - 0.4)
        );
        // the window reaching 3.0 ends out of tolerance: never settled
        assert_eq!(settling_time(&s, 0.4, 3.0, 0.2, 0.02).unwrap(), None);
        assert_eq!(settling_time(&s, 1.2, 1.5, 0.2, 0.02).unwrap(), Some(0.0));
        assert_eq!(settling_time(&s, 10.0, 1.0, 0.2, 0.02).unwrap(), None);
        assert!(settling_time(&s, 0.0, 1.0, 0.2, -1.0).is_err());
    }
}
