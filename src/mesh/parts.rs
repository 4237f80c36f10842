//! Per-triangle labels: which object, group and material each triangle belongs to (OBJ's
//! `o`, `g` and `usemtl`; glTF's mesh, primitive and material).

use serde::{Deserialize, Serialize};

/// The labels one part of a mesh carries. Two parts differ in at least one label.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Part {
    /// Object name (OBJ `o`, glTF mesh or node name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object: Option<String>,
    /// Group name (OBJ `g`, with several names joined by one space).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// Material name (OBJ `usemtl`, glTF material name or `material<i>`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

/// The parts of a mesh and the part of every triangle.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Parts {
    /// The parts, each once.
    pub parts: Vec<Part>,
    /// Part of triangle `t`: `parts[of_triangle[t]]`. One entry per triangle.
    #[serde(skip)]
    pub of_triangle: Vec<u32>,
    /// Material libraries the source referred to (OBJ `mtllib`), kept but not read.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub material_libraries: Vec<String>,
}

impl Parts {
    /// The part of triangle `t`.
    pub fn of(&self, t: usize) -> &Part {
        &self.parts[self.of_triangle[t] as usize]
    }

    /// Index of `part`, added if new (a linear search: parts are few).
    pub fn intern(&mut self, part: Part) -> u32 {
        match self.parts.iter().position(|p| *p == part) {
            Some(i) => i as u32,
            None => {
                self.parts.push(part);
                (self.parts.len() - 1) as u32
            }
        }
    }
}
