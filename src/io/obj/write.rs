//! The OBJ writer: records, part statements and faces written so that the reader gives back
//! the same mesh (rules in the module documentation).

use std::borrow::Cow;
use std::collections::HashMap;
use std::io::{BufWriter, Write};

use super::NONE;
use crate::io::{check_writable, u8_to_unit, Float};
use crate::mesh::{Attribute, Mesh, Part, Semantic};

/// The `vt` or `vn` records of one attribute and the record each corner names.
struct Records<'a> {
    attribute: &'a Attribute,
    /// `None`: one record per vertex, each corner naming its vertex's. `Some`: the records
    /// as indices into the attribute's values, and the record of every triangle corner.
    per_corner: Option<(Vec<usize>, Vec<u32>)>,
}

impl<'a> Records<'a> {
    /// The records of `mesh`'s attribute `semantic`; `None` without one, or for a per-corner
    /// attribute of a mesh without triangles (no corner to carry it).
    fn new(mesh: &'a Mesh, semantic: &Semantic) -> Option<Records<'a>> {
        let attribute = mesh.attribute(semantic)?;
        if !attribute.is_per_corner() {
            return Some(Records {
                attribute,
                per_corner: None,
            });
        }
        if mesh.triangles.is_empty() {
            return None;
        }
        // Distinct values bit for bit, in order of first use; `record_of_value` saves hashing
        // a value's bytes at each of its corners.
        let mut record_of_value = vec![NONE; attribute.value_count()];
        let mut record_of_bytes: HashMap<Vec<u8>, u32> = HashMap::new();
        let mut records = Vec::new();
        let mut of_corner = Vec::with_capacity(3 * mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let i = attribute.value_index(t, k, *tri);
                if record_of_value[i] == NONE {
                    let mut bytes = Vec::new();
                    attribute.value_bytes(i, &mut bytes);
                    record_of_value[i] = *record_of_bytes.entry(bytes).or_insert_with(|| {
                        records.push(i);
                        (records.len() - 1) as u32
                    });
                }
                of_corner.push(record_of_value[i]);
            }
        }
        let lines_up = records.len() == mesh.positions.len()
            && of_corner
                .iter()
                .zip(mesh.triangles.iter().flatten())
                .all(|(r, v)| r == v);
        if lines_up {
            // The reader would take these records per vertex; an unused one keeps them per
            // corner.
            records.push(records[0]);
        }
        Some(Records {
            attribute,
            per_corner: Some((records, of_corner)),
        })
    }

    /// Writes `keyword` and the components of every record.
    fn write<W: Write>(&self, w: &mut W, keyword: &str) -> std::io::Result<()> {
        let mut line = |i: usize| -> std::io::Result<()> {
            w.write_all(keyword.as_bytes())?;
            for x in self.attribute.value_f32(i) {
                write!(w, " {}", Float(x))?;
            }
            writeln!(w)
        };
        match &self.per_corner {
            None => (0..self.attribute.value_count()).try_for_each(line),
            Some((records, _)) => records.iter().try_for_each(|&i| line(i)),
        }
    }

    /// The 1-based record number at corner `k` of triangle `t`, whose vertex is `v`.
    fn number(&self, t: usize, k: usize, v: u32) -> u64 {
        match &self.per_corner {
            None => u64::from(v) + 1,
            Some((_, of_corner)) => u64::from(of_corner[3 * t + k]) + 1,
        }
    }
}

/// Writes an OBJ file; see the module documentation for what is written and how.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mesh = split_color_seams(mesh);
    let mesh = mesh.as_ref();
    let mut w = BufWriter::new(w);
    writeln!(w, "# written by lrmesh")?;
    if let Some(parts) = &mesh.parts {
        let mut written: Vec<String> = Vec::new();
        for library in &parts.material_libraries {
            let name = library
                .split_ascii_whitespace()
                .collect::<Vec<_>>()
                .join("_")
                .replace('#', "_");
            if !name.is_empty() && !written.contains(&name) {
                statement(&mut w, "mtllib", &name)?;
                written.push(name);
            }
        }
    }
    let colors = mesh.vertex_colors_rgba8();
    let alpha = colors
        .as_ref()
        .is_some_and(|cs| cs.iter().any(|c| c[3] != 255));
    for (i, p) in mesh.positions.iter().enumerate() {
        write!(w, "v {} {} {}", Float(p[0]), Float(p[1]), Float(p[2]))?;
        if let Some(cs) = &colors {
            let n = if alpha { 4 } else { 3 };
            for &c in &cs[i][..n] {
                write!(w, " {}", Float(u8_to_unit(c)))?;
            }
        }
        writeln!(w)?;
    }
    let texcoords = Records::new(mesh, &Semantic::TexCoord(0));
    let normals = Records::new(mesh, &Semantic::Normal);
    if let Some(r) = &texcoords {
        r.write(&mut w, "vt")?;
    }
    if let Some(r) = &normals {
        r.write(&mut w, "vn")?;
    }
    let unlabelled = Part::default();
    let mut labels = &unlabelled;
    let mut last_part = None;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if let Some(parts) = &mesh.parts {
            let i = parts.of_triangle[t];
            if last_part != Some(i) {
                let part = &parts.parts[i as usize];
                label(&mut w, "o", &labels.object, &part.object)?;
                label(&mut w, "g", &labels.group, &part.group)?;
                label(&mut w, "usemtl", &labels.material, &part.material)?;
                labels = part;
                last_part = Some(i);
            }
        }
        w.write_all(b"f")?;
        for (k, &v) in tri.iter().enumerate() {
            write!(w, " {}", u64::from(v) + 1)?;
            match (&texcoords, &normals) {
                (None, None) => {}
                (Some(a), None) => write!(w, "/{}", a.number(t, k, v))?,
                (None, Some(b)) => write!(w, "//{}", b.number(t, k, v))?,
                (Some(a), Some(b)) => write!(w, "/{}/{}", a.number(t, k, v), b.number(t, k, v))?,
            }
        }
        writeln!(w)?;
    }
    w.flush()
}

/// Writes `keyword name` when a label changes: the name with each run of white space as one
/// space and `#` as `_`, or the bare keyword when there is no name left.
fn label<W: Write>(
    w: &mut W,
    keyword: &str,
    before: &Option<String>,
    after: &Option<String>,
) -> std::io::Result<()> {
    if before == after {
        return Ok(());
    }
    let name = after.as_deref().map_or_else(String::new, |name| {
        name.split_ascii_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
            .replace('#', "_")
    });
    statement(w, keyword, &name)
}

/// Writes one statement line; a trailing ` #` keeps a name that ends in `\` from being read
/// as a line continuation.
fn statement<W: Write>(w: &mut W, keyword: &str, name: &str) -> std::io::Result<()> {
    w.write_all(keyword.as_bytes())?;
    if !name.is_empty() {
        write!(w, " {name}")?;
        if name.ends_with('\\') {
            w.write_all(b" #")?;
        }
    }
    writeln!(w)
}

/// The mesh with per-corner colors, which OBJ cannot hold, made per vertex by splitting the
/// vertices whose corners differ in color; texture coordinates and normals are carried over
/// per corner. Any other mesh as it is.
fn split_color_seams(mesh: &Mesh) -> Cow<'_, Mesh> {
    let Some(color) = mesh
        .attribute(&Semantic::Color(0))
        .filter(|a| a.is_per_corner())
    else {
        return Cow::Borrowed(mesh);
    };
    let mut split = Mesh {
        attributes: vec![color.clone()],
        parts: mesh.parts.clone(),
        ..Mesh::new(mesh.positions.clone(), mesh.triangles.clone())
    }
    .split_seams();
    for semantic in [Semantic::TexCoord(0), Semantic::Normal] {
        if let Some(a) = mesh.attribute(&semantic) {
            let corners = a
                .corners
                .clone()
                .unwrap_or_else(|| mesh.triangles.iter().flatten().copied().collect());
            split.attributes.push(Attribute {
                corners: Some(corners),
                ..a.clone()
            });
        }
    }
    Cow::Owned(split)
}
