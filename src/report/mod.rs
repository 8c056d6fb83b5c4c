//! Output: CSV tables, JSON files and SVG figures (plotters' SVG backend, no system fonts). A
//! leaf: nothing here knows about experiments (their `summary.json` is
//! [`crate::experiments::summary`]) or the simulator.

mod atomic;
pub mod band;
mod csv_file;
pub(crate) mod csv_read;
mod error;
pub mod fall_rate;
pub mod figures;
pub mod forest;
pub mod html;

pub use atomic::write_file;
pub use csv_file::{Fixed, Shortest, write_rows};
pub use error::ReportError;
