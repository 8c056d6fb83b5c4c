//! Saving and loading models as JSON, with an invariant check on load.

use super::ApproxError;
use serde::{Serialize, de::DeserializeOwned};
use std::path::Path;

/// JSON persistence for a model whose invariants can be checked after loading.
///
/// Floats round-trip exactly (serde_json's `float_roundtrip`), so a loaded model predicts
/// bit-identically to the saved one. [`Persist::save`] writes to a uniquely named temporary file
/// and renames it, so a failed save never damages a file that was already there.
pub trait Persist: Serialize + DeserializeOwned {
    /// Checks the invariants a deserialized model must satisfy (dimensions agree, numbers are
    /// finite, parameters in range). Called by every load.
    fn check_invariants(&self) -> Result<(), ApproxError>;

    /// Serializes the model to a JSON string.
    fn to_json(&self) -> Result<String, ApproxError> {
        serde_json::to_string(self).map_err(|e| ApproxError::Corrupt(e.to_string()))
    }

    /// Parses and checks a model from a JSON string.
    fn from_json(json: &str) -> Result<Self, ApproxError> {
        let model: Self =
            serde_json::from_str(json).map_err(|e| ApproxError::Corrupt(e.to_string()))?;
        model.check_invariants()?;
        Ok(model)
    }

    /// Writes the model to `path` atomically ([`crate::atomic_file::write_atomic`]).
    fn save(&self, path: impl AsRef<Path>) -> Result<(), ApproxError> {
        let json = self.to_json()?;
        crate::atomic_file::write_atomic(path.as_ref(), json.as_bytes())?;
        Ok(())
    }

    /// Reads and checks a model from `path`.
    fn load(path: impl AsRef<Path>) -> Result<Self, ApproxError> {
        Self::from_json(&std::fs::read_to_string(path)?)
    }
}
