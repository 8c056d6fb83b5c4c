//! Fall probability versus push impulse (experiment C, Fig. 6): a logistic fit, the impulse at
//! which half the pushes make the robot fall, and binned fall rates.

use super::ReportError;
use serde::{Deserialize, Serialize};

/// One push: its impulse (Ns) and whether the robot fell.
pub type PushResult = (f64, bool);

/// P(fall | impulse x) = 1 / (1 + exp(-(intercept + slope x))).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LogisticFit {
    /// Intercept a.
    pub intercept: f64,
    /// Slope b (1/Ns).
    pub slope: f64,
}

impl LogisticFit {
    /// The fitted fall probability at `impulse`.
    pub fn probability(&self, impulse: f64) -> f64 {
        1.0 / (1.0 + (-(self.intercept + self.slope * impulse)).exp())
    }

    /// `n` evenly spaced impulses over [lo, hi] and the fitted probabilities there (for
    /// [`crate::report::figures::FallCurve`]).
    pub fn curve(&self, lo: f64, hi: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let x = crate::stats::linspace(lo, hi, n);
        let p = x.iter().map(|&v| self.probability(v)).collect();
        (x, p)
    }

    /// The impulse where the probability is 1/2: -a / b.
    pub fn impulse_at_half(&self) -> f64 {
        -self.intercept / self.slope
    }
}

/// How [`impulse_at_50pct_fall`] obtained its estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Fall50Method {
    /// Maximum-likelihood logistic fit, -a / b.
    Logistic,
    /// No push made the robot fall: the largest impulse tested (a lower bound).
    NoFalls,
    /// Every push made the robot fall: the smallest impulse tested (an upper bound).
    AllFell,
    /// Every fall had a larger impulse than every survived push (the maximum-likelihood slope
    /// is infinite): the midpoint between the largest survived and the smallest fallen impulse.
    Separated,
    /// The fit says falls do not become more likely with the impulse (slope <= 0), or the
    /// 50% point lies outside the tested range: the largest impulse tested if fewer than half
    /// of the pushes fell, else the smallest.
    Inconclusive,
}

/// The impulse at which half the pushes make the robot fall, with how it was found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Fall50Estimate {
    /// The estimate (Ns).
    pub impulse_ns: f64,
    /// How it was obtained.
    pub method: Fall50Method,
    /// The logistic fit, when it exists.
    pub fit: Option<LogisticFit>,
}

/// (min, max) impulse of the pushes with `fell == which` (infinities if there are none).
fn range_of(samples: &[PushResult], which: bool) -> (f64, f64) {
    samples
        .iter()
        .filter(|s| s.1 == which)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.0), hi.max(s.0))
        })
}

fn check_samples(samples: &[PushResult]) -> Result<(), ReportError> {
    if samples.is_empty() {
        return Err(ReportError::invalid(
            "no pushes to estimate a fall rate from",
        ));
    }
    if let Some((x, _)) = samples.iter().find(|(x, _)| !x.is_finite()) {
        return Err(ReportError::invalid(format!(
            "push impulse {x} is not finite"
        )));
    }
    Ok(())
}

/// Maximum-likelihood logistic regression of `fell` on `impulse` by Newton's method with step
/// halving, on impulses standardised to mean 0 and standard deviation 1 (for conditioning) and
/// mapped back. `None` when the maximum likelihood estimate does not exist or is not reached:
/// no falls, no survivals, (quasi-)separated data (every fall on one side of every survived
/// push, or a standardised slope beyond 100), or all impulses equal.
pub fn fit_logistic(samples: &[PushResult]) -> Result<Option<LogisticFit>, ReportError> {
    check_samples(samples)?;
    let stats = crate::stats::MeanStd::of(samples.iter().map(|s| s.0));
    let (mean, std) = (stats.mean(), stats.population_std());
    let falls = samples.iter().filter(|s| s.1).count();
    if std == 0.0 || falls == 0 || falls == samples.len() {
        return Ok(None);
    }
    let (survived, fell) = (range_of(samples, false), range_of(samples, true));
    if survived.1 <= fell.0 || fell.1 <= survived.0 {
        return Ok(None);
    }
    let z: Vec<(f64, f64)> = samples
        .iter()
        .map(|&(x, f)| ((x - mean) / std, if f { 1.0 } else { 0.0 }))
        .collect();
    let log_lik = |a: f64, b: f64| -> f64 {
        z.iter()
            .map(|&(zi, yi)| {
                let t = a + b * zi;
                // log p = -log(1 + e^-t), log(1 - p) = -log(1 + e^t), computed stably
                let softplus = |u: f64| u.max(0.0) + (-u.abs()).exp().ln_1p();
                -yi * softplus(-t) - (1.0 - yi) * softplus(t)
            })
            .sum()
    };
    let (mut a, mut b) = (0.0f64, 0.0f64);
    let mut ll = log_lik(a, b);
    for _ in 0..200 {
        let (mut g0, mut g1, mut h00, mut h01, mut h11) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for &(zi, yi) in &z {
            let p = 1.0 / (1.0 + (-(a + b * zi)).exp());
            let w = p * (1.0 - p);
            g0 += yi - p;
            g1 += (yi - p) * zi;
            h00 += w;
            h01 += w * zi;
            h11 += w * zi * zi;
        }
        let det = h00 * h11 - h01 * h01;
        if !(det > 0.0 && det.is_finite()) {
            return Ok(None);
        }
        // Newton step for the (concave) log-likelihood: delta = H^-1 g with H the information.
        let (mut da, mut db) = ((h11 * g0 - h01 * g1) / det, (h00 * g1 - h01 * g0) / det);
        let mut improved = false;
        for _ in 0..50 {
            let cand = log_lik(a + da, b + db);
            if cand >= ll {
                a += da;
                b += db;
                improved = cand - ll > 0.0;
                ll = cand;
                break;
            }
            da *= 0.5;
            db *= 0.5;
        }
        if b.abs() > 100.0 {
            return Ok(None);
        }
        if !improved || da.abs().max(db.abs()) < 1e-12 {
            return Ok(Some(LogisticFit {
                intercept: a - b * mean / std,
                slope: b / std,
            }));
        }
    }
    Ok(None)
}

/// Estimates the impulse at which half the pushes make the robot fall (Fig. 6's 50% point)
/// from (impulse, fell) pairs: the logistic fit's -a/b when it exists and lies within the tested
/// range, otherwise the documented fallback of [`Fall50Method`]. Errors on no data or a
/// non-finite impulse.
pub fn impulse_at_50pct_fall(samples: &[PushResult]) -> Result<Fall50Estimate, ReportError> {
    check_samples(samples)?;
    let lo = samples.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
    let hi = samples
        .iter()
        .map(|s| s.0)
        .fold(f64::NEG_INFINITY, f64::max);
    let falls = samples.iter().filter(|s| s.1).count();
    let estimate = |impulse_ns, method, fit| Fall50Estimate {
        impulse_ns,
        method,
        fit,
    };
    if falls == 0 {
        return Ok(estimate(hi, Fall50Method::NoFalls, None));
    }
    if falls == samples.len() {
        return Ok(estimate(lo, Fall50Method::AllFell, None));
    }
    let max_survived = range_of(samples, false).1;
    let min_fell = range_of(samples, true).0;
    let fit = fit_logistic(samples)?;
    let inconclusive = if 2 * falls < samples.len() { hi } else { lo };
    match fit {
        Some(f) if f.slope > 0.0 => {
            let x = f.impulse_at_half();
            if x.is_finite() && (lo..=hi).contains(&x) {
                Ok(estimate(x, Fall50Method::Logistic, fit))
            } else {
                Ok(estimate(inconclusive, Fall50Method::Inconclusive, fit))
            }
        }
        Some(_) => Ok(estimate(inconclusive, Fall50Method::Inconclusive, fit)),
        None if max_survived <= min_fell => Ok(estimate(
            0.5 * (max_survived + min_fell),
            Fall50Method::Separated,
            None,
        )),
        None => Ok(estimate(inconclusive, Fall50Method::Inconclusive, None)),
    }
}

/// Pushes and falls in one impulse bin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FallBin {
    /// Lower edge (Ns).
    pub lo: f64,
    /// Upper edge (Ns).
    pub hi: f64,
    /// Pushes in the bin.
    pub pushes: usize,
    /// Falls among them.
    pub falls: usize,
}

impl FallBin {
    /// Bin centre.
    pub fn center(&self) -> f64 {
        0.5 * (self.lo + self.hi)
    }

    /// Fraction of pushes that made the robot fall (`None` for an empty bin).
    pub fn fraction(&self) -> Option<f64> {
        (self.pushes > 0).then(|| self.falls as f64 / self.pushes as f64)
    }
}

/// Counts pushes and falls in `bins` equal bins over [lo, hi]; impulses outside the range count
/// in the nearest end bin.
pub fn fall_rate_bins(
    samples: &[PushResult],
    lo: f64,
    hi: f64,
    bins: usize,
) -> Result<Vec<FallBin>, ReportError> {
    if !(lo.is_finite() && hi.is_finite() && lo < hi && bins > 0) {
        return Err(ReportError::invalid(format!(
            "fall-rate bins need finite lo < hi and at least one bin, got [{lo}, {hi}] x {bins}"
        )));
    }
    if let Some((x, _)) = samples.iter().find(|(x, _)| !x.is_finite()) {
        return Err(ReportError::invalid(format!(
            "push impulse {x} is not finite"
        )));
    }
    let width = (hi - lo) / bins as f64;
    let mut out: Vec<FallBin> = (0..bins)
        .map(|i| FallBin {
            lo: lo + width * i as f64,
            hi: lo + width * (i + 1) as f64,
            pushes: 0,
            falls: 0,
        })
        .collect();
    for &(x, fell) in samples {
        let i = (((x - lo) / width).floor().max(0.0) as usize).min(bins - 1);
        out[i].pushes += 1;
        out[i].falls += usize::from(fell);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::ChaCha8Rng;
    use rand::{RngExt, SeedableRng};

    #[test]
    fn recovers_a_known_logistic_curve() {
        // true P(fall) = sigmoid((x - 10) / 1.5), 4000 pushes uniform in [0, 20]
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let samples: Vec<PushResult> = (0..4000)
            .map(|_| {
                let x: f64 = rng.random_range(0.0..20.0);
                let p = 1.0 / (1.0 + (-(x - 10.0) / 1.5).exp());
                (x, rng.random_range(0.0..1.0) < p)
            })
            .collect();
        let est = impulse_at_50pct_fall(&samples).unwrap();
        assert_eq!(est.method, Fall50Method::Logistic);
        assert!((est.impulse_ns - 10.0).abs() < 0.3, "{est:?}");
        let fit = est.fit.unwrap();
        assert!((fit.slope - 1.0 / 1.5).abs() < 0.08, "{fit:?}");
        assert!((fit.probability(est.impulse_ns) - 0.5).abs() < 1e-9);
        let (x, p) = fit.curve(0.0, 20.0, 5);
        assert_eq!(x, vec![0.0, 5.0, 10.0, 15.0, 20.0]);
        assert!(p.windows(2).all(|w| w[0] < w[1]) && p[0] < 0.01 && p[4] > 0.99);
        // same data, same answer
        assert_eq!(impulse_at_50pct_fall(&samples).unwrap(), est);
    }

    #[test]
    fn symmetric_data_gives_the_exact_centre() {
        let mut samples = Vec::new();
        for (x, falls) in [(8.0, 1), (12.0, 3)] {
            for k in 0..4 {
                samples.push((x, k < falls));
            }
        }
        let est = impulse_at_50pct_fall(&samples).unwrap();
        assert_eq!(est.method, Fall50Method::Logistic);
        assert!((est.impulse_ns - 10.0).abs() < 1e-9, "{est:?}");
        // ln 3 = slope * 2 at x = 12
        assert!((est.fit.unwrap().slope - 3f64.ln() / 2.0).abs() < 1e-9);
    }

    #[test]
    fn fallbacks_when_the_fit_does_not_exist() {
        let none = [(2.0, false), (5.0, false), (9.0, false)];
        let e = impulse_at_50pct_fall(&none).unwrap();
        assert_eq!((e.impulse_ns, e.method), (9.0, Fall50Method::NoFalls));
        let all = [(2.0, true), (5.0, true), (9.0, true)];
        let e = impulse_at_50pct_fall(&all).unwrap();
        assert_eq!((e.impulse_ns, e.method), (2.0, Fall50Method::AllFell));
        let separated = [(2.0, false), (5.0, false), (7.0, true), (9.0, true)];
        let e = impulse_at_50pct_fall(&separated).unwrap();
        assert_eq!((e.impulse_ns, e.method), (6.0, Fall50Method::Separated));
        let quasi = [(2.0, false), (5.0, false), (5.0, true), (9.0, true)];
        let e = impulse_at_50pct_fall(&quasi).unwrap();
        assert_eq!((e.impulse_ns, e.method), (5.0, Fall50Method::Separated));
        // falls at small impulses only: slope < 0
        let backwards = [
            (1.0, true),
            (2.0, true),
            (3.0, false),
            (4.0, true),
            (8.0, false),
            (9.0, false),
        ];
        let e = impulse_at_50pct_fall(&backwards).unwrap();
        assert_eq!(e.method, Fall50Method::Inconclusive);
        assert_eq!(e.impulse_ns, 1.0);
        assert!(impulse_at_50pct_fall(&[]).is_err());
        assert!(impulse_at_50pct_fall(&[(f64::NAN, true)]).is_err());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { rng_seed: proptest::test_runner::RngSeed::Fixed(11), failure_persistence: None, ..proptest::prelude::ProptestConfig::default() })]
        /// Shifting every impulse by c shifts the 50% estimate by c, with the same method.
        #[test]
        fn estimate_is_translation_equivariant(
            pushes in proptest::collection::vec((0.0..20.0f64, proptest::bool::ANY), 1..60),
            c in -5.0..5.0f64,
        ) {
            let a = impulse_at_50pct_fall(&pushes).unwrap();
            let shifted: Vec<PushResult> = pushes.iter().map(|&(x, f)| (x + c, f)).collect();
            let b = impulse_at_50pct_fall(&shifted).unwrap();
            proptest::prop_assert_eq!(a.method, b.method);
            proptest::prop_assert!((b.impulse_ns - a.impulse_ns - c).abs() < 1e-6,
                "{a:?} vs {b:?}");
            let lo = pushes.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let hi = pushes.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
            proptest::prop_assert!(a.impulse_ns >= lo && a.impulse_ns <= hi);
        }
    }

    #[test]
    fn bins_count_pushes_and_falls() {
        let samples = [
            (0.5, false),
            (1.5, true),
            (1.9, false),
            (5.0, true),
            (-1.0, true),
        ];
        let bins = fall_rate_bins(&samples, 0.0, 4.0, 2).unwrap();
        assert_eq!((bins[0].pushes, bins[0].falls), (4, 2));
        assert_eq!((bins[1].pushes, bins[1].falls), (1, 1));
        assert_eq!(bins[0].fraction(), Some(0.5));
        assert_eq!(bins[1].center(), 3.0);
        assert!(fall_rate_bins(&samples, 1.0, 1.0, 2).is_err());
        assert_eq!(
            fall_rate_bins(&[], 0.0, 1.0, 1).unwrap()[0].fraction(),
            None
        );
    }
}
