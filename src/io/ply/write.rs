//! The PLY writer: binary little-endian, with the header and record layout described in the
//! module documentation of [`super`].

use std::io::{BufWriter, Write};

use crate::io::check_writable;
use crate::mesh::{Mesh, Semantic};

/// Writes a binary little-endian PLY file (see the module documentation for the layout).
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    let mesh = &mesh.split_seams();
    let normals = mesh.vertex_values::<3>(&Semantic::Normal);
    let texcoords = mesh.vertex_values::<2>(&Semantic::TexCoord(0));
    let colors = mesh.vertex_colors_rgba8();
    writeln!(w, "ply")?;
    writeln!(w, "format binary_little_endian 1.0")?;
    writeln!(w, "comment written by lrmesh")?;
    writeln!(w, "element vertex {}", mesh.positions.len())?;
    for p in ["x", "y", "z"] {
        writeln!(w, "property float {p}")?;
    }
    if normals.is_some() {
        for p in ["nx", "ny", "nz"] {
            writeln!(w, "property float {p}")?;
        }
    }
    if texcoords.is_some() {
        for p in ["s", "t"] {
            writeln!(w, "property float {p}")?;
        }
    }
    if colors.is_some() {
        for p in ["red", "green", "blue", "alpha"] {
            writeln!(w, "property uchar {p}")?;
        }
    }
    writeln!(w, "element face {}", mesh.triangles.len())?;
    writeln!(w, "property list uchar uint vertex_indices")?;
    writeln!(w, "end_header")?;
    for (i, p) in mesh.positions.iter().enumerate() {
        for x in p {
            w.write_all(&x.to_le_bytes())?;
        }
        if let Some(n) = &normals {
            for x in n[i] {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        if let Some(t) = &texcoords {
            for x in t[i] {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        if let Some(c) = &colors {
            w.write_all(&c[i])?;
        }
    }
    for t in &mesh.triangles {
        w.write_all(&[3])?;
        for v in t {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    w.flush()
}
