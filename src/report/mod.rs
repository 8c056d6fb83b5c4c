//! Output: CSV tables, `summary.json` files and SVG figures (plotters' SVG backend, no system
//! fonts), plus the run picture of a simulated walk.

mod atomic;
mod error;
pub mod fall_rate;
pub mod figures;
pub mod run_picture;
pub mod settling;
pub mod summary;

pub use atomic::write_atomic;
pub use error::ReportError;
