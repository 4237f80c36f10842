//! Writing a [`Mesh`] as glTF 2.0: one buffer holding every attribute once (all primitives
//! share the vertex accessors) and one index accessor per primitive.

use std::io::Write;

use serde_json::{json, Map, Value};

use super::buffers::{CHUNK_BIN, CHUNK_JSON, GLB_MAGIC};
use crate::io::check_writable;
use crate::mesh::{Attribute, ComponentType, Mesh, Part, Semantic, Values};

/// `bufferView.target` of vertex attributes.
const ARRAY_BUFFER: u32 = 34962;
/// `bufferView.target` of indices.
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Writes a self-contained `.gltf`: the JSON document, its one buffer in a base64 `data:` URI.
///
/// What is written: attributes given per corner are first made per vertex by splitting
/// vertices at seams ([`Mesh::split_seams`]), since glTF knows only per-vertex attributes. Every
/// vertex is written, referenced or not, once: `POSITION` (f32, with the `min` and `max` glTF
/// requires), `NORMAL` (f32, converted if stored otherwise), `TEXCOORD_n` and `COLOR_n` as stored
/// when glTF allows the type (f32, normalized `u8`/`u16`; texture coordinates of other integer
/// types under `KHR_mesh_quantization`), else converted to f32, and each custom attribute
/// `NAME` as `_NAME`, as stored (a `u32` custom attribute is written as `UNSIGNED_INT`, which
/// validators flag: glTF reserves it for indices). Elements are padded to 4 bytes as glTF
/// requires. Triangles go into one primitive per [`Part`](crate::mesh::Part), grouped into one
/// glTF mesh and node per object name, with the part's material as a material holding only its
/// name and its group in the primitive's `extras.group` (which the reader reads back); without
/// parts, one primitive. Indices are `u16` when they fit, else `u32`. A mesh with vertices but
/// no triangle is written as a `POINTS` primitive. OBJ material libraries are not written.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write_gltf<W: Write>(mut w: W, mesh: &Mesh) -> std::io::Result<()> {
    let (mut doc, bin) = document(mesh)?;
    if !bin.is_empty() {
        doc["buffers"] = json!([{
            "byteLength": bin.len(),
            "uri": format!("data:application/octet-stream;base64,{}", super::base64::encode(&bin)),
        }]);
    }
    let text = serde_json::to_vec_pretty(&doc).map_err(std::io::Error::other)?;
    w.write_all(&text)?;
    w.write_all(b"\n")?;
    w.flush()
}

/// Writes a `.glb`: the same document as [`write_gltf`] in a JSON chunk, its buffer in the
/// BIN chunk.
///
/// # Errors
/// As [`write_gltf`]; also a mesh too large for a GLB's 32-bit lengths.
pub fn write_glb<W: Write>(mut w: W, mesh: &Mesh) -> std::io::Result<()> {
    let (mut doc, bin) = document(mesh)?;
    if !bin.is_empty() {
        doc["buffers"] = json!([{ "byteLength": bin.len() }]);
    }
    let mut text = serde_json::to_vec(&doc).map_err(std::io::Error::other)?;
    text.resize(text.len().next_multiple_of(4), b' ');
    let bin_padded = bin.len().next_multiple_of(4);
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin_padded };
    let total = u32::try_from(12 + 8 + text.len() + bin_chunk)
        .map_err(|_| std::io::Error::other("the mesh is too large for a GLB (4 GiB)"))?;
    w.write_all(&GLB_MAGIC.to_le_bytes())?;
    w.write_all(&2u32.to_le_bytes())?;
    w.write_all(&total.to_le_bytes())?;
    // Both lengths are below `total`.
    w.write_all(&(text.len() as u32).to_le_bytes())?;
    w.write_all(&CHUNK_JSON.to_le_bytes())?;
    w.write_all(&text)?;
    if !bin.is_empty() {
        w.write_all(&(bin_padded as u32).to_le_bytes())?;
        w.write_all(&CHUNK_BIN.to_le_bytes())?;
        w.write_all(&bin)?;
        w.write_all(&vec![0u8; bin_padded - bin.len()])?;
    }
    w.flush()
}

/// The binary buffer and its views and accessors, as they are added.
#[derive(Default)]
struct Binary {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Binary {
    /// Adds a view of `data` (starting 4-aligned) and an accessor over all of it; returns the
    /// accessor's index.
    fn add(&mut self, data: &[u8], stride: Option<usize>, target: u32, accessor: Value) -> usize {
        self.bytes.resize(self.bytes.len().next_multiple_of(4), 0);
        let mut view = json!({
            "buffer": 0,
            "byteOffset": self.bytes.len(),
            "byteLength": data.len(),
            "target": target,
        });
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        self.bytes.extend_from_slice(data);
        self.views.push(view);
        let mut accessor = accessor;
        accessor["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }
}

fn component_code(t: ComponentType) -> u32 {
    match t {
        ComponentType::I8 => 5120,
        ComponentType::U8 => 5121,
        ComponentType::I16 => 5122,
        ComponentType::U16 => 5123,
        ComponentType::U32 => 5125,
        ComponentType::F32 => 5126,
    }
}

fn type_name(components: u8) -> &'static str {
    match components {
        1 => "SCALAR",
        2 => "VEC2",
        3 => "VEC3",
        _ => "VEC4",
    }
}

/// An attribute as glTF may store it: its name, and whether it needs `KHR_mesh_quantization`;
/// converted to f32 where glTF allows neither.
fn storable(a: &Attribute) -> (String, Attribute, bool) {
    use ComponentType::*;
    let t = a.values.component_type();
    let unit = t == F32 || (matches!(t, U8 | U16) && a.normalized);
    let (name, keep, quantized) = match &a.semantic {
        Semantic::Normal => ("NORMAL".to_string(), t == F32, false),
        Semantic::TexCoord(n) => {
            let quantized = !unit && matches!(t, I8 | U8 | I16 | U16);
            (format!("TEXCOORD_{n}"), unit || quantized, quantized)
        }
        Semantic::Color(n) => (format!("COLOR_{n}"), unit, false),
        // glTF cannot normalize UNSIGNED_INT.
        Semantic::Custom(name) => (format!("_{name}"), !(t == U32 && a.normalized), false),
    };
    if keep {
        return (name, a.clone(), quantized);
    }
    let values: Vec<f32> = (0..a.value_count()).flat_map(|i| a.value_f32(i)).collect();
    let converted = Attribute {
        normalized: false,
        values: Values::F32(values),
        ..a.clone()
    };
    (name, converted, false)
}

/// The values of `a`, each padded to a multiple of 4 bytes; and the stride when padded.
fn padded(a: &Attribute) -> (Vec<u8>, Option<usize>) {
    let size = usize::from(a.components) * a.values.component_type().size();
    let stride = size.next_multiple_of(4);
    let mut out = Vec::with_capacity(stride * a.value_count());
    for i in 0..a.value_count() {
        a.value_bytes(i, &mut out);
        out.resize(out.len() + stride - size, 0);
    }
    (out, (stride != size).then_some(stride))
}

/// The JSON document (without `buffers`) and the buffer's bytes.
fn document(mesh: &Mesh) -> std::io::Result<(Value, Vec<u8>)> {
    check_writable(mesh)?;
    let split;
    let mesh = if mesh.has_per_corner_attributes() {
        split = mesh.split_seams();
        &split
    } else {
        mesh
    };
    let mut bin = Binary::default();
    let mut attributes = Map::new();
    let mut quantized = false;
    if !mesh.positions.is_empty() {
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        let mut bytes = Vec::with_capacity(12 * mesh.positions.len());
        for p in &mesh.positions {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
                bytes.extend_from_slice(&p[k].to_le_bytes());
            }
        }
        let accessor = json!({
            "componentType": component_code(ComponentType::F32),
            "count": mesh.positions.len(),
            "type": "VEC3",
            "min": min,
            "max": max,
        });
        let index = bin.add(&bytes, None, ARRAY_BUFFER, accessor);
        attributes.insert("POSITION".into(), json!(index));
        for a in &mesh.attributes {
            let (name, a, needs_quantization) = storable(a);
            quantized |= needs_quantization;
            let (bytes, stride) = padded(&a);
            let mut accessor = json!({
                "componentType": component_code(a.values.component_type()),
                "count": a.value_count(),
                "type": type_name(a.components),
            });
            if a.normalized {
                accessor["normalized"] = json!(true);
            }
            let index = bin.add(&bytes, stride, ARRAY_BUFFER, accessor);
            attributes.insert(name, json!(index));
        }
    }
    let mut materials: Vec<String> = Vec::new();
    let mut meshes = Vec::new();
    for (object, parts) in objects(mesh) {
        let mut primitives = Vec::new();
        for (part, triangles) in parts {
            let mut primitive = json!({ "attributes": attributes.clone() });
            let max = triangles.iter().flatten().copied().max().unwrap_or(0);
            let (code, bytes): (_, Vec<u8>) = if max < u32::from(u16::MAX) {
                let i = triangles
                    .iter()
                    .flatten()
                    .flat_map(|&v| (v as u16).to_le_bytes());
                (ComponentType::U16, i.collect())
            } else {
                (
                    ComponentType::U32,
                    triangles
                        .iter()
                        .flatten()
                        .flat_map(|v| v.to_le_bytes())
                        .collect(),
                )
            };
            let accessor = json!({
                "componentType": component_code(code),
                "count": 3 * triangles.len(),
                "type": "SCALAR",
            });
            primitive["indices"] = json!(bin.add(&bytes, None, ELEMENT_ARRAY_BUFFER, accessor));
            if let Some(name) = &part.material {
                let index = match materials.iter().position(|m| m == name) {
                    Some(i) => i,
                    None => {
                        materials.push(name.clone());
                        materials.len() - 1
                    }
                };
                primitive["material"] = json!(index);
            }
            if let Some(group) = &part.group {
                primitive["extras"] = json!({ "group": group });
            }
            primitives.push(primitive);
        }
        meshes.push(named(json!({ "primitives": primitives }), object));
    }
    if meshes.is_empty() && !mesh.positions.is_empty() {
        // 0 is POINTS.
        meshes.push(json!({ "primitives": [{ "attributes": attributes, "mode": 0 }] }));
    }
    let nodes: Vec<Value> = meshes
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mut node = json!({ "mesh": i });
            if let Some(name) = m.get("name") {
                node["name"] = name.clone();
            }
            node
        })
        .collect();
    let mut doc = json!({
        "asset": {
            "version": "2.0",
            "generator": concat!("lrmesh ", env!("CARGO_PKG_VERSION")),
        },
        "scene": 0,
        "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
    });
    let mut put = |key: &str, items: Vec<Value>| {
        if !items.is_empty() {
            doc[key] = Value::Array(items);
        }
    };
    put("nodes", nodes);
    put("meshes", meshes);
    put(
        "materials",
        materials
            .into_iter()
            .map(|m| json!({ "name": m }))
            .collect(),
    );
    put("accessors", bin.accessors);
    put("bufferViews", bin.views);
    if quantized {
        doc["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
        doc["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    }
    Ok((doc, bin.bytes))
}

/// `value` with `"name": name` when there is a name.
fn named(mut value: Value, name: Option<&str>) -> Value {
    if let Some(name) = name {
        value["name"] = json!(name);
    }
    value
}

/// The triangles of one part.
type PartTriangles = (Part, Vec<[u32; 3]>);

/// The triangles grouped by part, and the parts by object, both in order of first appearance
/// (parts with no triangle left out); without parts, one unnamed object with one part.
fn objects(mesh: &Mesh) -> Vec<(Option<&str>, Vec<PartTriangles>)> {
    if mesh.triangles.is_empty() {
        return Vec::new();
    }
    let Some(parts) = &mesh.parts else {
        return vec![(None, vec![(Part::default(), mesh.triangles.clone())])];
    };
    let mut by_part: Vec<Vec<[u32; 3]>> = vec![Vec::new(); parts.parts.len()];
    let mut order = Vec::new();
    for (t, &p) in parts.of_triangle.iter().enumerate() {
        let list = &mut by_part[p as usize];
        if list.is_empty() {
            order.push(p as usize);
        }
        list.push(mesh.triangles[t]);
    }
    let mut out: Vec<(Option<&str>, Vec<PartTriangles>)> = Vec::new();
    for p in order {
        let part = &parts.parts[p];
        let object = part.object.as_deref();
        let triangles = std::mem::take(&mut by_part[p]);
        match out.iter_mut().find(|(o, _)| *o == object) {
            Some((_, list)) => list.push((part.clone(), triangles)),
            None => out.push((object, vec![(part.clone(), triangles)])),
        }
    }
    out
}
