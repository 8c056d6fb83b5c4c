//! A robot file named in a run's settings: its path and the SHA-256 of its content, so that a
//! changed file is never answered with results of the old one.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::NUM_JOINTS;
use super::description::{Description, RobotError};
use super::urdf::{Feet, ServoReference};

/// A URDF file and the SHA-256 of its content (lower-case hex), with the links that end its
/// legs where the loader is told them.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotFile {
    /// Where the URDF lies.
    pub path: PathBuf,
    /// SHA-256 of its bytes.
    pub sha256: String,
    /// The foot links, where named (otherwise the lowest leaf on each side).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub feet: Option<Feet>,
}

/// SHA-256 of `bytes` as lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn read(path: &Path) -> Result<Vec<u8>, RobotError> {
    std::fs::read(path).map_err(|e| RobotError::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}

/// `path` relative to the current directory where it lies inside it, otherwise as given.
fn relative_to_current_dir(path: &Path) -> PathBuf {
    std::env::current_dir()
        .ok()
        .and_then(|dir| path.strip_prefix(dir).ok())
        .filter(|rel| !rel.as_os_str().is_empty())
        .map_or_else(|| path.to_path_buf(), Path::to_path_buf)
}

impl RobotFile {
    /// Names `path` with the hash of what it holds now, after checking that it loads (its
    /// legs ending at `feet` where given) and stands in `stance`. A path inside the current
    /// directory is kept relative to it, so that a run configured from a checkout's root names
    /// the same file in every clone.
    pub fn open(
        path: &Path,
        feet: Option<&Feet>,
        reference: &ServoReference,
        stance: &[f64; NUM_JOINTS],
    ) -> Result<(Self, Description), RobotError> {
        let bytes = read(path)?;
        let file = RobotFile {
            path: relative_to_current_dir(path),
            sha256: sha256_hex(&bytes),
            feet: feet.cloned(),
        };
        let d = file.parse(&bytes, reference)?;
        d.validate_standing(stance)?;
        Ok((file, d))
    }

    /// Loads the description, refusing a file whose content changed since it was named.
    pub fn load(&self, reference: &ServoReference) -> Result<Description, RobotError> {
        let bytes = read(&self.path)?;
        let now = sha256_hex(&bytes);
        if now != self.sha256 {
            return Err(RobotError::invalid(
                format!("robot file {}", self.path.display()),
                format!(
                    "changed since the run was configured (SHA-256 {} then, {now} now)",
                    self.sha256
                ),
            ));
        }
        self.parse(&bytes, reference)
    }

    fn parse(&self, bytes: &[u8], reference: &ServoReference) -> Result<Description, RobotError> {
        let text = std::str::from_utf8(bytes)
            .map_err(|e| RobotError::Xml(format!("{}: not UTF-8 ({e})", self.path.display())))?;
        let dir = self.path.parent().unwrap_or(Path::new("."));
        let d = Description::from_urdf_feet(text, dir, reference, self.feet.as_ref())?;
        d.validate()?;
        Ok(d)
    }
}
