//! Output: CSV tables, `summary.json` files and SVG figures (plotters' SVG backend, no system
//! fonts), plus the run picture of a simulated walk.
pub mod run_picture;
