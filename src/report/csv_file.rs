//! CSV tables written atomically.

use super::{ReportError, write_atomic};
use std::path::Path;

/// Writes a CSV table (header + rows of already formatted cells) to `path` atomically.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<(), ReportError> {
    let write = || -> Result<Vec<u8>, csv::Error> {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(header)?;
        for row in rows {
            if row.len() != header.len() {
                return Err(csv::Error::from(std::io::Error::other(format!(
                    "row has {} cells, header {}",
                    row.len(),
                    header.len()
                ))));
            }
            w.write_record(row)?;
        }
        w.into_inner()
            .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
    };
    let bytes = write().map_err(|e| ReportError::invalid(format!("csv: {e}")))?;
    write_atomic(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_cells_and_keeps_the_old_file_on_a_bad_row() {
        let dir = tempfile::tempdir().unwrap();
        let csv_path = dir.path().join("t.csv");
        write_csv(&csv_path, &["a", "b"], &[vec!["1".into(), "x,y".into()]]).unwrap();
        assert_eq!(
            std::fs::read_to_string(&csv_path).unwrap(),
            "a,b\n1,\"x,y\"\n"
        );
        assert!(write_csv(&csv_path, &["a"], &[vec![]]).is_err());
        assert_eq!(
            std::fs::read_to_string(&csv_path).unwrap(),
            "a,b\n1,\"x,y\"\n"
        );
    }
}
