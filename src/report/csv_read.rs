//! Reading back the CSV tables this crate writes (for figures across runs).

use super::ReportError;
use serde::de::DeserializeOwned;
use std::path::Path;

/// The rows of the CSV file at `path` (with a header line; columns `R` does not name are
/// ignored).
pub fn read_rows<R: DeserializeOwned>(path: &Path) -> Result<Vec<R>, ReportError> {
    let mut reader = csv::Reader::from_path(path)
        .map_err(|e| ReportError::invalid(format!("{}: {e}", path.display())))?;
    reader
        .deserialize()
        .collect::<Result<Vec<R>, _>>()
        .map_err(|e| ReportError::invalid(format!("{}: {e}", path.display())))
}

/// A number cell that may be empty or `NaN` (then NaN).
pub(crate) fn number(cell: &str) -> f64 {
    cell.trim().parse().unwrap_or(f64::NAN)
}
