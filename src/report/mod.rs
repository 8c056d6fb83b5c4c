//! Output: CSV tables, JSON files and SVG figures (plotters' SVG backend, no system
//! fonts), plus the run picture of a simulated walk. A leaf: nothing here knows about
//! experiments (their `summary.json` is [`crate::experiments::summary`]).

mod atomic;
mod csv_file;
mod error;
pub mod fall_rate;
pub mod figures;
pub mod run_picture;

pub use atomic::write_atomic;
pub use csv_file::write_csv;
pub use error::ReportError;
