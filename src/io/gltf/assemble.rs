//! From mesh instances to one [`Mesh`]: each primitive's vertices decoded, placed by its
//! node and appended (once per set of accessors and world matrix), its indices turned into
//! triangles with their part, and the attributes of all primitives joined.

use std::collections::{BTreeMap, HashMap};

use super::accessor::{component_name, decode, decode_indices, Budget, Decoded};
use super::buffers::Buffers;
use super::document::{Document, ElementType, Primitive};
use super::read::Instance;
use super::semantics::{allowed, kind_of, to_f32, Kind};
use super::transform::Placement;
use super::{escape, json_error};
use crate::error::Result;
use crate::io::{MAX_TRIANGLES, MAX_VERTICES};
use crate::mesh::{Attribute, ComponentType, Mesh, Part, Parts, Semantic, Values};

/// A run of vertices: one primitive's, or several primitives' that share every accessor.
struct Block {
    count: usize,
    attributes: BTreeMap<Semantic, Decoded>,
}

/// What was skipped or adjusted, reported once per kind.
#[derive(Default)]
struct Notes {
    skipped: BTreeMap<String, &'static str>,
    dropped_modes: usize,
    without_position: usize,
    with_targets: usize,
    skinned: bool,
}

/// A world matrix's bits and a primitive's attribute accessors, sorted.
type BlockKey = (Vec<u64>, Vec<(String, usize)>);

pub(super) struct Builder<'d> {
    doc: &'d Document,
    buffers: &'d Buffers<'d>,
    budget: Budget,
    quantized: bool,
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    blocks: Vec<Block>,
    /// Block of (world matrix bits, attribute accessors): primitives that share all their
    /// accessors under one transform share their vertices.
    block_of: HashMap<BlockKey, (usize, u32)>,
    parts: Parts,
    notes: Notes,
}

impl<'d> Builder<'d> {
    pub fn new(doc: &'d Document, buffers: &'d Buffers<'d>, budget: Budget) -> Builder<'d> {
        Builder {
            doc,
            buffers,
            budget,
            quantized: doc
                .extensions_used
                .iter()
                .any(|e| e == "KHR_mesh_quantization"),
            positions: Vec::new(),
            triangles: Vec::new(),
            blocks: Vec::new(),
            block_of: HashMap::new(),
            parts: Parts::default(),
            notes: Notes::default(),
        }
    }

    pub fn add_instance(&mut self, instance: &Instance) -> Result<()> {
        let placement = Placement::new(instance.world);
        if let Some(n) = instance.node {
            self.notes.skinned |= self.doc.nodes[n].has_skin;
        }
        for p in 0..self.doc.meshes[instance.mesh].primitives.len() {
            self.add_primitive(instance, &placement, p)?;
        }
        Ok(())
    }

    fn add_primitive(
        &mut self,
        instance: &Instance,
        placement: &Placement,
        p: usize,
    ) -> Result<()> {
        let doc = self.doc;
        let mesh = &doc.meshes[instance.mesh];
        let prim = &mesh.primitives[p];
        let path = format!("meshes[{}].primitives[{p}]", instance.mesh);
        if prim.mode > 6 {
            return Err(json_error(
                &format!("{path}.mode"),
                format!("unknown mode {} (0 to 6)", prim.mode),
            ));
        }
        if !prim.attributes.iter().any(|(name, _)| name == "POSITION") {
            self.notes.without_position += 1;
            return Ok(());
        }
        if prim.has_targets {
            self.notes.with_targets += 1;
        }
        let mut key_attributes = prim.attributes.clone();
        key_attributes.sort();
        let key = (instance.world.map(f64::to_bits).to_vec(), key_attributes);
        let (block, start) = match self.block_of.get(&key) {
            Some(&found) => found,
            None => {
                let found = self.add_block(prim, placement, &path)?;
                self.block_of.insert(key, found);
                found
            }
        };
        let count = self.blocks[block].count;
        if prim.mode < 4 {
            self.notes.dropped_modes += 1;
            return Ok(());
        }
        let indices = match prim.indices {
            Some(a) => decode_indices(
                doc,
                self.buffers,
                a,
                &mut self.budget,
                &format!("{path}.indices"),
            )?,
            None => {
                self.budget.charge(4 * count as u64, &path)?;
                (0..count as u32).collect()
            }
        };
        if let Some(k) = indices.iter().position(|&i| i as usize >= count) {
            return Err(json_error(
                &format!("{path}.indices"),
                format!(
                    "index {} at entry {k} is out of range: the primitive has {count} vertices",
                    indices[k]
                ),
            ));
        }
        if prim.mode == 4 && indices.len() % 3 != 0 {
            return Err(json_error(
                &path,
                format!(
                    "TRIANGLES with {} indices, not a multiple of 3",
                    indices.len()
                ),
            ));
        }
        let n = indices.len();
        let new = match prim.mode {
            4 => n / 3,
            _ => n.saturating_sub(2),
        };
        if (self.triangles.len() + new) as u64 > MAX_TRIANGLES {
            return Err(json_error(
                &path,
                format!("more than {MAX_TRIANGLES} triangles"),
            ));
        }
        self.budget.charge(16 * new as u64, &path)?;
        let corner = |k: usize| indices[k] + start;
        for t in 0..new {
            let tri = match prim.mode {
                4 => [corner(3 * t), corner(3 * t + 1), corner(3 * t + 2)],
                // TRIANGLE_STRIP: {v_i, v_(i+1+i%2), v_(i+2-i%2)}.
                5 => [corner(t), corner(t + 1 + t % 2), corner(t + 2 - t % 2)],
                // TRIANGLE_FAN: {v_(i+1), v_(i+2), v_0}.
                _ => [corner(t + 1), corner(t + 2), corner(0)],
            };
            self.triangles.push(if placement.mirrors() {
                [tri[0], tri[2], tri[1]]
            } else {
                tri
            });
        }
        let part = Part {
            object: instance
                .node
                .and_then(|n| doc.nodes[n].name.clone())
                .or_else(|| mesh.name.clone()),
            group: prim.group.clone(),
            material: prim.material.map(|m| {
                doc.materials[m]
                    .clone()
                    .unwrap_or_else(|| format!("material{m}"))
            }),
        };
        let id = self.parts.intern(part);
        self.parts.of_triangle.resize(self.triangles.len(), id);
        Ok(())
    }

    /// Decodes and places a primitive's vertices; returns the block and its first vertex.
    fn add_block(
        &mut self,
        prim: &Primitive,
        placement: &Placement,
        path: &str,
    ) -> Result<(usize, u32)> {
        let doc = self.doc;
        let mut count = None;
        let mut positions = Vec::new();
        let mut attributes = BTreeMap::new();
        for (name, accessor) in &prim.attributes {
            let kind = kind_of(name);
            let apath = format!("{path}.attributes.{}", escape(name));
            if let Kind::Skip(why) = kind {
                self.notes.skipped.insert(escape(name), why);
                continue;
            }
            let a = &doc.accessors[*accessor];
            if let Err(want) = allowed(&kind, a.element, a.component, a.normalized, self.quantized)
            {
                return Err(json_error(
                    &apath,
                    format!(
                        "accessors[{accessor}] is {} of {}{}; {} must be {want}",
                        a.element.name(),
                        if a.normalized { "normalized " } else { "" },
                        component_name(a.component),
                        escape(name)
                    ),
                ));
            }
            if let ElementType::Matrix(_) = a.element {
                self.notes
                    .skipped
                    .insert(escape(name), "matrix-typed attributes are not kept");
                continue;
            }
            let d = decode(doc, self.buffers, *accessor, &mut self.budget)?;
            match count {
                None => count = Some(d.count()),
                Some(c) if c != d.count() => {
                    return Err(json_error(
                        &apath,
                        format!(
                            "accessors[{accessor}] has {} elements, another attribute of the \
                             primitive {c}",
                            d.count()
                        ),
                    ))
                }
                Some(_) => {}
            }
            match kind {
                Kind::Position => positions = to_f32(&d),
                Kind::Attribute(Semantic::Normal)
                    if !placement.is_identity()
                        || d.values.component_type() != ComponentType::F32 =>
                {
                    let normals: Vec<f32> = to_f32(&d)
                        .chunks_exact(3)
                        .flat_map(|n| placement.normal([n[0], n[1], n[2]]))
                        .collect();
                    attributes.insert(
                        Semantic::Normal,
                        Decoded {
                            components: 3,
                            normalized: false,
                            values: Values::F32(normals),
                        },
                    );
                }
                Kind::Attribute(semantic) => {
                    attributes.insert(semantic, d);
                }
                Kind::Skip(_) => {}
            }
        }
        let count = count.unwrap_or(0);
        let start = self.positions.len();
        if (start + count) as u64 > MAX_VERTICES {
            return Err(json_error(
                path,
                format!("more than {MAX_VERTICES} vertices"),
            ));
        }
        self.budget.charge(12 * count as u64, path)?;
        for (v, p) in positions.chunks_exact(3).enumerate() {
            let placed = placement.position([p[0], p[1], p[2]]);
            if placed.iter().any(|x| !x.is_finite()) {
                return Err(json_error(
                    path,
                    format!(
                        "the node transform takes vertex {v} to a non-finite position {placed:?}"
                    ),
                ));
            }
            self.positions.push(placed);
        }
        self.blocks.push(Block { count, attributes });
        Ok((self.blocks.len() - 1, start as u32))
    }

    /// Joins the blocks' attributes into the mesh's and reports what was adjusted.
    pub fn finish(mut self, warnings: &mut Vec<String>) -> Result<Mesh> {
        let mut semantics: Vec<Semantic> = self
            .blocks
            .iter()
            .flat_map(|b| b.attributes.keys().cloned())
            .collect();
        semantics.sort();
        semantics.dedup();
        let mut attributes = Vec::new();
        for semantic in semantics {
            attributes.push(self.join(&semantic, warnings)?);
        }
        let notes = &self.notes;
        for (name, why) in &notes.skipped {
            warnings.push(format!("attribute `{name}` skipped: {why}"));
        }
        if notes.dropped_modes > 0 {
            warnings.push(format!(
                "{} point or line primitives: their points and lines are dropped, their \
                 vertices kept (unreferenced)",
                notes.dropped_modes
            ));
        }
        if notes.without_position > 0 {
            warnings.push(format!(
                "{} primitives without POSITION skipped",
                notes.without_position
            ));
        }
        if notes.with_targets > 0 {
            warnings.push(format!(
                "{} primitives have morph targets; the base shape is read",
                notes.with_targets
            ));
        }
        if notes.skinned {
            warnings
                .push("skins are ignored: skinned meshes are read as placed by their nodes".into());
        }
        if self.triangles.is_empty() && self.positions.is_empty() {
            warnings.push("the scene holds no triangle primitive: the mesh is empty".into());
        }
        let any_label = self.parts.parts.iter().any(|p| *p != Part::default());
        // Without a vertex, an attribute holds no value (a primitive of empty accessors):
        // it says nothing, and no file could store it.
        let attributes = if self.positions.is_empty() {
            Vec::new()
        } else {
            attributes
        };
        Ok(Mesh {
            positions: self.positions,
            triangles: self.triangles,
            attributes,
            parts: any_label.then_some(self.parts),
        })
    }

    /// One attribute over all blocks: as stored when every block stores it alike, else as
    /// f32; with zeros (colors: ones) where a block lacks it.
    fn join(&mut self, semantic: &Semantic, warnings: &mut Vec<String>) -> Result<Attribute> {
        let shape = |d: &Decoded| (d.values.component_type() as u8, d.components, d.normalized);
        let mut shapes: Vec<_> = self
            .blocks
            .iter()
            .filter_map(|b| b.attributes.get(semantic).map(shape))
            .collect();
        shapes.sort_unstable();
        shapes.dedup();
        let converted = shapes.len() > 1;
        let (kind, components, normalized) = if converted {
            let components = shapes.iter().map(|s| s.1).max().unwrap_or(1);
            warnings.push(format!(
                "{semantic} is stored with different types in different primitives: converted \
                 to f32"
            ));
            (ComponentType::F32, components, false)
        } else {
            let s = shapes[0];
            (
                ComponentType::from_code(s.0).unwrap_or(ComponentType::F32),
                s.1,
                s.2,
            )
        };
        let is_color = matches!(semantic, Semantic::Color(_));
        // The value of a vertex that lacks the attribute: zeros, or for colors ones (colors
        // are f32 or normalized u8 or u16, or converted to f32).
        let mut one = Vec::new();
        for _ in 0..components {
            match (is_color, kind) {
                (true, ComponentType::F32) => one.extend_from_slice(&1.0f32.to_le_bytes()),
                (true, ComponentType::U8) => one.push(u8::MAX),
                (true, ComponentType::U16) => one.extend_from_slice(&u16::MAX.to_le_bytes()),
                _ => one.resize(one.len() + kind.size(), 0),
            }
        }
        let mut bytes = Vec::new();
        let mut missing = (0usize, 0usize);
        for b in &self.blocks {
            match b.attributes.get(semantic) {
                Some(d) if !converted => {
                    d.values.write_le(0..d.values.len(), &mut bytes);
                }
                Some(d) => {
                    let have = usize::from(d.components);
                    for value in to_f32(d).chunks_exact(have) {
                        for k in 0..usize::from(components) {
                            let x = value.get(k).copied().unwrap_or(if is_color && k == 3 {
                                1.0
                            } else {
                                0.0
                            });
                            bytes.extend_from_slice(&x.to_le_bytes());
                        }
                    }
                }
                None => {
                    self.budget
                        .charge((one.len() * b.count) as u64, &format!("{semantic}"))?;
                    missing.0 += 1;
                    missing.1 += b.count;
                    for _ in 0..b.count {
                        bytes.extend_from_slice(&one);
                    }
                }
            }
        }
        if missing.0 > 0 {
            warnings.push(format!(
                "{semantic} is missing in {} primitives: their {} vertices get {}",
                missing.0,
                missing.1,
                if is_color {
                    "ones (opaque white)"
                } else {
                    "zeros"
                }
            ));
        }
        let mut values = Values::with_capacity(kind, bytes.len() / kind.size());
        values.push_le(&bytes);
        Ok(Attribute {
            semantic: semantic.clone(),
            components,
            normalized,
            values,
            corners: None,
        })
    }
}
