//! The indexed triangle mesh that every importer produces and every representation starts from.

mod attribute;
mod locality;
mod orient;
mod parts;
pub(crate) mod seams;

pub use attribute::{Attribute, ComponentType, Semantic, Values};
pub(crate) use locality::is_in_order;
pub use locality::{Order, LOCALITY_TRIANGLES};
pub(crate) use orient::reverse_triangle;
pub use orient::{orient, reversed, Oriented};
pub use parts::{Part, Parts};

use crate::error::{Error, Result};

/// An indexed triangle set with attributes per vertex or per corner, and per-triangle parts.
///
/// Nothing about the connectivity is assumed: triangles may repeat vertices, duplicate one
/// another, meet along non-manifold edges or leave vertices unreferenced. Positions define
/// the connectivity; every other attribute may differ between the corners of a vertex (a
/// texture seam, a crease in the normals).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles as oriented vertex triples (counter-clockwise seen from outside, by convention).
    pub triangles: Vec<[u32; 3]>,
    /// Attributes, each semantic at most once.
    pub attributes: Vec<Attribute>,
    /// Objects, groups and materials of the triangles, when the source has them.
    pub parts: Option<Parts>,
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

    /// The attribute of `semantic`, if the mesh has it.
    pub fn attribute(&self, semantic: &Semantic) -> Option<&Attribute> {
        self.attributes.iter().find(|a| a.semantic == *semantic)
    }

    /// Adds `attribute`, replacing the one of the same semantic.
    pub fn set_attribute(&mut self, attribute: Attribute) {
        self.attributes.retain(|a| a.semantic != attribute.semantic);
        self.attributes.push(attribute);
    }

    /// The values of a per-vertex attribute with `N` components, as f32 (normalized integers
    /// mapped to fractions); `None` when absent, per corner or of another width.
    pub fn vertex_values<const N: usize>(&self, semantic: &Semantic) -> Option<Vec<[f32; N]>> {
        let a = self.attribute(semantic)?;
        if a.is_per_corner() || usize::from(a.components) != N {
            return None;
        }
        Some(
            (0..a.value_count())
                .map(|i| {
                    let v = a.value_f32(i);
                    std::array::from_fn(|k| v[k])
                })
                .collect(),
        )
    }

    /// Per-vertex colors of set 0 as RGBA bytes (fractions scaled to 0–255 and rounded, a
    /// missing alpha 255); `None` when absent or per corner.
    pub fn vertex_colors_rgba8(&self) -> Option<Vec<[u8; 4]>> {
        let a = self.attribute(&Semantic::Color(0))?;
        if a.is_per_corner() {
            return None;
        }
        let n = usize::from(a.components);
        Some(
            (0..a.value_count())
                .map(|i| {
                    if let (Values::U8(v), true) = (&a.values, a.normalized) {
                        return std::array::from_fn(|k| if k < n { v[n * i + k] } else { 255 });
                    }
                    let f = a.value_f32(i);
                    std::array::from_fn(|k| {
                        if k < n {
                            (f[k].clamp(0.0, 1.0) * 255.0).round() as u8
                        } else {
                            255
                        }
                    })
                })
                .collect(),
        )
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
    /// vertices and triangles, every vertex index in range, finite coordinates, and
    /// attributes and parts that fit the vertices and triangles.
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
        for a in &self.attributes {
            check_attribute(a, n, self.triangles.len())?;
        }
        for (i, a) in self.attributes.iter().enumerate() {
            if self.attributes[..i]
                .iter()
                .any(|b| b.semantic == a.semantic)
            {
                return Err(Error::InvalidMesh(format!("two {} attributes", a.semantic)));
            }
        }
        if let Some(parts) = &self.parts {
            if parts.of_triangle.len() != self.triangles.len() {
                return Err(Error::InvalidMesh(format!(
                    "{} part indices for {} triangles",
                    parts.of_triangle.len(),
                    self.triangles.len()
                )));
            }
            if let Some(t) = parts
                .of_triangle
                .iter()
                .position(|&p| p as usize >= parts.parts.len())
            {
                return Err(Error::InvalidMesh(format!(
                    "triangle {t} is in part {}, but there are {} parts",
                    parts.of_triangle[t],
                    parts.parts.len()
                )));
            }
        }
        Ok(())
    }
}

/// One attribute's invariants: component count, whole values, one value per vertex or an
/// index in range per corner, finite floats.
fn check_attribute(a: &Attribute, vertices: usize, triangles: usize) -> Result<()> {
    let fail = |what: String| {
        Err(Error::InvalidMesh(format!(
            "{} attribute: {what}",
            a.semantic
        )))
    };
    if !a.semantic.allowed_components().contains(&a.components) {
        return fail(format!("{} components per value", a.components));
    }
    if matches!(&a.semantic, Semantic::Custom(name) if name.is_empty()) {
        return fail("a custom attribute needs a name".into());
    }
    if a.normalized && !a.values.component_type().is_integer() {
        return fail("only integers can be normalized".into());
    }
    let n = usize::from(a.components);
    if a.values.len() % n != 0 {
        return fail(format!(
            "{} numbers are not whole values of {n}",
            a.values.len()
        ));
    }
    if let Some(i) = a.values.first_non_finite() {
        return fail(format!("value {} has a non-finite component", i / n));
    }
    let count = a.value_count();
    match &a.corners {
        None if count != vertices => fail(format!("{count} values for {vertices} vertices")),
        None => Ok(()),
        Some(index) if index.len() != 3 * triangles => fail(format!(
            "{} corner indices for {triangles} triangles",
            index.len()
        )),
        Some(index) => match index.iter().position(|&i| i as usize >= count) {
            Some(c) => fail(format!(
                "corner {} of triangle {} refers to value {}, but there are {count}",
                c % 3,
                c / 3,
                index[c]
            )),
            None => Ok(()),
        },
    }
}
