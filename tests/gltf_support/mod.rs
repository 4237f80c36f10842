//! glTF files made by hand for the tests, independently of the crate's writer: a buffer,
//! views and accessors added one by one, then the document as JSON with its buffer embedded
//! (base64 `data:` URI), as a GLB, or as a `.gltf` beside a `.bin`.
#![allow(dead_code)]

use serde_json::{json, Value};

pub const BYTE: u32 = 5120;
pub const UNSIGNED_BYTE: u32 = 5121;
pub const SHORT: u32 = 5122;
pub const UNSIGNED_SHORT: u32 = 5123;
pub const UNSIGNED_INT: u32 = 5125;
pub const FLOAT: u32 = 5126;

/// A buffer under construction, with its views and accessors.
#[derive(Default)]
pub struct Builder {
    pub bin: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

/// Little-endian bytes of `f32`s.
pub fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|x| x.to_le_bytes()).collect()
}

impl Builder {
    /// A view of `bytes`, starting at a multiple of 4.
    pub fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(s) = stride {
            v["byteStride"] = json!(s);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    /// An accessor given as JSON (its `bufferView` included when it has one).
    pub fn accessor(&mut self, a: Value) -> usize {
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// A tightly packed float accessor of `components` per element.
    pub fn floats(&mut self, values: &[f32], components: usize) -> usize {
        let view = self.view(&f32_bytes(values), None);
        self.accessor(json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": values.len() / components,
            "type": type_name(components),
        }))
    }

    /// Integers of `component` type (`UNSIGNED_BYTE` ...), each element padded to 4 bytes
    /// as glTF requires of vertex attributes.
    pub fn integers(
        &mut self,
        values: &[u32],
        component: u32,
        components: usize,
        normalized: bool,
    ) -> usize {
        let size = match component {
            BYTE | UNSIGNED_BYTE => 1,
            SHORT | UNSIGNED_SHORT => 2,
            _ => 4,
        };
        let element = size * components;
        let stride = element.div_ceil(4) * 4;
        let mut bytes = Vec::new();
        for chunk in values.chunks(components) {
            for &x in chunk {
                bytes.extend_from_slice(&x.to_le_bytes()[..size]);
            }
            bytes.resize(bytes.len() + stride - element, 0);
        }
        let view = self.view(&bytes, (stride != element).then_some(stride));
        let mut a = json!({
            "bufferView": view,
            "componentType": component,
            "count": values.len() / components,
            "type": type_name(components),
        });
        if normalized {
            a["normalized"] = json!(true);
        }
        self.accessor(a)
    }

    /// Indices of the given width (`UNSIGNED_BYTE`, `UNSIGNED_SHORT` or `UNSIGNED_INT`).
    pub fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let size = match component {
            UNSIGNED_BYTE => 1,
            UNSIGNED_SHORT => 2,
            _ => 4,
        };
        let bytes: Vec<u8> = indices
            .iter()
            .flat_map(|x| x.to_le_bytes()[..size].to_vec())
            .collect();
        let view = self.view(&bytes, None);
        self.accessor(json!({
            "bufferView": view,
            "componentType": component,
            "count": indices.len(),
            "type": "SCALAR",
        }))
    }

    /// The document: `rest` (meshes, nodes, scenes, materials ...) with the asset, the
    /// accessors, the views and one buffer of `uri` (none for a GLB).
    pub fn document(&self, rest: Value, uri: Option<String>) -> Value {
        let mut doc = rest;
        doc["asset"] = json!({ "version": "2.0" });
        if !self.accessors.is_empty() {
            doc["accessors"] = json!(self.accessors);
        }
        if !self.views.is_empty() {
            doc["bufferViews"] = json!(self.views);
        }
        if !self.bin.is_empty() {
            let mut buffer = json!({ "byteLength": self.bin.len() });
            if let Some(uri) = uri {
                buffer["uri"] = json!(uri);
            }
            doc["buffers"] = json!([buffer]);
        }
        doc
    }

    /// A `.gltf` with the buffer in a base64 `data:` URI.
    pub fn embedded(&self, rest: Value) -> Vec<u8> {
        let uri = format!("data:application/octet-stream;base64,{}", base64(&self.bin));
        serde_json::to_vec_pretty(&self.document(rest, Some(uri))).unwrap()
    }

    /// A `.glb`.
    pub fn glb(&self, rest: Value) -> Vec<u8> {
        glb(
            &serde_json::to_vec(&self.document(rest, None)).unwrap(),
            &self.bin,
        )
    }
}

/// A GLB of a JSON text and a BIN chunk (left out when empty).
pub fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut json = json.to_vec();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

pub fn type_name(components: usize) -> &'static str {
    ["", "SCALAR", "VEC2", "VEC3", "VEC4"][components]
}

/// Padded base64.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A cube of side 2 as glTF stores it: 24 vertices (4 per face, so that each face has its
/// own normal and texture coordinates), 36 indices, faces counter-clockwise from outside.
pub struct SplitBox {
    pub positions: Vec<f32>,
    pub normals: Vec<f32>,
    pub texcoords: Vec<f32>,
    pub indices: Vec<u32>,
}

pub fn split_box() -> SplitBox {
    let mut b = SplitBox {
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: Vec::new(),
    };
    // (normal, u, v) with u × v = normal.
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    for (f, (n, u, v)) in faces.iter().enumerate() {
        for (k, (su, sv)) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .enumerate()
        {
            for i in 0..3 {
                b.positions.push(n[i] + su * u[i] + sv * v[i]);
            }
            b.normals.extend_from_slice(n);
            // Each face gets its own region of the texture, so that every seam differs.
            b.texcoords.push((f as f32 + [0.0, 1.0, 1.0, 0.0][k]) / 6.0);
            b.texcoords.push([0.0, 0.0, 1.0, 1.0][k]);
        }
        let o = 4 * f as u32;
        b.indices
            .extend_from_slice(&[o, o + 1, o + 2, o, o + 2, o + 3]);
    }
    b
}

/// The box as a one-primitive, one-node document in `builder`; returns the JSON to pass to
/// [`Builder::embedded`] or [`Builder::glb`].
pub fn box_document(builder: &mut Builder, index_type: u32) -> Value {
    let b = split_box();
    let position = builder.floats(&b.positions, 3);
    let normal = builder.floats(&b.normals, 3);
    let texcoord = builder.floats(&b.texcoords, 2);
    let indices = builder.indices(&b.indices, index_type);
    json!({
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "name": "box" }],
        "meshes": [{ "primitives": [{
            "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord },
            "indices": indices,
            "material": 0,
        }]}],
        "materials": [{ "name": "crate" }],
    })
}
