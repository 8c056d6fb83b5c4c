//! The main job: the paper's four experiments with one approximator and rule (by default LWPR
//! and the pendulum-cart rule) over several seeds, and a report of whether each of the paper's
//! four claims holds, seed by seed and paired over seeds.
//!
//! The runs go through the sweep machinery ([`crate::experiments::sweep::run_sweep`]): one directory per
//! run with its CSV, SVG and `summary.json`, finished runs reused. [`Claims::from_summaries`]
//! then reads only the summaries, so the verdicts can be recomputed from the files alone.

use crate::Named;
use crate::experiments::ExperimentKind;
use crate::experiments::error::ExperimentError;
use crate::experiments::paired::Verdict;
use crate::experiments::summary::Summary;
use crate::experiments::sweep::{RunSpec, Runner, SUMMARY_FILE, SweepGrid, read_current};
use crate::experiments::{disturbance, robustness, stability, tracking};
use crate::report::{ReportError, write_file};
use serde::{Deserialize, Serialize};
use std::path::Path;
use strum::VariantArray;

/// The runs of a reproduction: the paper's four experiments with `approx` and `rule`, seeds
/// `0..seeds`.
pub fn grid(approx: &str, rule: &str, seeds: u64) -> SweepGrid {
    let experiments: Vec<&str> = ExperimentKind::VARIANTS.iter().map(|k| k.name()).collect();
    SweepGrid::new(&experiments, &[approx], &[rule], seeds)
}

use crate::experiments::claim::Claim;

/// The paper's four claims, checked on a set of summaries.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Claims {
    /// 1: learned std of F_E below the model's at every time after a reference change.
    pub tracking: Claim,
    /// 2: after 8 Ns pushes the learned walker returns sooner, TDA near p_theta.
    pub disturbance: Claim,
    /// 3: impulse at 50% falls learned > model > open-loop.
    pub stability: Claim,
    /// 4: without initialisation, a push absorbed within the first three pushes, and more
    /// pushes absorbed than by the same walker without learning.
    pub robustness: Claim,
    /// Tracking: mean over the seeds with data in every bin of the std of F_E per bin,
    /// (bin centre s, model, learned); empty if no seed has.
    pub tracking_std_mean: Vec<(f64, f64, f64)>,
}

impl Claims {
    /// Checks the claims on `summaries` (any order; other approximators or rules are ignored
    /// by the caller's choice of summaries). `p_theta` is the rule's TDA tolerance.
    pub fn from_summaries(summaries: &[Summary], p_theta: f64) -> Self {
        Self::from_runs(&summaries.iter().collect::<Vec<_>>(), p_theta)
    }

    /// [`Claims::from_summaries`] on borrowed summaries. Each built-in experiment's
    /// leaderboard comparisons are its claim's `over_seeds` (one definition for both), which
    /// `p_theta` does not enter.
    pub fn from_runs(summaries: &[&Summary], p_theta: f64) -> Self {
        Claims {
            tracking: tracking::claim(summaries),
            disturbance: disturbance::claim(summaries, p_theta),
            stability: stability::claim(summaries),
            robustness: robustness::claim(summaries),
            tracking_std_mean: tracking::std_over_seeds(summaries),
        }
    }

    /// The four claims in order.
    pub fn all(&self) -> [&Claim; 4] {
        [
            &self.tracking,
            &self.disturbance,
            &self.stability,
            &self.robustness,
        ]
    }

    /// One line per claim stating both verdicts: paired over seeds (the claim's headline
    /// comparison: better, level or worse, with its mean and 95% interval) and strict per seed
    /// (holds on k of N seeds).
    pub fn lead_lines(&self) -> Vec<String> {
        self.all()
            .iter()
            .zip(LEADS)
            .enumerate()
            .map(|(i, (c, lead))| lead.line(i + 1, c))
            .collect()
    }

    /// A Markdown report of the claims checked with approximator `approx` and rule `rule`: the
    /// lead lines, then one section per claim with its verdicts and per-seed figures.
    pub fn to_markdown(&self, approx: &str, rule: &str) -> String {
        let mut md = format!("# Reproduction of the paper's claims ({approx} + {rule})\n\n");
        for line in self.lead_lines() {
            md.push_str(&format!("- {line}\n"));
        }
        md.push_str(
            "\nPaired over seeds compares learned and model on the same seeds: better or worse \
             when the 95% Student-t interval of the mean difference (or ratio) excludes no \
             difference, level when it contains it. Strict per seed counts the seeds on which \
             the claim holds as the paper states it; the claim is reproduced strictly only when \
             enough seeds pass (the rule is in each claim's statement).\n\n",
        );
        for c in self.all() {
            md.push_str(&format!(
                "## {}\n\nStrict per seed: **{}** ({} of {} seeds)\n\n| seed | holds | measured |\n|---|---|---|\n",
                c.statement,
                if c.holds {
                    "reproduced"
                } else {
                    "not reproduced"
                },
                c.seeds_holding(),
                c.seeds.len()
            ));
            for (seed, holds, text) in &c.seeds {
                md.push_str(&format!(
                    "| {seed} | {} | {text} |\n",
                    if *holds { "yes" } else { "no" }
                ));
            }
            md.push('\n');
            if !c.over_seeds.is_empty() {
                md.push_str(
                    "Over seeds, paired by seed (95% Student-t interval of the mean; level: \
                     no difference beyond the seed-to-seed noise):\n\n\
                     | quantity | mean | 95% interval | seeds | verdict |\n|---|---|---|---|---|\n",
                );
                for p in &c.over_seeds {
                    let (interval, verdict) = match p.verdict {
                        Some(v) => (format!("[{:.3}, {:.3}]", p.ci95.0, p.ci95.1), v.to_string()),
                        None => ("-".to_string(), "too few seeds".to_string()),
                    };
                    md.push_str(&format!(
                        "| {} | {:.3} | {interval} | {} | {verdict} |\n",
                        p.quantity,
                        p.mean,
                        p.values.len()
                    ));
                }
                md.push('\n');
            }
        }
        md
    }

    /// Writes `claims.md` (titled with `approx` and `rule`), `claims.json` and the figures
    /// across seeds (`<experiment>_..._over_seeds.svg`, from the runs of the claims' seeds
    /// under `dir`) into `dir`.
    pub fn write(&self, dir: &Path, approx: &str, rule: &str) -> Result<(), ExperimentError> {
        std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
        write_file(
            &dir.join("claims.md"),
            self.to_markdown(approx, rule).as_bytes(),
        )?;
        let json =
            serde_json::to_string_pretty(self).map_err(|e| ReportError::invalid(e.to_string()))?;
        write_file(&dir.join("claims.json"), json.as_bytes())?;
        let runs = |kind: ExperimentKind, claim: &Claim| -> Vec<std::path::PathBuf> {
            claim
                .seeds
                .iter()
                .map(|(seed, _, _)| {
                    dir.join(
                        RunSpec {
                            experiment: kind.name().to_string(),
                            approx: approx.to_string(),
                            rule: rule.to_string(),
                            seed: *seed,
                            learn: None,
                        }
                        .id(),
                    )
                })
                .collect()
        };
        let summaries = |dirs: &[std::path::PathBuf]| -> Result<Vec<Summary>, ExperimentError> {
            dirs.iter()
                .map(|d| d.join(SUMMARY_FILE))
                .filter(|p| p.is_file())
                .map(|p| Summary::read(&p).map_err(ExperimentError::from))
                .collect()
        };
        let tracking_runs = summaries(&runs(ExperimentKind::Tracking, &self.tracking))?;
        tracking::figure_over_seeds(dir, &tracking_runs.iter().collect::<Vec<_>>())?;
        disturbance::figure_over_seeds(dir, &runs(ExperimentKind::Disturbance, &self.disturbance))?;
        stability::figure_over_seeds(dir, &runs(ExperimentKind::Stability, &self.stability))?;
        let robustness_runs = summaries(&runs(ExperimentKind::Robustness, &self.robustness))?;
        robustness::figure_over_seeds(dir, &robustness_runs.iter().collect::<Vec<_>>())?;
        Ok(())
    }
}

/// How a claim's lead line names it and its headline comparison.
#[derive(Debug, Clone, Copy)]
struct Lead {
    /// The experiment (A-D) and its name.
    experiment: &'static str,
    /// The paper's figures.
    figures: &'static str,
    /// What the learned walker is compared with.
    against: &'static str,
    /// The headline quantity, in words.
    quantity: &'static str,
    /// Its unit after the number (with its leading space), or "" for a ratio.
    unit: &'static str,
    /// Decimals shown.
    decimals: usize,
}

/// The lead of each claim, in the order of [`Claims::all`].
const LEADS: [Lead; 4] = [
    Lead {
        experiment: "A, tracking",
        figures: "Fig. 4",
        against: "the model",
        quantity: "std of F_E after a reference change, learned - model",
        unit: " cm",
        decimals: 2,
    },
    Lead {
        experiment: "B, disturbance",
        figures: "Fig. 5",
        against: "the model",
        quantity: "return time to F_R after a push, learned - model",
        unit: " s",
        decimals: 2,
    },
    Lead {
        experiment: "C, stability",
        figures: "Fig. 6",
        against: "the model",
        quantity: "I50 learned / model",
        unit: "",
        decimals: 3,
    },
    Lead {
        experiment: "D, robustness",
        figures: "Figs. 7-8",
        against: "the same walker without learning",
        quantity: "pushes absorbed, learned - without learning",
        unit: " pushes",
        decimals: 1,
    },
];

impl Lead {
    /// Claim `n`'s lead line.
    fn line(&self, n: usize, c: &Claim) -> String {
        let d = self.decimals;
        let paired = match c.headline() {
            Some(p) => {
                // Differences carry their sign; ratios (null 1) do not.
                let num = |v: f64| {
                    if p.null == 0.0 {
                        format!("{v:+.d$}")
                    } else {
                        format!("{v:.d$}")
                    }
                };
                match p.verdict {
                    Some(v) => {
                        let standing = match v {
                            Verdict::Better => format!("better than {}", self.against),
                            Verdict::Level => format!("level with {}", self.against),
                            Verdict::Worse => format!("worse than {}", self.against),
                        };
                        format!(
                            "learned {standing} over seeds ({}), mean {}{u}, 95% [{}, {}]",
                            self.quantity,
                            num(p.mean),
                            num(p.ci95.0),
                            num(p.ci95.1),
                            u = self.unit
                        )
                    }
                    None => format!(
                        "too few seeds for a paired verdict ({}), mean {}{}",
                        self.quantity,
                        num(p.mean),
                        self.unit
                    ),
                }
            }
            None => "no paired comparison".to_string(),
        };
        format!(
            "Claim {n}, experiment {} (paper {}): {paired}; strict per seed: {} on {} of {} seeds",
            self.experiment,
            self.figures,
            if c.holds {
                "reproduced, holds"
            } else {
                "not reproduced, holds"
            },
            c.seeds_holding(),
            c.seeds.len()
        )
    }
}

/// Reads the summaries of `grid`'s runs under `out` (one directory per run id); runs without a
/// summary, or whose recorded identity is not `runner`'s, are left out and listed in the second
/// value.
pub fn read_summaries(
    grid: &SweepGrid,
    out: &Path,
    runner: &dyn Runner,
) -> Result<(Vec<Summary>, Vec<String>), ExperimentError> {
    let runs = grid
        .runs()
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let mut summaries = Vec::new();
    let mut missing = Vec::new();
    for spec in runs {
        match read_current(runner, &spec, out)? {
            Some(summary) => summaries.push(summary),
            None => missing.push(spec.id()),
        }
    }
    Ok((summaries, missing))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::disturbance::{DisturbanceSummary, PushFalls};
    use crate::experiments::robustness::{NoLearning, RobustnessSummary};
    use crate::experiments::stability::{ControllerFalls, Controllers, StabilitySummary};
    use crate::experiments::summary::{ModelLearned, TypedResult};
    use crate::experiments::tracking::TrackingSummary;

    fn summary(seed: u64, result: impl TypedResult) -> Summary {
        Summary {
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed,
            learn: Default::default(),
            robot: None,
            result: result.into_result().unwrap(),
        }
    }

    fn falls(i50: f64) -> ControllerFalls {
        ControllerFalls {
            pushes: 10,
            falls: 5,
            impulse_at_50pct_fall_ns: i50,
        }
    }

    fn robustness(seed: u64, learned: [bool; 4], without: [bool; 4]) -> Summary {
        let misses = |a: &[bool; 4]| a.iter().filter(|&&x| !x).count() as u32;
        summary(
            seed,
            RobustnessSummary {
                pushes_until_first_absorbed: learned.iter().position(|&a| a).map(|i| i as u32 + 1),
                falls: misses(&learned),
                impulse_ns: Some(10.0),
                absorbed_by_push: learned.to_vec(),
                no_learning: Some(NoLearning {
                    absorbed_by_push: without.to_vec(),
                    falls: misses(&without),
                }),
            },
        )
    }

    fn disturbance(
        seed: u64,
        returns: (f64, f64),
        pushes: (u32, u32),
        falls: (u32, u32),
    ) -> Summary {
        summary(
            seed,
            DisturbanceSummary {
                return_time_s: ModelLearned {
                    model: returns.0,
                    learned: returns.1,
                },
                return_time_by_step_s: None,
                // Settled half a second before returning (a steady bias of either walker).
                settle_time_s: Some(ModelLearned {
                    model: (returns.0 - 0.5).max(0.0),
                    learned: (returns.1 - 0.5).max(0.0),
                }),
                // 1 cm per second of return time.
                step_error_after_push_m: Some(ModelLearned {
                    model: returns.0 / 100.0,
                    learned: returns.1 / 100.0,
                }),
                max_tda_rad: ModelLearned {
                    model: 0.1,
                    learned: 0.1,
                },
                falls: Some(PushFalls {
                    pushes: ModelLearned {
                        model: pushes.0,
                        learned: pushes.1,
                    },
                    falls: ModelLearned {
                        model: falls.0,
                        learned: falls.1,
                    },
                    causes: None,
                    // Three more of the learned walker's pushes end in a fall after the window.
                    before_next_push: Some(ModelLearned {
                        model: falls.0,
                        learned: (falls.1 + 3).min(pushes.1),
                    }),
                }),
            },
        )
    }

    #[test]
    fn disturbance_over_seeds_pairs_fall_rates_and_measured_return_times_only() {
        let s = [
            disturbance(0, (3.0, 2.0), (60, 60), (6, 3)),
            disturbance(1, (2.5, 2.0), (60, 30), (6, 6)),
            // The model fell while walking and received no push: no return time, no rate.
            disturbance(2, (4.0, 3.0), (0, 60), (0, 50)),
            // The learned walker absorbed nothing: its return time is the horizon.
            disturbance(3, (2.0, 4.0), (60, 60), (6, 60)),
        ];
        let c = Claims::from_summaries(&s, 0.15);
        let [ret, binned, settle, error, rate, late] = &c.disturbance.over_seeds[..] else {
            panic!("six paired quantities: {:?}", c.disturbance.over_seeds);
        };
        // The fixtures have no return time between touch-downs: the claim falls back to the
        // binned one, paired on the same seeds.
        assert_eq!(binned.values, ret.values);
        // Quantities are Markdown table cells in claims.md (and index.html's tables).
        for c in c.all() {
            for p in &c.over_seeds {
                assert!(!p.quantity.contains('|'), "{}", p.quantity);
            }
        }
        assert_eq!(ret.values, vec![-1.0, -0.5]);
        assert_eq!(settle.values, vec![-1.0, -0.5]);
        // Every seed has step errors (both walkers absorbed a push in the fixtures where it
        // is a measurement; otherwise the summary leaves it out).
        assert_eq!(error.values.len(), 4);
        assert!((error.values[0] - (-1.0)).abs() < 1e-12);
        assert_eq!(rate.values.len(), 3, "{:?}", rate.values);
        assert!((rate.values[0] - (-0.05)).abs() < 1e-12);
        assert!((rate.values[1] - 0.1).abs() < 1e-12);
        assert!((rate.values[2] - 0.9).abs() < 1e-12);
        // The falls before the next push pair the same seeds as the fall rate.
        assert_eq!(late.values.len(), 3, "{:?}", late.values);
        for (v, want) in late.values.iter().zip([0.0, 0.2, 0.9]) {
            assert!((v - want).abs() < 1e-12, "{:?}", late.values);
        }
    }

    #[test]
    fn verdicts_follow_the_claims_seed_by_seed() {
        let s = vec![
            // Tracking: seed 0 better everywhere, seed 1 one bin worse (allowed), seed 2 one
            // bin worse and one without data.
            summary(
                0,
                TrackingSummary {
                    step_error_std_m: ModelLearned {
                        model: vec![Some(0.05), Some(0.02), Some(0.02)],
                        learned: vec![Some(0.04), Some(0.01), Some(0.01)],
                    },
                    bin_s: 0.5,
                },
            ),
            summary(
                1,
                TrackingSummary {
                    step_error_std_m: ModelLearned {
                        model: vec![Some(0.05), Some(0.02), Some(0.02)],
                        learned: vec![Some(0.04), Some(0.03), Some(0.01)],
                    },
                    bin_s: 0.5,
                },
            ),
            summary(
                2,
                TrackingSummary {
                    step_error_std_m: ModelLearned {
                        model: vec![Some(0.05), Some(0.02), Some(0.02)],
                        learned: vec![Some(0.06), None, Some(0.01)],
                    },
                    bin_s: 0.5,
                },
            ),
            // Disturbance: sooner but TDA far above p_theta fails.
            summary(
                0,
                DisturbanceSummary {
                    return_time_s: ModelLearned {
                        model: 3.0,
                        learned: 2.0,
                    },
                    return_time_by_step_s: None,
                    settle_time_s: None,
                    step_error_after_push_m: None,
                    max_tda_rad: ModelLearned {
                        model: 0.1,
                        learned: 0.16,
                    },
                    falls: None,
                },
            ),
            summary(
                1,
                DisturbanceSummary {
                    return_time_s: ModelLearned {
                        model: 3.0,
                        learned: 2.0,
                    },
                    return_time_by_step_s: None,
                    settle_time_s: None,
                    step_error_after_push_m: None,
                    max_tda_rad: ModelLearned {
                        model: 0.1,
                        learned: 0.3,
                    },
                    falls: None,
                },
            ),
            summary(
                0,
                StabilitySummary {
                    controllers: Controllers {
                        open_loop: falls(4.0),
                        model: falls(12.0),
                        learned: falls(13.0),
                    },
                    fall_causes: Default::default(),
                    catch_step_reach: None,
                },
            ),
            // Stability: learned above the model, but the model not 1.5 x open-loop.
            summary(
                1,
                StabilitySummary {
                    controllers: Controllers {
                        open_loop: falls(9.0),
                        model: falls(12.0),
                        learned: falls(13.0),
                    },
                    fall_causes: Default::default(),
                    catch_step_reach: None,
                },
            ),
            // Robustness: seed 0 early and better than without learning; seed 1 too late;
            // seed 2 early but no better than without learning; seed 3 early and better;
            // seed 4 an older summary without the baseline.
            robustness(0, [false, false, true, true], [false, false, false, false]),
            robustness(1, [false, false, false, true], [false, false, false, false]),
            robustness(2, [true, false, false, false], [true, false, false, false]),
            robustness(3, [true, true, false, true], [false, false, true, false]),
            summary(
                4,
                RobustnessSummary {
                    pushes_until_first_absorbed: Some(1),
                    falls: 0,
                    impulse_ns: None,
                    absorbed_by_push: vec![],
                    no_learning: None,
                },
            ),
        ];
        let c = Claims::from_summaries(&s, 0.15);
        let holds = |c: &Claim| c.seeds.iter().map(|s| s.1).collect::<Vec<_>>();
        assert_eq!(holds(&c.tracking), [true, true, false]);
        assert!(!c.tracking.holds);
        assert_eq!(holds(&c.disturbance), [true, false]);
        assert!(!c.disturbance.holds);
        assert_eq!(holds(&c.stability), [true, false]);
        assert!(!c.stability.holds);
        assert_eq!(holds(&c.robustness), [true, false, false, true, false]);
        // 2 of 5 seeds is not "most".
        assert!(!c.robustness.holds);
        assert!(
            c.robustness.seeds[0]
                .2
                .contains("absorbed 2 of 4 pushes at 10 Ns")
        );
        assert!(c.robustness.seeds[4].2.contains("no run without learning"));
        let mut four = s.clone();
        // 4 of 7 seeds is.
        four.push(robustness(5, [false, true, true, true], [false; 4]));
        four.push(robustness(6, [false, false, true, false], [false; 4]));
        assert!(Claims::from_summaries(&four, 0.15).robustness.holds);
        // The mean over seeds uses the seeds with data in every bin (0 and 1).
        assert_eq!(c.tracking_std_mean.len(), 3);
        assert!((c.tracking_std_mean[1].2 - 0.02).abs() < 1e-12);
        assert!((c.tracking_std_mean[0].0 - 0.25).abs() < 1e-12);
        let md = c.to_markdown("lwpr", "pendulum-cart");
        assert!(md.starts_with("# Reproduction of the paper's claims (lwpr + pendulum-cart)"));
        assert!(md.contains("**not reproduced** (1 of 2 seeds)"), "{md}");
        assert!(md.contains("**not reproduced** (2 of 3 seeds)"), "{md}");
        assert!(md.contains("**not reproduced** (2 of 5 seeds)"), "{md}");
        // Over seeds: the per-seed values paired by seed, seeds without a figure left out.
        // The headline first (each seed's mean over its bins), then one comparison per bin.
        let headline = c.tracking.headline().unwrap();
        assert!(headline.quantity.contains("averaged over the bins"));
        assert_eq!(headline.values.len(), 3);
        assert!((headline.values[0] - (-1.0)).abs() < 1e-9, "{headline:?}");
        let bins = &c.tracking.over_seeds[1..];
        assert_eq!(bins.len(), 3);
        assert_eq!(bins[0].values.len(), 3);
        assert_eq!(bins[1].values.len(), 2, "seed 2 has no data in bin 1");
        assert!((bins[0].mean - (-1.0 / 3.0)).abs() < 1e-9, "{:?}", bins[0]);
        assert_eq!(bins[0].verdict, Some(Verdict::Level));
        assert!(
            bins[1].quantity.contains("0.5-1.0 s"),
            "{}",
            bins[1].quantity
        );
        let i50 = &c.stability.over_seeds[0];
        assert_eq!(i50.values.len(), 2);
        assert!((i50.mean - 13.0 / 12.0).abs() < 1e-12);
        assert_eq!(i50.verdict, Some(Verdict::Better));
        let ratio = &c.stability.over_seeds[1];
        assert!((ratio.values[1] - 12.0 / 9.0).abs() < 1e-12);
        assert_eq!(c.disturbance.over_seeds[0].values, vec![-1.0, -1.0]);
        assert_eq!(c.disturbance.over_seeds[1].values, vec![-1.0, -1.0]);
        assert!(
            c.disturbance.over_seeds[2].values.is_empty(),
            "no falls recorded"
        );
        assert_eq!(c.robustness.over_seeds[0].values, vec![2.0, 1.0, 0.0, 2.0]);
        assert!(
            md.contains("| I50 learned / model | 1.083 | [1.083, 1.083] | 2 | better |"),
            "{md}"
        );
        // The lead lines: one per claim, both verdicts, first in claims.md.
        let lead = c.lead_lines();
        assert_eq!(lead.len(), 4);
        assert!(
            lead[2].starts_with("Claim 3, experiment C, stability (paper Fig. 6): learned better than the model over seeds (I50 learned / model), mean 1.083, 95% [1.083, 1.083]; strict per seed: not reproduced, holds on 1 of 2 seeds"),
            "{}",
            lead[2]
        );
        assert!(lead[0].contains("level with the model"), "{}", lead[0]);
        assert!(lead[0].contains("holds on 2 of 3 seeds"), "{}", lead[0]);
        assert!(lead[3].contains("without learning"), "{}", lead[3]);
        let first_section = md.find("\n## ").unwrap();
        for line in &lead {
            assert!(md[..first_section].contains(line.as_str()), "{line}");
        }
        assert!(!md.contains("*level*"));
        // Nothing measured, nothing reproduced.
        assert!(!Claims::from_summaries(&[], 0.15).robustness.holds);
    }
}
