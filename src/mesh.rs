//! The indexed triangle mesh that every importer produces and every representation starts from.

use crate::error::{Error, Result};

/// An indexed triangle set with optional per-vertex attributes.
///
/// Nothing about the connectivity is assumed: triangles may repeat vertices, duplicate one
/// another, meet along non-manifold edges or leave vertices unreferenced. Attributes, when
/// present, hold exactly one entry per vertex.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles as oriented vertex triples (counter-clockwise seen from outside, by convention).
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex normals.
    pub normals: Option<Vec<[f32; 3]>>,
    /// Per-vertex texture coordinates.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// Per-vertex colors, RGBA with 8 bits a channel.
    pub colors: Option<Vec<[u8; 4]>>,
}

impl Mesh {
    /// A mesh of positions and triangles without attributes.
    pub fn new(positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
        Mesh {
            positions,
            triangles,
            ..Mesh::default()
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Checks the invariants that the rest of the crate relies on: fewer than `u32::MAX`
    /// vertices and triangles, every vertex index in range, finite coordinates and one
    /// attribute entry per vertex.
    ///
    /// # Errors
    /// [`Error::InvalidMesh`] naming the first offending vertex or triangle.
    pub fn validate(&self) -> Result<()> {
        let n = self.positions.len();
        if n >= u32::MAX as usize || self.triangles.len() >= (u32::MAX / 3) as usize {
            return Err(Error::InvalidMesh(format!(
                "{} vertices and {} triangles exceed the 32-bit id space",
                n,
                self.triangles.len()
            )));
        }
        if let Some(i) = self
            .positions
            .iter()
            .position(|p| p.iter().any(|x| !x.is_finite()))
        {
            return Err(Error::InvalidMesh(format!(
                "vertex {i} has a non-finite coordinate {:?}",
                self.positions[i]
            )));
        }
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
                return Err(Error::InvalidMesh(format!(
                    "triangle {t} refers to vertex {v}, but there are {n} vertices"
                )));
            }
        }
        let check_len = |name: &str, len: Option<usize>| match len {
            Some(len) if len != n => {
                Err(Error::InvalidMesh(format!("{len} {name} for {n} vertices")))
            }
            _ => Ok(()),
        };
        check_len("normals", self.normals.as_ref().map(Vec::len))?;
        check_len("texture coordinates", self.texcoords.as_ref().map(Vec::len))?;
        check_len("colors", self.colors.as_ref().map(Vec::len))?;
        Ok(())
    }
}
