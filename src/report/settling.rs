//! Settling time of a signal after an event, e.g. how long the step size takes to return to
//! the reference after a push (experiment B's `return_time_s`). Per-bin statistics aligned at
//! events are in [`crate::experiments::aligned`].

use super::ReportError;

/// A time-stamped value, e.g. (touch-down time, step size error).
pub type Sample = (f64, f64);

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
    if samples.windows(2).any(|w| w[0].0 > w[1].0) {
        return Err(ReportError::invalid("samples must be sorted by time"));
    }
    Ok(())
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
        assert!(settling_time(&[(1.0, 0.0), (0.5, 0.0)], 0.0, 1.0, 0.0, 0.1).is_err());
    }
}
