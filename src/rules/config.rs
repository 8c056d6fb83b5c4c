//! Choosing a rule by name and building it from a validated, serializable config.

use super::{
    BalanceOnly, LearningRule, Linear, PendulumCart, PolicyGradient, PolicyGradientParams,
    RateDamped, TrackingOnly,
};
use crate::Named;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A rule's name, as used on the command line (`--rule`), in run ids and in `summary.json`.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    serde::Serialize,
    serde::Deserialize,
    strum::Display,
    strum::IntoStaticStr,
    strum::VariantArray,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum RuleKind {
    /// [`PendulumCart`], the paper's eq. (5).
    PendulumCart,
    /// [`BalanceOnly`]: G = theta_E.
    BalanceOnly,
    /// [`TrackingOnly`]: the saturated F_E term alone.
    TrackingOnly,
    /// [`Linear`]: eq. (5) without saturation.
    Linear,
    /// [`RateDamped`]: eq. (5) plus k theta_E_dot.
    RateDamped,
    /// [`PolicyGradient`]: model-free REINFORCE with a baseline.
    PolicyGradient,
}

impl std::str::FromStr for RuleKind {
    type Err = RuleError;
    fn from_str(s: &str) -> Result<Self, RuleError> {
        RuleKind::from_name(s).ok_or_else(|| RuleError::UnknownRule(s.to_string()))
    }
}

/// An invalid rule name or parameter.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RuleError {
    /// The name is not one of the variants of [`RuleKind`].
    #[error("unknown rule {0:?} (expected {names})", names = RuleKind::names())]
    UnknownRule(String),
    /// A parameter is out of range.
    #[error("invalid rule parameter {param}: {reason}")]
    InvalidParameter {
        /// The parameter's field name.
        param: &'static str,
        /// Why, with the value.
        reason: String,
    },
    /// A rule's saved state (see [`LearningRule::state`]) does not fit the rule.
    #[error("invalid rule state: {0}")]
    InvalidState(String),
}

/// Any rule with its parameters: the serde form (`{"rule": "pendulum-cart", "p_theta": 0.15,
/// "p_f": 30}`; missing parameters take their defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "rule", rename_all = "kebab-case")]
pub enum RuleConfig {
    /// See [`PendulumCart`].
    PendulumCart(PendulumCart),
    /// See [`BalanceOnly`].
    BalanceOnly(BalanceOnly),
    /// See [`TrackingOnly`].
    TrackingOnly(TrackingOnly),
    /// See [`Linear`].
    Linear(Linear),
    /// See [`RateDamped`].
    RateDamped(RateDamped),
    /// See [`PolicyGradient`].
    PolicyGradient(PolicyGradientParams),
}

impl Default for RuleConfig {
    /// The paper's rule with the paper's parameters.
    fn default() -> Self {
        RuleConfig::PendulumCart(PendulumCart::default())
    }
}

impl From<RuleKind> for RuleConfig {
    /// The rule `kind` with its default parameters.
    fn from(kind: RuleKind) -> Self {
        match kind {
            RuleKind::PendulumCart => RuleConfig::PendulumCart(PendulumCart::default()),
            RuleKind::BalanceOnly => RuleConfig::BalanceOnly(BalanceOnly),
            RuleKind::TrackingOnly => RuleConfig::TrackingOnly(TrackingOnly::default()),
            RuleKind::Linear => RuleConfig::Linear(Linear::default()),
            RuleKind::RateDamped => RuleConfig::RateDamped(RateDamped::default()),
            RuleKind::PolicyGradient => RuleConfig::PolicyGradient(PolicyGradientParams::default()),
        }
    }
}

/// Checks that a parameter is finite and >= 0.
fn non_negative(param: &'static str, value: f64) -> Result<(), RuleError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(RuleError::InvalidParameter {
            param,
            reason: format!("must be finite and >= 0, got {value}"),
        })
    }
}

impl RuleConfig {
    /// Which rule this is.
    pub fn kind(&self) -> RuleKind {
        match self {
            RuleConfig::PendulumCart(_) => RuleKind::PendulumCart,
            RuleConfig::BalanceOnly(_) => RuleKind::BalanceOnly,
            RuleConfig::TrackingOnly(_) => RuleKind::TrackingOnly,
            RuleConfig::Linear(_) => RuleKind::Linear,
            RuleConfig::RateDamped(_) => RuleKind::RateDamped,
            RuleConfig::PolicyGradient(_) => RuleKind::PolicyGradient,
        }
    }

    /// Checks every parameter: p_theta, p_F and k must be finite and >= 0 (a negative value
    /// would flip the sign of a term and make the rule push the wrong way); see
    /// [`PolicyGradientParams::validate`] for the policy gradient's.
    pub fn validate(&self) -> Result<(), RuleError> {
        match *self {
            RuleConfig::PendulumCart(PendulumCart { p_theta, p_f })
            | RuleConfig::TrackingOnly(TrackingOnly { p_theta, p_f })
            | RuleConfig::Linear(Linear { p_theta, p_f }) => {
                non_negative("p_theta", p_theta)?;
                non_negative("p_f", p_f)
            }
            RuleConfig::BalanceOnly(_) => Ok(()),
            RuleConfig::RateDamped(RateDamped { p_theta, p_f, k }) => {
                non_negative("p_theta", p_theta)?;
                non_negative("p_f", p_f)?;
                non_negative("k", k)
            }
            RuleConfig::PolicyGradient(p) => p.validate(),
        }
    }

    /// Validates and builds the rule.
    pub fn build(&self) -> Result<Box<dyn LearningRule>, RuleError> {
        self.validate()?;
        Ok(match *self {
            RuleConfig::PendulumCart(r) => Box::new(r),
            RuleConfig::BalanceOnly(r) => Box::new(r),
            RuleConfig::TrackingOnly(r) => Box::new(r),
            RuleConfig::Linear(r) => Box::new(r),
            RuleConfig::RateDamped(r) => Box::new(r),
            RuleConfig::PolicyGradient(p) => Box::new(PolicyGradient::new(p)?),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rules::StepOutcome;
    use strum::VariantArray;

    #[test]
    #[cfg(feature = "cli")]
    fn names_round_trip_through_str_serde_and_clap() {
        use clap::ValueEnum;
        for &kind in RuleKind::VARIANTS {
            assert_eq!(kind.name().parse::<RuleKind>(), Ok(kind));
            let json = serde_json::to_string(&kind).unwrap();
            assert_eq!(json, format!("\"{}\"", kind.name()));
            assert_eq!(RuleKind::from_str(kind.name(), false), Ok(kind));
            assert_eq!(RuleConfig::from(kind).kind(), kind);
        }
        assert!(matches!(
            "pendulum".parse::<RuleKind>(),
            Err(RuleError::UnknownRule(_))
        ));
    }

    #[test]
    fn config_serde_uses_tag_and_defaults() {
        let cfg: RuleConfig = serde_json::from_str(r#"{"rule":"pendulum-cart"}"#).unwrap();
        assert_eq!(cfg, RuleConfig::PendulumCart(PendulumCart::default()));
        let cfg: RuleConfig = serde_json::from_str(r#"{"rule":"rate-damped","k":0.5}"#).unwrap();
        assert_eq!(
            cfg,
            RuleConfig::RateDamped(RateDamped {
                k: 0.5,
                ..Default::default()
            })
        );
        let cfg: RuleConfig = serde_json::from_str(r#"{"rule":"balance-only"}"#).unwrap();
        assert_eq!(cfg.kind(), RuleKind::BalanceOnly);
        for &kind in RuleKind::VARIANTS {
            let cfg = RuleConfig::from(kind);
            let back: RuleConfig =
                serde_json::from_str(&serde_json::to_string(&cfg).unwrap()).unwrap();
            assert_eq!(back, cfg);
        }
        assert!(serde_json::from_str::<RuleConfig>(r#"{"rule":"linear","p_x":1}"#).is_err());
        assert!(serde_json::from_str::<RuleConfig>(r#"{"rule":"nope"}"#).is_err());
    }

    #[test]
    fn build_rejects_bad_parameters_and_builds_good_ones() {
        let bad = [
            RuleConfig::PendulumCart(PendulumCart {
                p_theta: -0.1,
                p_f: 30.0,
            }),
            RuleConfig::Linear(Linear {
                p_theta: 0.15,
                p_f: f64::NAN,
            }),
            RuleConfig::RateDamped(RateDamped {
                k: f64::INFINITY,
                ..Default::default()
            }),
        ];
        for cfg in bad {
            assert!(matches!(
                cfg.build(),
                Err(RuleError::InvalidParameter { .. })
            ));
        }
        let step = StepOutcome {
            theta_e: 0.1,
            theta_e_dot: 0.0,
            f_e: 0.0,
            f_r: 0.2,
        };
        for &kind in RuleKind::VARIANTS {
            let rule = RuleConfig::from(kind).build().unwrap();
            let g = rule.gradient(&step);
            // policy-gradient learns only through `learn`, with its perturbation
            let expected = if matches!(kind, RuleKind::TrackingOnly | RuleKind::PolicyGradient) {
                0.0
            } else {
                0.1
            };
            assert_eq!(g, expected, "{kind}");
        }
    }
}
