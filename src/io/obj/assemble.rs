//! From the statements of an OBJ file to a mesh: indices checked against the whole file,
//! faces fan-triangulated, texture coordinates and normals bound per vertex or per corner,
//! parts attached (the rules are in the module documentation).

use super::read::Statements;
use super::{FORMAT, NONE};
use crate::error::{Location, Result};
use crate::io::{perr, push_fan, Loaded};
use crate::mesh::{Attribute, Mesh, Parts, Semantic};

/// Which record a face corner names, for one kind of record.
struct Channel<'a, const N: usize> {
    /// `vt` or `vn`.
    keyword: &'static str,
    /// What the records are, for messages.
    what: &'static str,
    semantic: Semantic,
    records: &'a [[f32; N]],
    /// The record of every triangle corner (3 per triangle), [`NONE`] where the face gives
    /// none.
    of_corner: Vec<u32>,
}

/// Builds the mesh.
pub(super) fn assemble(s: Statements) -> Result<Loaded> {
    let Statements {
        positions,
        colors,
        texcoords,
        normals,
        corners,
        faces,
        parts,
        libraries,
        mut warnings,
    } = s;
    let nv = positions.len();
    let mut triangles = Vec::new();
    let mut of_triangle = Vec::new();
    let mut texture = Channel {
        keyword: "vt",
        what: "texture coordinate",
        semantic: Semantic::TexCoord(0),
        records: &texcoords,
        of_corner: Vec::new(),
    };
    let mut normal = Channel {
        keyword: "vn",
        what: "normal",
        semantic: Semantic::Normal,
        records: &normals,
        of_corner: Vec::new(),
    };
    let mut poly: Vec<u32> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let end = faces.get(f + 1).map_or(corners.len(), |next| next.start);
        let face_corners = &corners[face.start..end];
        let err = |m: String| perr(FORMAT, Location::Line(face.line), m);
        poly.clear();
        for &[v, t, n] in face_corners {
            if v as usize >= nv {
                return Err(err(format!(
                    "vertex index {} out of range: the file has {nv} vertices",
                    u64::from(v) + 1
                )));
            }
            texture.check(t).map_err(err)?;
            normal.check(n).map_err(err)?;
            poly.push(v);
        }
        let before = triangles.len();
        push_fan(&mut triangles, &poly).map_err(err)?;
        of_triangle.resize(triangles.len(), face.part);
        for i in 0..triangles.len() - before {
            for c in [face_corners[0], face_corners[i + 1], face_corners[i + 2]] {
                texture.push(c[1]);
                normal.push(c[2]);
            }
        }
    }

    let mut mesh = Mesh::new(positions, triangles);
    let no_faces = faces.is_empty();
    for attribute in [
        texture.bind(&mesh, no_faces, &mut warnings),
        normal.bind(&mesh, no_faces, &mut warnings),
    ]
    .into_iter()
    .flatten()
    {
        mesh.attributes.push(attribute);
    }
    if colors.count > 0 && colors.count == nv as u64 {
        mesh.attributes
            .push(Attribute::rgba8(&colors.finish(&mut warnings)?));
    } else if colors.count > 0 {
        warnings.push(format!(
            "only {} of {nv} `v` records carry a color; colors were ignored",
            colors.count
        ));
    }
    let labelled = parts.iter().any(|p| *p != Default::default());
    if labelled || !libraries.is_empty() {
        mesh.parts = Some(Parts {
            parts,
            of_triangle,
            material_libraries: libraries,
        });
    }
    Ok(Loaded { mesh, warnings })
}

impl<const N: usize> Channel<'_, N> {
    /// Adds the record of the next triangle corner; nothing when the file has no records
    /// (then no corner names one: [`Channel::check`] saw to it).
    fn push(&mut self, r: u32) {
        if !self.records.is_empty() {
            self.of_corner.push(r);
        }
    }

    /// Checks a corner's record number against the whole file.
    fn check(&self, r: u32) -> Result<(), String> {
        if r != NONE && r as usize >= self.records.len() {
            return Err(format!(
                "{} index {} out of range: the file has {} `{}` records",
                self.what,
                u64::from(r) + 1,
                self.records.len(),
                self.keyword
            ));
        }
        Ok(())
    }

    /// The attribute: per vertex when every corner names its vertex's record and there are
    /// as many records as vertices, per corner otherwise; `None` when no corner names a
    /// record (and the records, if any, cannot be per-vertex values of a file without faces).
    fn bind(self, mesh: &Mesh, no_faces: bool, warnings: &mut Vec<String>) -> Option<Attribute> {
        let nv = mesh.positions.len();
        let vertices = mesh.triangles.iter().flatten();
        if self.of_corner.iter().all(|&r| r == NONE) {
            if self.records.is_empty() {
                return None;
            }
            if no_faces && self.records.len() == nv {
                return Some(Attribute::per_vertex(self.semantic, self.records));
            }
            warnings.push(format!(
                "{} `{}` records were ignored: no face corner refers to one{}",
                self.records.len(),
                self.keyword,
                if no_faces {
                    format!(", and there are {nv} vertices")
                } else {
                    String::new()
                }
            ));
            return None;
        }
        if self.records.len() == nv && self.of_corner.iter().zip(vertices).all(|(r, v)| r == v) {
            return Some(Attribute::per_vertex(self.semantic, self.records));
        }
        let missing = self.of_corner.iter().filter(|&&r| r == NONE).count();
        let mut values = self.records.to_vec();
        let mut index = self.of_corner;
        if missing > 0 {
            let added = values.len() as u32;
            values.push([0.0; N]);
            index
                .iter_mut()
                .filter(|r| **r == NONE)
                .for_each(|r| *r = added);
            warnings.push(format!(
                "{missing} of {} triangle corners have no {} while others have one; they were \
                 given a value of zeros, added after the file's {added} `{}` records",
                index.len(),
                self.what,
                self.keyword,
            ));
        }
        Some(Attribute::per_corner(self.semantic, &values, index))
    }
}
