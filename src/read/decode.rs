//! Decoding a container back to a mesh (FORMAT.md §4): copies merged into their originals,
//! the connectivity's triangles then the kept-aside ones, attributes, and the input order
//! when the file keeps it.

use super::Container;
use crate::corner_table::NONE;
use crate::format::le_f32;
use crate::ids::Vertex;
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
        let mut triangles: Vec<[u32; 3]> =
            Vec::with_capacity(self.triangles as usize + self.kept.count() / 3);
        self.connectivity
            .for_each_triangle(|t| triangles.push(t.map(|v| output[v as usize])));
        for i in 0..self.kept.count() / 3 {
            triangles.push([0, 1, 2].map(|k| output[self.kept.at(3 * i + k) as usize]));
        }
        let floats = |b: &[u8], v: u32, n: usize, k: usize| le_f32(b, 4 * (n * v as usize + k));
        let mut mesh = Mesh {
            positions: order.iter().map(|&v| self.position(Vertex(v))).collect(),
            triangles,
            normals: self.normals.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1, 2].map(|k| floats(b, v, 3, k)))
                    .collect()
            }),
            texcoords: self.texcoords.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1].map(|k| floats(b, v, 2, k)))
                    .collect()
            }),
            colors: self.colors.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1, 2, 3].map(|k| b[4 * v as usize + k]))
                    .collect()
            }),
        };
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
    let renamed: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| vertices.at(v as usize)))
        .collect();
    Mesh {
        positions: permute(&mesh.positions, to_v),
        triangles: permute(&renamed, |j| tris.at(j) as usize),
        normals: mesh.normals.as_deref().map(|n| permute(n, to_v)),
        texcoords: mesh.texcoords.as_deref().map(|t| permute(t, to_v)),
        colors: mesh.colors.as_deref().map(|c| permute(c, to_v)),
    }
}
