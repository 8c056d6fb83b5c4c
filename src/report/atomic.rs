//! Writing a file without ever leaving a half-written or clobbered file behind.

use super::ReportError;
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes `contents` to `path` atomically: to a uniquely named temporary file in the same
/// directory, flushed to disk, then renamed over `path`. If anything fails, `path` keeps its old
/// contents (or stays absent) and the temporary file is removed.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), ReportError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| ReportError::invalid(format!("{} is not a file path", path.display())))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(
        ".{}.{}.tmp",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let tmp = path.with_file_name(tmp_name);
    let result = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        file.write_all(contents)?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        ReportError::io(path, e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_contents_and_keeps_old_file_on_failure() {
        let dir = std::env::temp_dir().join(format!("steplearn-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.txt");
        write_atomic(&path, b"one").unwrap();
        write_atomic(&path, b"two").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"two");
        // a directory in the way: the rename fails, nothing is left behind
        let blocked = dir.join("sub");
        std::fs::create_dir_all(blocked.join("x")).unwrap();
        assert!(matches!(
            write_atomic(&blocked, b"three"),
            Err(ReportError::Io { .. })
        ));
        assert!(blocked.join("x").is_dir());
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 2, "no temporary file left");
        assert!(write_atomic(&dir.join("missing/a.txt"), b"x").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
