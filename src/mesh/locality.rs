//! A cache-friendly order for a large mesh, which the writer takes when the input's order need
//! not be kept: vertices along a Morton (Z-order) curve through their bounding box, triangles
//! by the first of their vertices in that order. Building a connectivity walks the mesh by
//! adjacency (the LR's ring expansions, leaf moves and tables, the corner table's matching);
//! on a mesh stored in scattered order, as subdivisions and shuffles leave it, nearly every
//! step of those walks misses the cache. Nothing is lost: every vertex (unreferenced ones too),
//! triangle, attribute value and part label moves, none changes.

use super::{Attribute, Mesh, Values};
use crate::error::{Error, Result};

/// Meshes of fewer triangles keep their order: their arrays fit in the caches, and small
/// files come out as they always did.
pub const LOCALITY_TRIANGLES: usize = 1 << 17;

/// Bits of each coordinate in a vertex's Morton key (three of them fit in 32 bits).
const AXIS_BITS: u32 = 10;

/// A new order of a mesh's vertices and triangles.
#[derive(Debug, Clone)]
pub struct Order {
    /// `old_vertex[i]`: the vertex that becomes vertex `i`.
    old_vertex: Vec<u32>,
    /// `new_vertex[v]`: the new id of vertex `v` (the inverse of `old_vertex`).
    new_vertex: Vec<u32>,
    /// `old_triangle[t]`: the triangle that becomes triangle `t`.
    old_triangle: Vec<u32>,
}

impl Order {
    /// The order of `mesh`: vertices by Morton key (ties by id), triangles by their smallest
    /// new vertex id (ties by id). Linear time: two radix passes over the keys and a counting
    /// sort.
    ///
    /// # Errors
    /// [`Error::InvalidMesh`] for a mesh that breaks [`Mesh::validate`].
    pub fn of(mesh: &Mesh) -> Result<Order> {
        mesh.validate()?;
        Ok(Order::of_valid(mesh))
    }

    /// `mesh` in this order, the order of a mesh of the same vertex and triangle counts.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the counts differ; [`Error::InvalidMesh`] for a mesh
    /// that breaks [`Mesh::validate`].
    pub fn apply(&self, mesh: &Mesh) -> Result<Mesh> {
        let (v, t) = (self.new_vertex.len(), self.old_triangle.len());
        if mesh.positions.len() != v || mesh.triangles.len() != t {
            return Err(Error::InvalidArgument(format!(
                "an order of {v} vertices and {t} triangles applied to a mesh of {} and {}",
                mesh.positions.len(),
                mesh.triangles.len()
            )));
        }
        mesh.validate()?;
        Ok(self.apply_valid(mesh))
    }

    /// [`Order::of`] of a mesh known to be valid (the writer's, validated already).
    pub(crate) fn of_valid(mesh: &Mesh) -> Order {
        let keys = morton_keys(&mesh.positions);
        let old_vertex = sorted_by_key(&keys);
        drop(keys);
        let mut new_vertex = vec![0u32; old_vertex.len()];
        for (i, &v) in old_vertex.iter().enumerate() {
            new_vertex[v as usize] = i as u32;
        }
        // Counting sort of the triangles by their first vertex in the new order.
        let first = |tri: &[u32; 3]| tri.iter().map(|&v| new_vertex[v as usize]).min();
        let mut starts = vec![0u32; new_vertex.len() + 1];
        for tri in &mesh.triangles {
            if let Some(k) = first(tri) {
                starts[k as usize + 1] += 1;
            }
        }
        for k in 1..starts.len() {
            starts[k] += starts[k - 1];
        }
        let mut old_triangle = vec![0u32; mesh.triangles.len()];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if let Some(k) = first(tri) {
                let at = &mut starts[k as usize];
                old_triangle[*at as usize] = t as u32;
                *at += 1;
            }
        }
        Order {
            old_vertex,
            new_vertex,
            old_triangle,
        }
    }

    /// [`Order::apply`] to a valid mesh of this order's counts.
    pub(crate) fn apply_valid(&self, mesh: &Mesh) -> Mesh {
        let triangles = self
            .old_triangle
            .iter()
            .map(|&t| mesh.triangles[t as usize].map(|v| self.new_vertex[v as usize]))
            .collect();
        let attributes = mesh.attributes.iter().map(|a| self.attribute(a)).collect();
        let parts = mesh.parts.as_ref().map(|p| super::Parts {
            of_triangle: self.per_triangle(&p.of_triangle),
            ..p.clone()
        });
        Mesh {
            positions: gather(&mesh.positions, 1, &self.old_vertex),
            triangles,
            attributes,
            parts,
        }
    }

    /// Per-triangle `values` (one each) in the new triangle order.
    pub fn per_triangle<T: Copy>(&self, values: &[T]) -> Vec<T> {
        gather(values, 1, &self.old_triangle)
    }

    /// Per-vertex values follow their vertices; per-corner indices follow their triangles
    /// (the values themselves stay where they are).
    fn attribute(&self, a: &Attribute) -> Attribute {
        match &a.corners {
            Some(corners) => Attribute {
                corners: Some(gather(corners, 3, &self.old_triangle)),
                ..a.clone()
            },
            None => {
                let n = usize::from(a.components);
                let values = match &a.values {
                    Values::I8(v) => Values::I8(gather(v, n, &self.old_vertex)),
                    Values::U8(v) => Values::U8(gather(v, n, &self.old_vertex)),
                    Values::I16(v) => Values::I16(gather(v, n, &self.old_vertex)),
                    Values::U16(v) => Values::U16(gather(v, n, &self.old_vertex)),
                    Values::U32(v) => Values::U32(gather(v, n, &self.old_vertex)),
                    Values::F32(v) => Values::F32(gather(v, n, &self.old_vertex)),
                };
                Attribute {
                    semantic: a.semantic.clone(),
                    components: a.components,
                    normalized: a.normalized,
                    values,
                    corners: None,
                }
            }
        }
    }
}

/// Groups of `n` values of `values`, group `order[i]` at place `i`.
fn gather<T: Copy>(values: &[T], n: usize, order: &[u32]) -> Vec<T> {
    let mut out = Vec::with_capacity(order.len() * n);
    for &i in order {
        let at = i as usize * n;
        out.extend_from_slice(&values[at..at + n]);
    }
    out
}

/// Morton keys over a bounding box: a position's cell in a grid of 2^10 steps per axis, the
/// coordinates' bits interleaved (x lowest).
struct Grid {
    low: [f64; 3],
    scale: [f64; 3],
}

impl Grid {
    fn of(positions: &[[f32; 3]]) -> Grid {
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        for p in positions {
            for i in 0..3 {
                low[i] = low[i].min(f64::from(p[i]));
                high[i] = high[i].max(f64::from(p[i]));
            }
        }
        // A flat box (or a single point) puts every coordinate of that axis in cell 0.
        let scale = std::array::from_fn(|i| match high[i] - low[i] {
            extent if extent > 0.0 => f64::from(CELLS) / extent,
            _ => 0.0,
        });
        Grid { low, scale }
    }

    fn key(&self, p: &[f32; 3]) -> u32 {
        (0..3).fold(0u32, |key, i| {
            // `as` saturates, and the scale keeps the cell within 0..=CELLS anyway.
            let cell = ((f64::from(p[i]) - self.low[i]) * self.scale[i]) as u32;
            key | spread(cell.min(CELLS)) << i
        })
    }
}

/// The last cell of an axis.
const CELLS: u32 = (1 << AXIS_BITS) - 1;

/// Each position's Morton key ([`Grid`]).
fn morton_keys(positions: &[[f32; 3]]) -> Vec<u32> {
    let grid = Grid::of(positions);
    positions.iter().map(|p| grid.key(p)).collect()
}

/// Whether [`Order::of`] of `mesh` would leave it as it is (vertex keys and triangles' first
/// vertices never decrease): two passes without allocating, so that a mesh put in order
/// already (by a caller that needed the order first) is not copied again. Any mesh: an
/// index out of range is compared, never used.
pub(crate) fn is_in_order(mesh: &Mesh) -> bool {
    let grid = Grid::of(&mesh.positions);
    let keys = mesh.positions.iter().map(|p| grid.key(p));
    let firsts = mesh.triangles.iter().map(|t| t[0].min(t[1]).min(t[2]));
    non_decreasing(keys) && non_decreasing(firsts)
}

fn non_decreasing(mut values: impl Iterator<Item = u32>) -> bool {
    let Some(mut last) = values.next() else {
        return true;
    };
    values.all(|x| {
        let ok = last <= x;
        last = x;
        ok
    })
}

/// The low 10 bits of `x`, two zero bits after each.
fn spread(x: u32) -> u32 {
    let mut x = x & 0x3ff;
    x = (x | x << 16) & 0x0300_00ff;
    x = (x | x << 8) & 0x0300_f00f;
    x = (x | x << 4) & 0x030c_30c3;
    (x | x << 2) & 0x0924_9249
}

/// The indices of `keys` in increasing order of key, equal keys by index: a least-significant
/// digit radix sort, 15 bits a pass (keys have 30).
fn sorted_by_key(keys: &[u32]) -> Vec<u32> {
    const DIGIT: u32 = 15;
    let mut order: Vec<u32> = (0..keys.len() as u32).collect();
    let mut next = vec![0u32; keys.len()];
    for pass in 0..2 {
        let digit = |i: u32| (keys[i as usize] >> (pass * DIGIT)) as usize & ((1 << DIGIT) - 1);
        let mut starts = vec![0u32; (1 << DIGIT) + 1];
        for &i in &order {
            starts[digit(i) + 1] += 1;
        }
        for k in 1..starts.len() {
            starts[k] += starts[k - 1];
        }
        for &i in &order {
            let at = &mut starts[digit(i)];
            next[*at as usize] = i;
            *at += 1;
        }
        std::mem::swap(&mut order, &mut next);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Part, Parts, Semantic};

    /// Positions along a line in scattered order, an unreferenced vertex, a per-vertex and a
    /// per-corner attribute, parts.
    fn scattered() -> Mesh {
        let xs = [5.0f32, 0.0, 3.0, 1.0, 4.0, 2.0, 9.0];
        let positions = xs.iter().map(|&x| [x, 0.0, 0.0]).collect();
        let triangles = vec![[0, 2, 4], [1, 3, 5], [2, 4, 0], [3, 3, 1]];
        let mut mesh = Mesh::new(positions, triangles);
        let normals: Vec<[f32; 3]> = xs.iter().map(|&x| [x, 1.0, 0.0]).collect();
        mesh.attributes
            .push(Attribute::per_vertex(Semantic::Normal, &normals));
        let uv: Vec<[f32; 2]> = (0..12).map(|i| [i as f32, 0.0]).collect();
        let corners = (0..12).rev().collect();
        mesh.attributes
            .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
        let mut parts = Parts::default();
        for name in ["a", "b", "a", "c"] {
            let part = Part {
                material: Some(name.into()),
                ..Part::default()
            };
            let p = parts.intern(part);
            parts.of_triangle.push(p);
        }
        mesh.parts = Some(parts);
        mesh
    }

    /// Every corner as (position, values, part), sorted: what must survive a new order.
    fn corners(mesh: &Mesh) -> Vec<String> {
        let mut all = Vec::new();
        for (t, &tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let values: Vec<Vec<f32>> = mesh
                    .attributes
                    .iter()
                    .map(|a| a.value_f32(a.value_index(t, k, tri)))
                    .collect();
                let part = mesh.parts.as_ref().map(|p| p.of(t).clone());
                let position = mesh.positions[tri[k] as usize];
                all.push(format!("{position:?} {values:?} {part:?}"));
            }
        }
        all.sort();
        all
    }

    #[test]
    fn vertices_follow_the_curve_and_triangles_their_first_vertex() {
        let mesh = scattered();
        let order = Order::of(&mesh).unwrap();
        let moved = order.apply(&mesh).unwrap();
        moved.validate().unwrap();
        let xs: Vec<f32> = moved.positions.iter().map(|p| p[0]).collect();
        assert_eq!(xs, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 9.0]);
        // Old triangles 1 and 3 start at new vertex 0, 0 and 2 at new vertex 3: each pair in
        // its old order, each triangle's corners in theirs.
        assert_eq!(
            moved.triangles,
            [[0, 1, 2], [1, 1, 0], [5, 3, 4], [3, 4, 5]]
        );
        assert_eq!(order.per_triangle(&[10, 11, 12, 13]), [11, 13, 10, 12]);
        // Every value and label moves with its corner and triangle.
        assert_eq!(corners(&moved), corners(&mesh));
        assert_eq!(moved.positions.len(), mesh.positions.len());
    }

    #[test]
    fn the_order_of_an_ordered_mesh_is_itself() {
        assert!(!is_in_order(&scattered()));
        let moved = Order::of(&scattered())
            .unwrap()
            .apply(&scattered())
            .unwrap();
        assert!(is_in_order(&moved));
        let again = Order::of(&moved).unwrap().apply(&moved).unwrap();
        assert_eq!(again, moved);
    }

    #[test]
    fn invalid_meshes_and_other_counts_get_errors() {
        let mesh = scattered();
        let order = Order::of(&mesh).unwrap();
        let mut broken = mesh.clone();
        broken.triangles[1][2] = 7;
        assert!(matches!(Order::of(&broken), Err(Error::InvalidMesh(_))));
        assert!(matches!(order.apply(&broken), Err(Error::InvalidMesh(_))));
        let mut fewer = mesh.clone();
        fewer.triangles.pop();
        assert!(matches!(
            order.apply(&fewer),
            Err(Error::InvalidArgument(_))
        ));
        let mut more = mesh;
        more.positions.push([0.0; 3]);
        assert!(matches!(order.apply(&more), Err(Error::InvalidArgument(_))));
    }

    #[test]
    fn keys_interleave_the_axes() {
        assert_eq!(spread(0x3ff), 0x0924_9249);
        assert_eq!(spread(0b101), 0b1_000_001);
        let keys = morton_keys(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]);
        assert_eq!(keys, [0, 0x0924_9249, 0x0924_9249 << 1, 0x0924_9249 << 2]);
        // Flat and degenerate boxes do not divide by zero.
        assert_eq!(morton_keys(&[[2.0, 2.0, 2.0], [2.0, 2.0, 2.0]]), [0, 0]);
        assert_eq!(sorted_by_key(&[3, 1 << 20, 1, 3, 0]), [4, 2, 0, 3, 1]);
    }
}
