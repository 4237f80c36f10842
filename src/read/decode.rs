//! Decoding a container back to a mesh (FORMAT.md §4): copies merged into their originals,
//! the connectivity's triangles then the kept-aside ones, attributes, and the input order
//! when the file keeps it.

use super::Container;
use crate::corner_table::NONE;
use crate::ids::Vertex;
use crate::mesh::seams::gather;
use crate::mesh::{Attribute, Parts, Values};
use crate::ops::CornerOps;
use crate::read::Positions;
use crate::words::{LeWords, Words};
use crate::Mesh;

impl Container<'_> {
    /// Decodes the mesh: copies merged back into their originals, canonical triangles in id
    /// order then the kept-aside ones, attributes; in the input's order when the file keeps it.
    pub fn to_mesh(&self) -> Mesh {
        let m = self.vertices as usize;
        // Output id of every container vertex: non-copies in order, copies share their original's.
        let mut output = vec![NONE; m];
        for i in 0..self.copies.count() / 2 {
            output[self.copies.at(2 * i) as usize] = u32::MAX - 1;
        }
        let mut next = 0u32;
        let mut order = Vec::with_capacity(self.output_vertices as usize);
        for (v, slot) in output.iter_mut().enumerate() {
            if *slot == NONE {
                *slot = next;
                next += 1;
                order.push(v as u32);
            }
        }
        for i in 0..self.copies.count() / 2 {
            let (copy, original) = (self.copies.at(2 * i), self.copies.at(2 * i + 1));
            output[copy as usize] = output[original as usize];
        }
        // Every triangle's container vertices, connectivity's then kept ones, and the slot
        // each comes from (`slot_ids`, left empty where slot `i` is `i`: Edgebreaker).
        let conn = &self.connectivity;
        let kept_count = self.kept.count() / 3;
        let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(self.triangles as usize + kept_count);
        let mut slot_ids = Vec::new();
        match conn {
            // The decoded table's triangles, straight from its V table.
            super::Connectivity::Edgebreaker(table) => {
                let v = table.v_table();
                triangles.extend(v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
            }
            // The standard LR tables the Zipper encodes, read back in one pass: the same
            // triangles, each a few reads instead of slot decodes.
            super::Connectivity::Zipper(zipper) => {
                let lr = zipper.to_lr_tables();
                for t in lr.triangles() {
                    slot_ids.push(t.0);
                    triangles.push(lr.triangle_vertices(t).map(|v| v.0));
                }
            }
            _ => {
                for t in conn.triangles() {
                    slot_ids.push(t.0);
                    triangles.push(conn.triangle_vertices(t).map(|v| v.0));
                }
            }
        }
        let bound = conn.triangle_id_bound();
        for j in 0..kept_count {
            if !slot_ids.is_empty() {
                slot_ids.push(bound + j as u32);
            }
            triangles.push([0, 1, 2].map(|k| self.kept.at(3 * j + k)));
        }
        let slot = |i: usize| slot_ids.get(i).copied().unwrap_or(i as u32);
        let attributes = self
            .attributes
            .iter()
            .map(|a| {
                let mut values = Values::with_capacity(a.component_type, 0);
                let n = usize::from(a.components);
                // Raw values as stored; quantized ones (f32 only) as they decode.
                let mut push = |i: u32| match a.value_bytes(i) {
                    Some(bytes) => values.push_le(bytes),
                    None => {
                        let x = a.value_f32(i);
                        let bytes: Vec<u8> = x[..n].iter().flat_map(|c| c.to_le_bytes()).collect();
                        values.push_le(&bytes);
                    }
                };
                let corners = if a.per_corner {
                    for i in 0..a.value_count() {
                        push(i);
                    }
                    let index = triangles
                        .iter()
                        .enumerate()
                        .flat_map(|(i, &tri)| {
                            let t = slot(i);
                            (0..3).map(move |k| a.value_index(t, k, tri[k], self.vertices))
                        })
                        .collect();
                    Some(index)
                } else {
                    for &v in &order {
                        push(v);
                    }
                    None
                };
                Attribute {
                    semantic: a.semantic.clone(),
                    components: a.components,
                    normalized: a.normalized,
                    values,
                    corners,
                }
            })
            .collect();
        let parts = self.parts.as_ref().map(|p| Parts {
            of_triangle: (0..triangles.len())
                .map(|i| p.part_of_slot(slot(i)))
                .collect(),
            ..p.labels.clone()
        });
        let copies = self.copies.count() > 0;
        if copies {
            for tri in &mut triangles {
                *tri = tri.map(|v| output[v as usize]);
            }
        }
        let positions = match &self.positions {
            Positions::Decoded { positions, .. } if !copies => positions.clone(),
            _ => order.iter().map(|&v| self.position(Vertex(v))).collect(),
        };
        let mut mesh = Mesh {
            positions,
            triangles,
            attributes,
            parts,
        };
        if let Some(flips) = &self.flips {
            // FORMAT.md §4 step 4: back to the input's orientation.
            for &t in flips {
                crate::mesh::reverse_triangle(&mut mesh, t as usize);
            }
        }
        if let Some((vertices, tris)) = self.perm {
            mesh = reorder(mesh, vertices, tris);
        }
        mesh
    }
}

/// Puts vertices and triangles back in the input order: output vertex `k` was input vertex
/// `vertices[k]`, output triangle `j` input triangle `tris[j]`.
fn reorder(mesh: Mesh, vertices: LeWords, tris: LeWords) -> Mesh {
    fn permute<T: Copy + Default>(items: &[T], to: impl Fn(usize) -> usize) -> Vec<T> {
        let mut out = vec![T::default(); items.len()];
        for (k, item) in items.iter().enumerate() {
            out[to(k)] = *item;
        }
        out
    }
    let to_v = |k: usize| vertices.at(k) as usize;
    let to_t = |j: usize| tris.at(j) as usize;
    let renamed: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| vertices.at(v as usize)))
        .collect();
    let attributes = mesh
        .attributes
        .iter()
        .map(|a| match &a.corners {
            // Values stay; each triangle's three corner indices move with it.
            Some(index) => {
                let by_triangle: Vec<[u32; 3]> =
                    index.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
                let moved = permute(&by_triangle, to_t);
                gather(a, (0..a.value_count()).map(Some), Some(moved.concat()))
            }
            None => {
                let mut from = vec![0; a.value_count()];
                for k in 0..from.len() {
                    from[to_v(k)] = k;
                }
                gather(a, from.into_iter().map(Some), None)
            }
        })
        .collect();
    let parts = mesh.parts.map(|p| crate::mesh::Parts {
        of_triangle: permute(&p.of_triangle, to_t),
        ..p
    });
    Mesh {
        positions: permute(&mesh.positions, to_v),
        triangles: permute(&renamed, to_t),
        attributes,
        parts,
    }
}
