//! The `[protocols]` section of a config file: one table per experiment, under its registered
//! name, which that experiment alone reads and checks ([`Protocol`]).
//!
//! The tables are kept as TOML values until an experiment reads its own, so a user's
//! experiment brings its protocol the same way the paper's do, and the section names only
//! what the registry holds (see `Experiment::protocol`).

use crate::config::ConfigError;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A protocol table as the config file holds it (a TOML table; re-exported so that an
/// experiment's crate needs no `toml` dependency).
pub type Table = toml::Table;

/// An experiment's protocol: the typed form of its table `[protocols.<name>]`. Every key
/// defaults (`#[serde(default, deny_unknown_fields)]`), so a partial table keeps the rest.
pub trait Protocol: Serialize + DeserializeOwned + Default {
    /// Checks every value; errors name the field relative to the table.
    fn validate(&self) -> Result<(), ConfigError>;
}

/// Every experiment's protocol table by experiment name; an experiment without a table runs
/// its protocol's defaults.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct ProtocolTables {
    tables: BTreeMap<String, Table>,
}

impl ProtocolTables {
    /// No tables: every experiment's defaults.
    pub fn new() -> Self {
        Self::default()
    }

    /// The protocol of the experiment `name`: its table over `P`'s defaults, checked. Errors
    /// name the key from the top of the config file (`protocols.stability.pushes`).
    pub fn get<P: Protocol>(&self, name: &str) -> Result<P, ConfigError> {
        let within = |e: ConfigError| e.within(&format!("protocols.{name}"));
        let protocol: P = match self.tables.get(name) {
            None => P::default(),
            Some(table) => serde_path_to_error::deserialize(toml::Value::Table(table.clone()))
                .map_err(|e| within(ConfigError::from_path(e)))?,
        };
        protocol.validate().map_err(within)?;
        Ok(protocol)
    }

    /// Sets the table of the experiment `name` to `protocol` (every key written).
    pub fn set<P: Protocol>(&mut self, name: &str, protocol: &P) -> Result<(), ConfigError> {
        let table = Table::try_from(protocol)
            .map_err(|e| ConfigError::new(format!("protocols.{name}"), e.to_string()))?;
        self.tables.insert(name.to_string(), table);
        Ok(())
    }

    /// The table of the experiment `name`, if the config gives one.
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.tables.get(name)
    }

    /// The names of the experiments that have a table, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.tables.keys().map(String::as_str)
    }

    /// Sets (or with `None` removes) the raw table of the experiment `name`.
    pub fn set_table(&mut self, name: &str, table: Option<Table>) {
        match table {
            Some(t) => self.tables.insert(name.to_string(), t),
            None => self.tables.remove(name),
        };
    }

    /// The full table of `P` for the experiment `name` (its defaults where this holds none),
    /// checked: what an experiment with a typed protocol returns from `Experiment::protocol`.
    pub fn resolve<P: Protocol>(&self, name: &str) -> Result<Option<Table>, ConfigError> {
        let protocol: P = self.get(name)?;
        let mut full = ProtocolTables::new();
        full.set(name, &protocol)?;
        Ok(full.tables.remove(name))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    #[serde(default, deny_unknown_fields)]
    struct Toy {
        pushes: usize,
        gap_s: (f64, f64),
    }

    impl Default for Toy {
        fn default() -> Self {
            Toy {
                pushes: 4,
                gap_s: (1.0, 2.0),
            }
        }
    }

    impl Protocol for Toy {
        fn validate(&self) -> Result<(), ConfigError> {
            crate::config::at_least("pushes", self.pushes, 1)
        }
    }

    fn tables(text: &str) -> ProtocolTables {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn a_partial_table_keeps_the_defaults_and_round_trips() {
        let t = tables("[toy]\npushes = 7\n");
        let toy: Toy = t.get("toy").unwrap();
        assert_eq!(toy.pushes, 7);
        assert_eq!(toy.gap_s, (1.0, 2.0));
        assert_eq!(t.get::<Toy>("other").unwrap(), Toy::default());
        let mut u = ProtocolTables::new();
        u.set("toy", &toy).unwrap();
        assert_eq!(u.get::<Toy>("toy").unwrap(), toy);
        let full = t.resolve::<Toy>("toy").unwrap().unwrap();
        assert!(full.contains_key("gap_s"));
    }

    #[test]
    fn errors_name_the_key_from_the_top_of_the_file() {
        let e = tables("[toy]\npushes = 0\n").get::<Toy>("toy").unwrap_err();
        assert_eq!(e.field, "protocols.toy.pushes");
        let e = tables("[toy]\npush = 3\n").get::<Toy>("toy").unwrap_err();
        assert!(e.field.starts_with("protocols.toy"), "{e:?}");
        assert!(e.reason.contains("unknown field `push`"), "{e:?}");
        let e = tables("[toy]\ngap_s = \"x\"\n")
            .get::<Toy>("toy")
            .unwrap_err();
        assert_eq!(e.field, "protocols.toy.gap_s");
    }
}
