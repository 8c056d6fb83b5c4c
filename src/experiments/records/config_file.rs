//! The configuration file of the `steplearn` command (`--config FILE`, TOML or JSON):
//! `[settings]` ([`Settings`]) and `[protocols.<experiment>]` ([`ProtocolTables`], each table
//! read and checked by its experiment).
//!
//! Strict and checked: every section and key must be known (an unknown one is an error that
//! names it, where it is, and what is allowed); a partial section keeps the defaults for the keys
//! it leaves out, at every level of nesting; values out of range are errors naming the field and
//! the reason ([`ConfigError`]), never silently adjusted. [`ConfigFile::default_toml`] is the
//! complete default file (what `steplearn config` prints).

use crate::config::ConfigError;
use crate::experiments::Experiment;
use crate::experiments::protocol::ProtocolTables;
use crate::experiments::settings::Settings;
use crate::experiments::suite;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thiserror::Error;

/// Why a config file cannot be loaded: each names the file.
#[derive(Debug, Error)]
pub enum ConfigFileError {
    /// The file cannot be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// The file is not valid TOML or JSON, or has an unknown section or key, or a value of
    /// the wrong type.
    #[error("{}: {}", path.display(), describe(source))]
    Parse {
        /// The file.
        path: PathBuf,
        /// Where and why (the table or key's path).
        source: ConfigError,
    },
    /// A value is out of range, or a protocol table is of no listed experiment.
    #[error("{}: invalid value: {source}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The field and why.
        source: ConfigError,
    },
}

/// A whole config file. Every field defaults, so an empty file is the paper's setup.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ConfigFile {
    /// Settings shared by every experiment.
    pub settings: Settings,
    /// Each experiment's protocol table (absent: that experiment's defaults).
    pub protocols: ProtocolTables,
}

impl ConfigFile {
    /// Parses TOML text (not yet validated: see [`ConfigFile::parse_toml`]). A parse error's
    /// `field` is the path of the table or key where it happened (empty at the top).
    pub fn from_toml(text: &str) -> Result<Self, ConfigError> {
        let de =
            toml::Deserializer::parse(text).map_err(|e| ConfigError::new("", e.to_string()))?;
        serde_path_to_error::deserialize(de).map_err(ConfigError::from_path)
    }

    /// Parses JSON text (not yet validated).
    pub fn from_json(text: &str) -> Result<Self, ConfigError> {
        let mut de = serde_json::Deserializer::from_str(text);
        let config: Self =
            serde_path_to_error::deserialize(&mut de).map_err(ConfigError::from_path)?;
        de.end().map_err(|e| ConfigError::new("", e.to_string()))?;
        Ok(config)
    }

    /// Parses and validates TOML text (against the built-in experiments).
    pub fn parse_toml(text: &str) -> Result<Self, ConfigError> {
        let config = Self::from_toml(text)?;
        config.validate()?;
        Ok(config)
    }

    /// Reads, parses (JSON if the name ends in `.json`, TOML otherwise) and validates a file
    /// against the built-in experiments. The message names the file and the offending key or
    /// field.
    pub fn load(path: &Path) -> Result<Self, ConfigFileError> {
        Self::load_for(path, &suite::builtin())
    }

    /// [`ConfigFile::load`] against `experiments` (a registry's): a protocol table is valid
    /// when its experiment accepts it, and a table of no listed experiment is an error.
    pub fn load_for(
        path: &Path,
        experiments: &[Arc<dyn Experiment>],
    ) -> Result<Self, ConfigFileError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigFileError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let config = if path.extension().is_some_and(|e| e == "json") {
            Self::from_json(&text)
        } else {
            Self::from_toml(&text)
        };
        let config = config.map_err(|source| ConfigFileError::Parse {
            path: path.to_path_buf(),
            source,
        })?;
        config
            .validate_for(experiments)
            .map_err(|source| ConfigFileError::Invalid {
                path: path.to_path_buf(),
                source,
            })?;
        Ok(config)
    }

    /// Checks every value of the settings and of the built-in experiments' protocols.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.validate_for(&suite::builtin())
    }

    /// Checks every value of the settings and every protocol table against `experiments`.
    pub fn validate_for(&self, experiments: &[Arc<dyn Experiment>]) -> Result<(), ConfigError> {
        self.resolved_for(experiments).map(drop)
    }

    /// This configuration checked against `experiments`, with every experiment's whole
    /// protocol table (its defaults where this leaves keys or tables out): the configuration
    /// a run records.
    pub fn resolved_for(
        &self,
        experiments: &[Arc<dyn Experiment>],
    ) -> Result<ConfigFile, ConfigError> {
        self.settings.validate()?;
        if let Some(unknown) = self
            .protocols
            .names()
            .find(|name| !experiments.iter().any(|e| e.name() == *name))
        {
            let known: Vec<String> = experiments
                .iter()
                .map(|e| format!("`{}`", e.name()))
                .collect();
            return Err(ConfigError::new(
                "protocols",
                format!(
                    "unknown field `{unknown}`, expected one of {} (the registered experiments)",
                    known.join(", ")
                ),
            ));
        }
        let mut resolved = self.clone();
        for e in experiments {
            let table = e.protocol(&self.protocols)?;
            resolved.protocols.set_table(e.name(), table);
        }
        Ok(resolved)
    }

    /// This configuration as TOML (every key that has a value).
    pub fn to_toml(&self) -> Result<String, ConfigError> {
        toml::to_string_pretty(self).map_err(|e| ConfigError::new("", e.to_string()))
    }

    /// The complete default configuration of the built-in experiments as TOML: every section
    /// and key with its default value (`steplearn config` adds the keys unset by default as
    /// comments, [`with_absent_keys`](crate::experiments::config_keys::with_absent_keys)).
    /// Parsing it gives the defaults.
    pub fn default_toml() -> String {
        Self::default_toml_for(&suite::builtin()).expect("the built-in defaults are valid")
    }

    /// [`ConfigFile::default_toml`] with the protocol tables of `experiments`; an error if an
    /// experiment rejects its own defaults.
    pub fn default_toml_for(experiments: &[Arc<dyn Experiment>]) -> Result<String, ConfigError> {
        let body = Self::default().resolved_for(experiments)?.to_toml()?;
        let mut out = String::from(
            "# steplearn's complete default configuration (`steplearn config`).\n\
             # Use with `--config FILE`; any key or section may be left out (it keeps its\n\
             # default), unknown keys are errors. Check a file with `steplearn config --check FILE`.\n\n",
        );
        out.push_str(&body);
        Ok(out)
    }
}

/// A parse error as one message: "at `settings.sim`: unknown field `x`, expected ...".
fn describe(e: &ConfigError) -> String {
    if e.field.is_empty() {
        e.reason.clone()
    } else {
        format!("at `{}`: {}", e.field, e.reason)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_toml_parses_back_to_the_defaults() {
        let parsed = ConfigFile::parse_toml(&ConfigFile::default_toml()).unwrap();
        let defaults = ConfigFile::default()
            .resolved_for(&suite::builtin())
            .unwrap();
        assert_eq!(parsed, defaults);
        // Resolving is idempotent, and the tables are those of the built-in experiments.
        assert_eq!(parsed.resolved_for(&suite::builtin()).unwrap(), defaults);
        let names: Vec<&str> = defaults.protocols.names().collect();
        assert_eq!(
            names,
            [
                "disturbance",
                "omnidirectional",
                "robustness",
                "stability",
                "tracking"
            ]
        );
    }

    #[test]
    fn a_table_of_no_registered_experiment_is_an_error() {
        let c = ConfigFile::from_toml(
            "[protocols.stabilty]
pushes = 3
",
        )
        .unwrap();
        let e = c.validate().unwrap_err();
        assert_eq!(e.field, "protocols");
        assert!(e.reason.contains("unknown field `stabilty`"), "{e}");
        assert!(e.reason.contains("`stability`"), "{e}");
        // Against no experiments at all, any table is unknown; without tables all is well.
        assert!(c.validate_for(&[]).is_err());
        assert!(ConfigFile::default().validate_for(&[]).is_ok());
    }

    #[test]
    fn unknown_keys_are_named_with_their_path() {
        let e = ConfigFile::from_toml("[settings.sim]\nbogus = 1\n").unwrap_err();
        assert_eq!(e.field, "settings.sim.bogus");
        assert!(e.reason.contains("unknown field `bogus`"), "{e}");
        assert!(e.reason.contains("expected one of"), "{e}");
    }
}
