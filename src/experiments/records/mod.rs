//! Records and reports of runs: `summary.json`, paired comparisons and claims, sweeps and
//! their resumption, the results page and config files.

pub mod claim;
pub mod config_file;
pub mod config_keys;
pub(crate) mod error;
pub mod index_page;
pub mod paired;
pub mod summary;
pub mod sweep;
