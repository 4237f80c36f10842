//! Moving attributes between per-vertex and per-corner binding without losing a value:
//! splitting vertices at seams for formats that only know per-vertex attributes (OFF, PLY,
//! STL, glTF), and welding split vertices back into one connectivity.

use std::collections::HashMap;

use super::{Attribute, Mesh, Values};

impl Mesh {
    /// Whether some attribute is given per corner.
    pub fn has_per_corner_attributes(&self) -> bool {
        self.attributes.iter().any(Attribute::is_per_corner)
    }

    /// The same triangles with every attribute per vertex: a vertex whose corners carry
    /// different values (a seam) becomes one vertex per distinct combination of value
    /// indices. Vertices keep their order (each split one's copies follow it); unreferenced
    /// vertices stay, with zeros for each per-corner attribute (they have no corner to take
    /// a value from). Without per-corner attributes the mesh is returned as it is.
    pub fn split_seams(&self) -> Mesh {
        if !self.has_per_corner_attributes() {
            return self.clone();
        }
        let per_corner: Vec<&Attribute> = self
            .attributes
            .iter()
            .filter(|a| a.is_per_corner())
            .collect();
        let key = |corner: usize| -> Vec<u32> {
            per_corner
                .iter()
                .map(|a| a.corners.as_ref().expect("per corner")[corner])
                .collect()
        };
        // The distinct keys of each vertex, in order of first use.
        let mut keys: Vec<Vec<Vec<u32>>> = vec![Vec::new(); self.positions.len()];
        let mut corner_slot = Vec::with_capacity(3 * self.triangles.len());
        for (c, &v) in self.triangles.iter().flatten().enumerate() {
            let k = key(c);
            let list = &mut keys[v as usize];
            let slot = match list.iter().position(|x| *x == k) {
                Some(i) => i,
                None => {
                    list.push(k);
                    list.len() - 1
                }
            };
            corner_slot.push(slot as u32);
        }
        let mut first_id = Vec::with_capacity(self.positions.len());
        let mut source = Vec::new(); // new vertex -> (old vertex, key)
        for (v, list) in keys.iter().enumerate() {
            first_id.push(source.len() as u32);
            if list.is_empty() {
                source.push((v, None));
            }
            source.extend(list.iter().map(|k| (v, Some(k))));
        }
        let triangles = self
            .triangles
            .iter()
            .enumerate()
            .map(|(t, tri)| [0, 1, 2].map(|k| first_id[tri[k] as usize] + corner_slot[3 * t + k]))
            .collect();
        let mut slot_of = vec![0usize; self.attributes.len()];
        let mut j = 0;
        for (i, a) in self.attributes.iter().enumerate() {
            if a.is_per_corner() {
                slot_of[i] = j;
                j += 1;
            }
        }
        let attributes = self
            .attributes
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let pick = |&(v, key): &(usize, Option<&Vec<u32>>)| match (&a.corners, key) {
                    (None, _) => Some(v),
                    (Some(_), Some(key)) => Some(key[slot_of[i]] as usize),
                    (Some(_), None) => None,
                };
                gather(a, source.iter().map(pick), None)
            })
            .collect();
        Mesh {
            positions: source.iter().map(|&(v, _)| self.positions[v]).collect(),
            triangles,
            attributes,
            parts: self.parts.clone(),
        }
    }

    /// Merges vertices whose positions are equal bit for bit, `-0.0` equal to `0.0` (glTF and STL split a vertex
    /// wherever an attribute changes) into one, so that the connectivity sees one surface.
    /// An attribute whose values differ between merged vertices becomes per corner (its
    /// values kept as they were, each corner pointing at its old vertex's); one that agrees
    /// stays per vertex. Vertices keep the order of their first occurrence.
    pub fn weld(&self) -> Mesh {
        let mut id_of: HashMap<[u32; 3], usize> = HashMap::with_capacity(self.positions.len());
        let representative = (self.positions.iter().enumerate())
            .map(|(v, p)| *id_of.entry(p.map(bits_of)).or_insert(v))
            .collect();
        self.welded(representative)
    }

    /// [`Mesh::weld`] that also merges vertices whose positions differ by at most
    /// `tolerance` in every coordinate: each vertex merges into the first earlier vertex
    /// that close (which need not be close to a third), and takes its position, so that
    /// positions move by at most `tolerance`. A `tolerance` of 0 (or less, or NaN) is
    /// [`Mesh::weld`]. Linear in the vertices, through a grid of cells `tolerance` wide.
    pub fn weld_within(&self, tolerance: f32) -> Mesh {
        if tolerance.is_nan() || tolerance <= 0.0 {
            return self.weld();
        }
        let cell = |p: [f32; 3]| p.map(|x| (x / tolerance).floor() as i64);
        let mut kept: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        let mut representative = Vec::with_capacity(self.positions.len());
        for (v, &p) in self.positions.iter().enumerate() {
            let [x, y, z] = cell(p);
            let near = (x - 1..=x + 1)
                .flat_map(|a| {
                    (y - 1..=y + 1).flat_map(move |b| (z - 1..=z + 1).map(move |c| [a, b, c]))
                })
                .filter_map(|k| kept.get(&k))
                .flatten()
                .copied()
                .filter(|&w| (0..3).all(|i| (self.positions[w][i] - p[i]).abs() <= tolerance))
                .min();
            match near {
                Some(w) => representative.push(w),
                None => {
                    kept.entry([x, y, z]).or_default().push(v);
                    representative.push(v);
                }
            }
        }
        self.welded(representative)
    }

    /// The mesh with each vertex `v` merged into `representative[v]` (an earlier or the same
    /// vertex, itself its own representative), which gives its position.
    fn welded(&self, representative: Vec<usize>) -> Mesh {
        let mut first = Vec::new(); // new vertex -> first old vertex
        let mut new_id = vec![0u32; self.positions.len()];
        for (v, &r) in representative.iter().enumerate() {
            if r == v {
                new_id[v] = first.len() as u32;
                first.push(v);
            }
        }
        let merged: Vec<u32> = representative.iter().map(|&r| new_id[r]).collect();
        let triangles: Vec<[u32; 3]> = self
            .triangles
            .iter()
            .map(|t| t.map(|v| merged[v as usize]))
            .collect();
        let attributes = self
            .attributes
            .iter()
            .map(|a| {
                if a.is_per_corner() {
                    return a.clone();
                }
                let agrees = (0..self.positions.len()).all(|v| {
                    let w = first[merged[v] as usize];
                    v == w || same_value(a, v, w)
                });
                if agrees {
                    gather(a, first.iter().map(|&v| Some(v)), None)
                } else {
                    let corners = self.triangles.iter().flatten().copied().collect();
                    Attribute {
                        corners: Some(corners),
                        ..a.clone()
                    }
                }
            })
            .collect();
        Mesh {
            positions: first.iter().map(|&v| self.positions[v]).collect(),
            triangles,
            attributes,
            parts: self.parts.clone(),
        }
    }
}

/// The bits of a coordinate, `-0.0` as `+0.0` (the same position).
fn bits_of(x: f32) -> u32 {
    if x == 0.0 {
        0
    } else {
        x.to_bits()
    }
}

/// Whether values `i` and `j` of `a` are equal bit for bit.
pub(crate) fn same_value(a: &Attribute, i: usize, j: usize) -> bool {
    let (mut x, mut y) = (Vec::new(), Vec::new());
    a.value_bytes(i, &mut x);
    a.value_bytes(j, &mut y);
    x == y
}

/// `a` with the values `picks` chooses, in that order (`None`: zeros), and the given binding.
pub(crate) fn gather(
    a: &Attribute,
    picks: impl Iterator<Item = Option<usize>>,
    corners: Option<Vec<u32>>,
) -> Attribute {
    let n = usize::from(a.components);
    let mut bytes = Vec::new();
    for pick in picks {
        match pick {
            Some(i) => a.values.write_le(n * i..n * i + n, &mut bytes),
            None => bytes.resize(bytes.len() + n * a.values.component_type().size(), 0),
        }
    }
    let mut values = Values::with_capacity(a.values.component_type(), bytes.len());
    values.push_le(&bytes);
    Attribute {
        semantic: a.semantic.clone(),
        components: a.components,
        normalized: a.normalized,
        values,
        corners,
    }
}
