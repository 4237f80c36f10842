//! The `META` section's record (FORMAT.md §3.1): a UTF-8 JSON object.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// The `META` section: who wrote the file and from what, plus free key/values.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Metadata {
    /// The program that wrote the file.
    pub generator: String,
    /// The file the mesh came from, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// Free key/values.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub extra: BTreeMap<String, String>,
}
