//! A claim of the paper checked on a set of runs: a verdict per seed (strict) and the claim's
//! figures paired over seeds (learned against model, with 95% intervals).

use crate::experiments::paired::Paired;
use crate::experiments::summary::Summary;
use serde::{Deserialize, Serialize};

/// One claim's verdict per seed and overall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Claim {
    /// The claim, in words.
    pub statement: String,
    /// `(seed, holds, the measured figures in words)`, by seed.
    pub seeds: Vec<(u64, bool, String)>,
    /// Whether it holds overall (the rule for "overall" is in `statement`).
    pub holds: bool,
    /// The claim's figures compared over seeds (learned against model, paired by seed, with
    /// 95% intervals): whether a difference exceeds the seed-to-seed noise; the first is the
    /// claim's headline. Empty in reports written before these existed.
    #[serde(default)]
    pub over_seeds: Vec<Paired>,
}

impl Claim {
    /// A claim holding overall when `overall(seeds where it holds, seeds)`.
    pub fn new(
        statement: &str,
        seeds: Vec<(u64, bool, String)>,
        overall: impl Fn(usize, usize) -> bool,
        over_seeds: Vec<Paired>,
    ) -> Self {
        let n = seeds.len();
        let k = seeds.iter().filter(|s| s.1).count();
        Claim {
            statement: statement.to_string(),
            holds: n > 0 && overall(k, n),
            seeds,
            over_seeds,
        }
    }

    /// The seeds on which the claim holds.
    pub fn seeds_holding(&self) -> usize {
        self.seeds.iter().filter(|s| s.1).count()
    }

    /// The comparison that sums the claim up over seeds (the first of `over_seeds`).
    pub fn headline(&self) -> Option<&Paired> {
        self.over_seeds.first()
    }

    /// Holds on every seed.
    pub fn every(k: usize, n: usize) -> bool {
        k == n
    }

    /// Holds on most seeds.
    pub fn most(k: usize, n: usize) -> bool {
        2 * k > n
    }
}

/// The summaries of `runs` that `pick` accepts, in seed order, with what it picked.
pub fn by_seed<'a, T>(
    runs: &[&'a Summary],
    pick: impl Fn(&'a Summary) -> Option<T>,
) -> Vec<(u64, T)> {
    let mut picked: Vec<(u64, T)> = runs
        .iter()
        .filter_map(|s| pick(s).map(|t| (s.seed, t)))
        .collect();
    picked.sort_by_key(|(seed, _)| *seed);
    picked
}
