//! Writing a report file: atomically ([`crate::atomic_file::write_atomic`]), with the report's
//! error type.

use super::ReportError;
use std::path::Path;

/// Writes `contents` to `path` atomically ([`crate::atomic_file::write_atomic`]); the error
/// names the path.
pub fn write_file(path: &Path, contents: &[u8]) -> Result<(), ReportError> {
    crate::atomic_file::write_atomic(path, contents).map_err(|e| ReportError::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing/a.txt");
        let err = write_file(&path, b"x").unwrap_err();
        assert!(matches!(err, ReportError::Io { .. }));
        assert!(err.to_string().contains("missing/a.txt"), "{err}");
    }
}
