//! `LrmFile`: an opened container and its corner queries, for JavaScript (`web/API.md`).
//! Ids from the page are checked before use: a bad id is an `Error` in the page, never a
//! trap of the WebAssembly module.

use lrmesh::lr::{LrInspect, TriangleClass};
use lrmesh::read::{open, open_verified, Connectivity, Container, Limits};
use lrmesh::{Corner, CornerOps, Triangle, Vertex};
use wasm_bindgen::prelude::*;

/// An opened container (`web/API.md`, `LrmFile`).
#[wasm_bindgen]
pub struct LrmFile {
    // Declared before `_bytes`, so dropped first, while the bytes it reads still exist.
    container: Container<'static>,
    /// The container's bytes, on the heap: they stay in place when the box moves.
    _bytes: Box<[u8]>,
    /// The triangle ids, in the connectivity's order.
    ids: Vec<u32>,
    /// Whether each id below the bound names a triangle.
    is_triangle: Vec<bool>,
}

fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A corner id for JavaScript (a number, not a BigInt): `-1` for none.
fn or_minus_one(c: Option<Corner>) -> f64 {
    c.map_or(-1.0, |c| c.0 as f64)
}

impl LrmFile {
    pub(crate) fn new(bytes: Vec<u8>, verify: bool) -> Result<LrmFile, JsError> {
        let bytes = bytes.into_boxed_slice();
        // SAFETY: the slice is the heap allocation of `bytes`, which this struct owns, never
        // changes and drops after `container` (field order); no method hands out anything
        // that borrows it, so the 'static lifetime never outlives the allocation.
        let view: &'static [u8] = unsafe { &*(bytes.as_ref() as *const [u8]) };
        let limits = Limits::default();
        let container = if verify {
            open_verified(view, &limits)
        } else {
            open(view, &limits)
        }
        .map_err(js_error)?;
        let conn = container.connectivity();
        let ids: Vec<u32> = conn.triangles().map(|t| t.0).collect();
        let mut is_triangle = vec![false; conn.triangle_id_bound() as usize];
        for &t in &ids {
            is_triangle[t as usize] = true;
        }
        Ok(LrmFile {
            container,
            _bytes: bytes,
            ids,
            is_triangle,
        })
    }

    fn conn(&self) -> &Connectivity<'static> {
        self.container.connectivity()
    }

    fn corner(&self, c: u32) -> Result<Corner, JsError> {
        let c = Corner(c);
        if self.conn().is_corner(c) {
            Ok(c)
        } else {
            Err(JsError::new(&format!(
                "{c} is not a corner of this {} mesh",
                self.conn().name()
            )))
        }
    }

    fn triangle(&self, t: u32) -> Result<Triangle, JsError> {
        if self.is_triangle.get(t as usize) == Some(&true) {
            Ok(Triangle(t))
        } else {
            Err(JsError::new(&format!(
                "{t} is not a triangle id of this mesh"
            )))
        }
    }

    fn vertex_id(&self, v: u32) -> Result<Vertex, JsError> {
        if v < self.conn().vertex_id_bound() {
            Ok(Vertex(v))
        } else {
            Err(JsError::new(&format!(
                "{v} is not a vertex id ({} vertices)",
                self.conn().vertex_id_bound()
            )))
        }
    }

    /// Place along its ring of each triangle, for an LR layout (`lrmesh render`'s colours).
    fn ring_places<L: LrInspect>(&self, lr: &L) -> Vec<f32> {
        let places = lr.ring_places();
        self.ids
            .iter()
            .map(|&t| {
                lr.triangle_ring_place(&places, Triangle(t))
                    .unwrap_or(f32::NAN)
            })
            .collect()
    }

    fn class_codes<L: LrInspect>(&self, lr: &L) -> Vec<u8> {
        self.ids
            .iter()
            .map(|&t| match lr.triangle_class(Triangle(t)) {
                Some(TriangleClass::T1Left) => 0,
                Some(TriangleClass::T1Right) => 1,
                Some(TriangleClass::T2) => 2,
                Some(TriangleClass::T2Wart) => 3,
                Some(TriangleClass::T0) => 4,
                Some(TriangleClass::T0Wart) => 5,
                None => 255,
            })
            .collect()
    }
}

#[wasm_bindgen]
impl LrmFile {
    /// Container vertices: the ids of `positions()` and `vertex(c)`.
    #[wasm_bindgen(js_name = vertexCount)]
    pub fn vertex_count(&self) -> u32 {
        self.container.connectivity_vertex_count()
    }

    /// Triangles of the connectivity (kept-aside degenerate ones not included).
    #[wasm_bindgen(js_name = triangleCount)]
    pub fn triangle_count(&self) -> u32 {
        self.ids.len() as u32
    }

    /// `lr`, `lr-compact`, `edgebreaker` or `strips`.
    pub fn kind(&self) -> String {
        self.conn().name().to_string()
    }

    /// What `lrmesh info FILE --json` prints.
    #[wasm_bindgen(js_name = infoJson)]
    pub fn info_json(&self) -> Result<String, JsError> {
        serde_json::to_string(&self.container.summary()).map_err(js_error)
    }

    /// x, y, z of every container vertex.
    pub fn positions(&self) -> Vec<f32> {
        self.container.positions().into_iter().flatten().collect()
    }

    /// The triangle ids in the connectivity's order.
    #[wasm_bindgen(js_name = triangleIds)]
    pub fn triangle_ids(&self) -> Vec<u32> {
        self.ids.clone()
    }

    /// The vertices of each triangle of `triangleIds()`, three each.
    pub fn triangles(&self) -> Vec<u32> {
        let conn = self.conn();
        self.ids
            .iter()
            .flat_map(|&t| conn.triangle_vertices(Triangle(t)).map(|v| v.0))
            .collect()
    }

    /// The three corners of triangle `t`.
    #[wasm_bindgen(js_name = triangleCorners)]
    pub fn triangle_corners(&self, t: u32) -> Result<Vec<u32>, JsError> {
        let t = self.triangle(t)?;
        Ok(self.conn().triangle_corners(t).map(|c| c.0).to_vec())
    }

    /// The triangle of corner `c`.
    #[wasm_bindgen(js_name = triangleOf)]
    pub fn triangle_of(&self, c: u32) -> Result<u32, JsError> {
        Ok(self.conn().triangle(self.corner(c)?).0)
    }

    /// `c.v`.
    pub fn vertex(&self, c: u32) -> Result<u32, JsError> {
        Ok(self.conn().vertex(self.corner(c)?).0)
    }

    /// `c.o`, or -1 across a boundary.
    pub fn opposite(&self, c: u32) -> Result<f64, JsError> {
        Ok(or_minus_one(self.conn().opposite(self.corner(c)?)))
    }

    /// `c.n`.
    pub fn next(&self, c: u32) -> Result<u32, JsError> {
        Ok(self.conn().next(self.corner(c)?).0)
    }

    /// `c.p`.
    pub fn prev(&self, c: u32) -> Result<u32, JsError> {
        Ok(self.conn().prev(self.corner(c)?).0)
    }

    /// `c.s`, the next corner around `c.v`, or -1 at a boundary.
    pub fn swing(&self, c: u32) -> Result<f64, JsError> {
        Ok(or_minus_one(self.conn().swing(self.corner(c)?)))
    }

    /// `v.c`, or -1 for a vertex of no triangle.
    #[wasm_bindgen(js_name = vertexCorner)]
    pub fn vertex_corner(&self, v: u32) -> Result<f64, JsError> {
        Ok(or_minus_one(self.conn().vertex_corner(self.vertex_id(v)?)))
    }

    /// The corners around `v`, walked with `swing` on the file's bytes.
    pub fn star(&self, v: u32) -> Result<Vec<u32>, JsError> {
        let v = self.vertex_id(v)?;
        Ok(lrmesh::ops::star(self.conn(), v).map(|c| c.0).collect())
    }

    /// Class code of each triangle (`web/API.md`); 255 without classes.
    pub fn classes(&self) -> Vec<u8> {
        match self.conn() {
            Connectivity::Lr(t) => self.class_codes(t),
            Connectivity::LrCompact(t) => self.class_codes(t),
            Connectivity::Zipper(t) => self.class_codes(t),
            _ => vec![255; self.ids.len()],
        }
    }

    /// Place along its ring of each triangle, 0 to 1; NaN without rings.
    #[wasm_bindgen(js_name = ringPositions)]
    pub fn ring_positions(&self) -> Vec<f32> {
        match self.conn() {
            Connectivity::Lr(t) => self.ring_places(t),
            Connectivity::LrCompact(t) => self.ring_places(t),
            Connectivity::Zipper(t) => self.ring_places(t),
            _ => vec![f32::NAN; self.ids.len()],
        }
    }

    /// `[{ "name", "components", "perCorner" }]`, one per attribute.
    #[wasm_bindgen(js_name = attributesJson)]
    pub fn attributes_json(&self) -> String {
        let list: Vec<serde_json::Value> = self
            .container
            .attributes()
            .iter()
            .map(|a| {
                serde_json::json!({
                    "name": a.semantic.to_string(),
                    "components": a.components,
                    "perCorner": a.per_corner,
                })
            })
            .collect();
        serde_json::Value::Array(list).to_string()
    }

    /// Attribute `i`'s value at every corner of every triangle of `triangleIds()`.
    #[wasm_bindgen(js_name = cornerValues)]
    pub fn corner_values(&self, i: u32) -> Result<Vec<f32>, JsError> {
        let a = self
            .container
            .attributes()
            .get(i as usize)
            .ok_or_else(|| JsError::new(&format!("no attribute {i}")))?;
        let n = a.components as usize;
        let conn = self.conn();
        let mut out = Vec::with_capacity(3 * n * self.ids.len());
        for &t in &self.ids {
            for c in conn.triangle_corners(Triangle(t)) {
                let value = a.value_f32(self.container.value_index(a, c));
                out.extend_from_slice(&value[..n]);
            }
        }
        Ok(out)
    }

    /// The decoded mesh written again as a container of `connectivity`.
    #[cfg(feature = "encoder")]
    pub fn reencode(&self, connectivity: &str) -> Result<Vec<u8>, JsError> {
        let options = lrmesh::write::EncodeOptions {
            connectivity: crate::connectivity(connectivity)?,
            metadata: crate::metadata(),
            ..Default::default()
        };
        lrmesh::write::encode(&self.container.to_mesh(), &options).map_err(js_error)
    }
}
