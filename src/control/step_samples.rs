//! What a learner remembers of the step in progress, shared by the one-plane
//! [`FootstepLearner`](super::learner::FootstepLearner) and the
//! [`CoupledLearner`](super::coupled::CoupledLearner): the inputs it was queried at, thinned so
//! that a bounded number stays evenly spread over the step, each with the reach of its offsets;
//! and the trust region both apply around the inputs they were trained at.

use crate::stats::MeanStd;

/// The inputs `X` recorded in one step, each with its reach `R` (the offsets that could still
/// change the step at that query). Every `stride`-th query is recorded; when `max` are held,
/// every second one is dropped and the stride doubles.
#[derive(Debug, Clone)]
pub(crate) struct StepSamples<X, R> {
    /// Inputs recorded in this step, in query order.
    pub(crate) inputs: Vec<X>,
    /// The reach of each recorded input.
    pub(crate) reach: Vec<R>,
    /// Whether the last query was recorded (so that a reach told after it applies to it).
    pub(crate) last_recorded: bool,
    /// Every `stride`-th query of this step is recorded (a power of two).
    pub(crate) stride: usize,
    /// Queries seen in this step.
    pub(crate) queries: usize,
}

impl<X: Copy, R: Copy> StepSamples<X, R> {
    /// An empty step with room for `max` inputs (it never grows beyond).
    pub(crate) fn with_capacity(max: usize) -> Self {
        StepSamples {
            inputs: Vec::with_capacity(max),
            reach: Vec::with_capacity(max),
            last_recorded: false,
            stride: 1,
            queries: 0,
        }
    }

    /// Counts a query at `x`, recording it with reach `open` if its turn has come, keeping at
    /// most `max` inputs (samples 0, 2, 4, ... are kept when the buffer is full).
    pub(crate) fn record(&mut self, x: X, open: R, max: usize) {
        self.last_recorded = false;
        if self.queries.is_multiple_of(self.stride) {
            if self.inputs.len() == max {
                let mut keep = 0;
                for i in (0..self.inputs.len()).step_by(2) {
                    self.inputs[keep] = self.inputs[i];
                    self.reach[keep] = self.reach[i];
                    keep += 1;
                }
                self.inputs.truncate(keep);
                self.reach.truncate(keep);
                self.stride *= 2;
            }
            if self.queries.is_multiple_of(self.stride) {
                self.inputs.push(x);
                self.reach.push(open);
                self.last_recorded = true;
            }
        }
        self.queries += 1;
    }

    /// The reach of the last query, if it was recorded.
    pub(crate) fn last_reach_mut(&mut self) -> Option<&mut R> {
        if self.last_recorded {
            self.reach.last_mut()
        } else {
            None
        }
    }

    /// Index of the first recorded input trained at touch-down: the latest `share` of them,
    /// at least one.
    pub(crate) fn first_trained(&self, share: f64) -> usize {
        let n = self.inputs.len();
        let keep = ((n as f64 * share).ceil() as usize).clamp(1, n.max(1));
        n.saturating_sub(keep)
    }

    /// Forgets the step (the capacity stays).
    pub(crate) fn clear(&mut self) {
        self.inputs.clear();
        self.reach.clear();
        self.last_recorded = false;
        self.stride = 1;
        self.queries = 0;
    }
}

impl<const N: usize, R> StepSamples<[f64; N], R> {
    /// Adds the inputs trained at touch-down (those from `first` on) to the per-axis
    /// statistics of the trust region.
    pub(crate) fn add_trained(&self, first: usize, trained: &mut [MeanStd; N]) {
        for x in &self.inputs[first..] {
            for (t, v) in trained.iter_mut().zip(x) {
                t.push(*v);
            }
        }
    }
}

/// The trust region's share of the offset at `x` for a region of `k` standard deviations:
/// 1 where every input lies within `k` of the mean of the `trained` inputs (distances in
/// `spread(axis)`), fading linearly to 0 at `1.5 k`; 0 before any training.
pub(crate) fn trust_share(
    k: f64,
    x: &[f64],
    trained: &[MeanStd],
    spread: impl Fn(usize) -> f64,
) -> f64 {
    let mut z: f64 = 0.0;
    for (a, (&xa, t)) in x.iter().zip(trained).enumerate() {
        if t.count() == 0 {
            return 0.0;
        }
        z = z.max((xa - t.mean()).abs() / spread(a));
    }
    ((1.5 * k - z) / (0.5 * k)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_buffer_keeps_every_second_input_and_records_half_as_often() {
        let mut s: StepSamples<usize, ()> = StepSamples::with_capacity(4);
        for q in 0..8 {
            s.record(q, (), 4);
        }
        // 0..4 filled it; at query 4 it kept 0, 2 and recorded 4, then 6 (7 is skipped).
        assert_eq!(s.inputs, [0, 2, 4, 6]);
        assert_eq!((s.stride, s.queries), (2, 8));
        assert!(s.last_reach_mut().is_none());
        assert_eq!(s.first_trained(0.5), 2);
        assert_eq!(s.first_trained(1.0), 0);
        s.clear();
        assert!(s.inputs.is_empty() && s.stride == 1 && s.queries == 0);
    }
}
