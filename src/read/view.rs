//! The validated container: every table borrowed from the buffer, the connectivity answering
//! the corner operators in place (Edgebreaker decoded once into a corner table), the
//! attributes read on demand, and the map back to the input's vertex ids.

use super::attributes::{self, AttributeView};
use super::parts::{self, PartsView};
use super::positions::{self, Positions};
use super::{counts, edgebreaker, lr, lr_compact, strips, zipper, Limits, Sections};
use crate::corner_table::CornerTable;
use crate::error::{Result, Rule};
use crate::format::{Kind, Metadata};
use crate::ids::{Corner, Triangle, Vertex};
use crate::lr::{CompactTables, LrLayout, LrTables, ZipperTables};
use crate::mesh::{ComponentType, Semantic};
use crate::ops::CornerOps;
use crate::strips::CtsTables;
use crate::words::{LeUnits, LeWords, Stored, Words};

/// The connectivity of a validated container. It implements [`CornerOps`] for every kind,
/// so that a caller need not match on it; the variants give the representation's own
/// tables for what only they offer.
///
/// # Panics
/// Its operators panic when given a corner that is not a corner of the mesh (see
/// [`Connectivity::is_corner`]), rather than answer something made up; vertex and triangle
/// ids must be below the bounds.
// The Zipper's tables are the largest variant (twenty slices and lists): a container holds
// one view, and a box would put a pointer between every operator and its tables.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum Connectivity<'a> {
    /// Standard LR tables, answering the corner operators on the buffer.
    Lr(LrTables<LeWords<'a>>),
    /// Edgebreaker, decoded when the container was opened: triangles in decode order.
    Edgebreaker(Box<CornerTable>),
    /// Constrained triangle strips and the adjacent-strips table, answering the corner
    /// operators on the buffer.
    Strips(CtsTables<LeWords<'a>>),
    /// Bit-efficient LR tables, answering the corner operators on the buffer.
    LrCompact(CompactTables<LeWords<'a>, LeUnits<'a>>),
    /// Zipper tables, answering the corner operators on the buffer.
    Zipper(ZipperTables<LeWords<'a>>),
}

/// Runs `$body` with `$t` bound to the variant's tables.
macro_rules! each {
    ($self:expr, $t:ident => $body:expr) => {
        match $self {
            Connectivity::Lr($t) => $body,
            Connectivity::Edgebreaker($t) => $body,
            Connectivity::Strips($t) => $body,
            Connectivity::LrCompact($t) => $body,
            Connectivity::Zipper($t) => $body,
        }
    };
}

impl Connectivity<'_> {
    /// The connectivity kind.
    pub fn kind(&self) -> Kind {
        match self {
            Connectivity::Lr(_) => Kind::LR,
            Connectivity::Edgebreaker(_) => Kind::EDGEBREAKER,
            Connectivity::Strips(_) => Kind::STRIPS,
            Connectivity::LrCompact(_) => Kind::LR_COMPACT,
            Connectivity::Zipper(_) => Kind::ZIPPER,
        }
    }

    /// The connectivity kind's name: `lr`, `edgebreaker`, `strips`, `lr-compact` or
    /// `zipper`.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// Whether `c` is a corner of the mesh (ids of some kinds have gaps).
    pub fn is_corner(&self, c: Corner) -> bool {
        match self {
            Connectivity::Lr(t) => t.is_corner(c),
            Connectivity::Edgebreaker(t) => c.0 < 3 * t.triangle_id_bound(),
            Connectivity::Strips(t) => t.is_corner(c),
            Connectivity::LrCompact(t) => t.is_corner(c),
            Connectivity::Zipper(t) => t.is_corner(c),
        }
    }

    fn checked(&self, c: Corner) -> Corner {
        assert!(
            self.is_corner(c),
            "corner {c} is not a corner of this {} mesh",
            self.name()
        );
        c
    }

    /// Number of triangles the connectivity holds.
    pub fn triangle_count(&self) -> u64 {
        self.triangles().count() as u64
    }
}

impl CornerOps for Connectivity<'_> {
    fn vertex_id_bound(&self) -> u32 {
        each!(self, t => t.vertex_id_bound())
    }
    fn triangle_id_bound(&self) -> u32 {
        each!(self, t => t.triangle_id_bound())
    }
    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        let it: Box<dyn Iterator<Item = Triangle> + '_> = each!(self, t => Box::new(t.triangles()));
        it
    }
    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        let it: Box<dyn Iterator<Item = Vertex> + '_> = each!(self, t => Box::new(t.vertices()));
        it
    }
    fn vertex(&self, c: Corner) -> Vertex {
        let c = self.checked(c);
        each!(self, t => t.vertex(c))
    }
    fn triangle(&self, c: Corner) -> Triangle {
        let c = self.checked(c);
        each!(self, t => t.triangle(c))
    }
    fn next(&self, c: Corner) -> Corner {
        let c = self.checked(c);
        each!(self, t => t.next(c))
    }
    fn prev(&self, c: Corner) -> Corner {
        let c = self.checked(c);
        each!(self, t => t.prev(c))
    }
    fn opposite(&self, c: Corner) -> Option<Corner> {
        let c = self.checked(c);
        each!(self, t => t.opposite(c))
    }
    // Swings check their corner once: the defaults would check it, its `next` and the
    // opposite again (three slot decodes of an LR layout for one answer).
    fn swing(&self, c: Corner) -> Option<Corner> {
        let c = self.checked(c);
        each!(self, t => t.swing(c))
    }
    fn unswing(&self, c: Corner) -> Option<Corner> {
        let c = self.checked(c);
        each!(self, t => t.unswing(c))
    }
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        assert!(v.0 < self.vertex_id_bound(), "vertex {v} out of range");
        each!(self, t => t.vertex_corner(v))
    }
    fn any_corner(&self, v: Vertex) -> Option<Corner> {
        assert!(v.0 < self.vertex_id_bound(), "vertex {v} out of range");
        each!(self, t => t.any_corner(v))
    }
    fn triangle_corner(&self, t: Triangle) -> Corner {
        each!(self, x => x.triangle_corner(t))
    }
}

/// A container whose tables are borrowed from the buffer, the connectivity answering the
/// corner operators in place. Made by [`super::open`] (the file is well formed: every answer
/// is in range) or [`super::open_verified`] (every rule holds: the answers are the mesh's).
#[derive(Debug, Clone)]
pub struct Container<'a> {
    /// The container's sections.
    pub sections: Sections<'a>,
    /// Whether every rule was checked ([`super::open_verified`] or [`Container::verify`]).
    verified: bool,
    /// The metadata, if the file has a `META` section.
    pub metadata: Option<Metadata>,
    pub(super) connectivity: Connectivity<'a>,
    /// Container vertices (copies included).
    pub(super) vertices: u32,
    pub(super) positions: Positions<'a>,
    pub(super) attributes: Vec<AttributeView<'a>>,
    pub(super) parts: Option<PartsView<'a>>,
    /// `(copy, original)` pairs, copies increasing.
    pub(super) copies: Stored<'a>,
    /// Kept-aside triangles, three vertices each.
    pub(super) kept: Stored<'a>,
    /// Vertex then triangle permutations to the input order.
    pub(super) perm: Option<(LeWords<'a>, LeWords<'a>)>,
    /// Output triangles the writer reversed (`FLIP`), increasing.
    pub(super) flips: Option<Vec<u32>>,
    pub(super) output_vertices: u32,
    pub(super) triangles: u32,
}

impl<'a> Container<'a> {
    /// Checks the sections' contents: every rule after V10 but the semantic ones
    /// (FORMAT.md §5.1), then with `verify` the semantic ones, so that both levels report the
    /// same first error on a file that is not well formed.
    pub(super) fn new(
        sections: Sections<'a>,
        limits: &Limits,
        verify: bool,
    ) -> Result<Container<'a>> {
        let mut container = Container::well_formed(sections, limits)?;
        if verify {
            container.check_semantic_rules()?;
        }
        Ok(container)
    }

    /// The semantic rules, on a well-formed container: the decoded values of blocked
    /// positions, then the connectivity's (its tables read again with every rule, which
    /// also derives the LR boundary flag from them).
    fn check_semantic_rules(&mut self) -> Result<()> {
        let m = self.vertices;
        if let Positions::Blocked(_) = self.positions {
            positions::positions(&self.sections, m, true)?;
        }
        match &mut self.connectivity {
            Connectivity::Lr(t) => *t = lr::lr_tables(&self.sections, m, true)?.0,
            Connectivity::LrCompact(t) => {
                *t = lr_compact::lr_compact_tables(&self.sections, m, true)?.0
            }
            Connectivity::Zipper(t) => *t = zipper::zipper_tables(&self.sections, m, true)?.0,
            Connectivity::Strips(t) => *t = strips::strips_tables(&self.sections, m, true)?,
            // Decoded whole when opened: the decoder checks everything it builds.
            Connectivity::Edgebreaker(_) => {}
        }
        self.verified = true;
        Ok(())
    }

    /// Every rule after V10 but the semantic ones.
    fn well_formed(sections: Sections<'a>, limits: &Limits) -> Result<Container<'a>> {
        let metadata = counts::metadata(&sections, limits)?;
        let (mesh, mesh_fields) = counts::mesh_record(&sections)?;
        let m = mesh.vertices;
        let (encoding, stored) = positions::positions(&sections, m, false)?;
        let legacy = counts::attributes(&sections, m)?;
        let (connectivity, held) = match mesh.kind {
            Kind::LR => {
                let (tables, held) = lr::lr_tables(&sections, m, false)?;
                (Connectivity::Lr(tables), held)
            }
            Kind::STRIPS => {
                let tables = strips::strips_tables(&sections, m, false)?;
                let held = tables.triangle_count() as u64;
                (Connectivity::Strips(tables), held)
            }
            Kind::LR_COMPACT => {
                let (tables, held) = lr_compact::lr_compact_tables(&sections, m, false)?;
                (Connectivity::LrCompact(tables), held)
            }
            Kind::ZIPPER => {
                let (tables, held) = zipper::zipper_tables(&sections, m, false)?;
                (Connectivity::Zipper(tables), held)
            }
            _ => {
                // Decoded whole: the decoder checks everything it builds.
                let table = edgebreaker::edgebreaker_table(&sections, m, limits)?;
                let held = table.triangle_id_bound() as u64;
                (Connectivity::Edgebreaker(Box::new(table)), held)
            }
        };
        let positions = match stored {
            Some(p) => p,
            None => {
                let table = match &connectivity {
                    Connectivity::Edgebreaker(t) => Some(&**t),
                    _ => None,
                };
                positions::decode(&sections, encoding, table)?
            }
        };
        if held != mesh.triangles as u64 {
            return Err(mesh_fields.err(
                8,
                Rule(12),
                format!(
                    "{} triangles, the connectivity holds {held}",
                    mesh.triangles
                ),
            ));
        }
        let copies = counts::copies(&sections, m, mesh.kind == Kind::EDGEBREAKER)?;
        let copy_count = (copies.count() / 2) as u32;
        if m - copy_count != mesh.output_vertices {
            return Err(mesh_fields.err(
                4,
                Rule(12),
                format!(
                    "{} output vertices, but {m} vertices with {copy_count} copies",
                    mesh.output_vertices
                ),
            ));
        }
        let kept = counts::kept(&sections, m, mesh.kind == Kind::EDGEBREAKER)?;
        if (kept.count() / 3) as u32 != mesh.kept {
            return Err(mesh_fields.err(
                12,
                Rule(12),
                format!(
                    "{} kept triangles, section KEPT or KEPC holds {}",
                    mesh.kept,
                    kept.count() / 3
                ),
            ));
        }
        let total = mesh.triangles as u64 + mesh.kept as u64;
        let perm = counts::perm(&sections, mesh.output_vertices, total)?;
        let flips = counts::flips(&sections, total)?;
        let cx = attributes::Context {
            vertices: m,
            connectivity: &connectivity,
            positions: &positions,
            kept: mesh.kept,
            kept_triangles: &kept,
            copies: &copies,
            holds: Default::default(),
            slots: Default::default(),
        };
        let attributes = attributes::attributes(&sections, legacy, &cx)?;
        let parts = parts::parts(&sections, &cx)?;
        Ok(Container {
            sections,
            verified: false,
            metadata,
            connectivity,
            vertices: m,
            positions,
            attributes,
            parts,
            copies,
            kept,
            perm,
            flips,
            output_vertices: mesh.output_vertices,
            triangles: mesh.triangles,
        })
    }

    /// Checks the rules that [`super::open`] leaves out (FORMAT.md §5.1: opposites that face
    /// each other, vertex corners that start their fans, the LR flags), so that the
    /// operators' answers are the mesh's and every walk ends within its fan. Does nothing on
    /// a container opened with [`super::open_verified`].
    ///
    /// # Errors
    /// As [`super::open_verified`].
    pub fn verify(&mut self) -> Result<()> {
        if !self.verified {
            self.check_semantic_rules()?;
        }
        Ok(())
    }

    /// Whether every rule has been checked ([`super::open_verified`], [`Container::verify`]).
    pub fn is_verified(&self) -> bool {
        self.verified
    }

    /// The connectivity, answering the corner operators for every kind.
    pub fn connectivity(&self) -> &Connectivity<'a> {
        &self.connectivity
    }

    /// The connectivity kind.
    pub fn kind(&self) -> Kind {
        self.connectivity.kind()
    }

    /// The standard LR tables, when the container holds them.
    pub fn lr(&self) -> Option<&LrTables<LeWords<'a>>> {
        match &self.connectivity {
            Connectivity::Lr(lr) => Some(lr),
            _ => None,
        }
    }

    /// The bit-efficient LR tables, when the container holds them.
    pub fn lr_compact(&self) -> Option<&CompactTables<LeWords<'a>, LeUnits<'a>>> {
        match &self.connectivity {
            Connectivity::LrCompact(lr) => Some(lr),
            _ => None,
        }
    }

    /// The Zipper tables, when the container holds them.
    pub fn zipper(&self) -> Option<&ZipperTables<LeWords<'a>>> {
        match &self.connectivity {
            Connectivity::Zipper(z) => Some(z),
            _ => None,
        }
    }

    /// The constrained strips and adjacent-strips table, when the container holds them.
    pub fn strips(&self) -> Option<&CtsTables<LeWords<'a>>> {
        match &self.connectivity {
            Connectivity::Strips(strips) => Some(strips),
            _ => None,
        }
    }

    /// Number of connectivity triangles (kept-aside ones not included).
    pub fn triangle_count(&self) -> u32 {
        self.triangles
    }

    /// Number of degenerate triangles kept aside.
    pub fn kept_triangle_count(&self) -> u32 {
        (self.kept.count() / 3) as u32
    }

    /// Container vertex `k` of kept-aside triangle `j`.
    ///
    /// # Panics
    /// When `j` is not below [`Container::kept_triangle_count`] or `k > 2`.
    pub fn kept_vertex(&self, j: u32, k: usize) -> Vertex {
        assert!(
            k < 3 && j < self.kept_triangle_count(),
            "kept corner {j}:{k} out of range"
        );
        Vertex(self.kept.at(3 * j as usize + k))
    }

    /// Number of container vertices: those of the connectivity, copies included.
    pub fn connectivity_vertex_count(&self) -> u32 {
        self.vertices
    }

    /// Number of vertices once copies are merged back (the decoded mesh's).
    pub fn output_vertex_count(&self) -> u32 {
        self.output_vertices
    }

    /// Whether positions are stored quantized (lossy).
    pub fn is_quantized(&self) -> bool {
        self.positions.is_quantized()
    }

    /// The positions as stored: their encoding, and the grid of a lossy one.
    pub fn stored_positions(&self) -> &Positions<'a> {
        &self.positions
    }

    /// Whether the file stores the input's vertex and triangle order.
    pub fn keeps_order(&self) -> bool {
        self.perm.is_some()
    }

    fn check_vertex(&self, v: Vertex) -> usize {
        assert!(
            v.0 < self.vertices,
            "vertex {v} out of range ({} vertices)",
            self.vertices
        );
        v.idx()
    }

    /// The position of container vertex `v` (dequantized when stored as 16-bit: FORMAT.md
    /// §3.3).
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn position(&self, v: Vertex) -> [f32; 3] {
        let i = self.check_vertex(v);
        self.positions.get(i)
    }

    /// Every container vertex's position, in container vertex order.
    pub fn positions(&self) -> Vec<[f32; 3]> {
        (0..self.vertices)
            .map(|v| self.position(Vertex(v)))
            .collect()
    }

    /// The value of per-vertex attribute `semantic` at container vertex `v` as f32s;
    /// `None` when the file has no such attribute or has it per corner.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    fn vertex_value(&self, semantic: &Semantic, v: Vertex) -> Option<[f32; 4]> {
        self.check_vertex(v);
        self.attribute(semantic)
            .filter(|a| !a.per_corner)
            .map(|a| a.value_f32(v.0))
    }

    /// The normal of container vertex `v`, when the file has normals per vertex.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn normal(&self, v: Vertex) -> Option<[f32; 3]> {
        self.vertex_value(&Semantic::Normal, v)
            .map(|x| [x[0], x[1], x[2]])
    }

    /// The texture coordinates (set 0) of container vertex `v`, when the file has them
    /// per vertex.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn texcoord(&self, v: Vertex) -> Option<[f32; 2]> {
        self.vertex_value(&Semantic::TexCoord(0), v)
            .map(|x| [x[0], x[1]])
    }

    /// The RGBA color (set 0) of container vertex `v` as bytes, when the file has RGBA
    /// bytes per vertex.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn color(&self, v: Vertex) -> Option<[u8; 4]> {
        self.check_vertex(v);
        let a = self.attribute(&Semantic::Color(0))?;
        if a.per_corner || a.component_type != ComponentType::U8 || a.components != 4 {
            return None;
        }
        let b = a.value_bytes(v.0)?;
        Some([b[0], b[1], b[2], b[3]])
    }

    /// The vertex of the decoded mesh ([`Container::to_mesh`]) that container vertex `v`
    /// becomes: copies merge into their originals, and with a stored input order this is the
    /// input's vertex id.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn output_vertex(&self, v: Vertex) -> u32 {
        self.check_vertex(v);
        let pairs = self.copies.count() / 2;
        let copy_at = |i: usize| self.copies.at(2 * i);
        // Copies below x, by binary search over the increasing copy ids.
        let below = |x: u32| {
            let (mut lo, mut hi) = (0, pairs);
            while lo < hi {
                let mid = (lo + hi) / 2;
                if copy_at(mid) < x {
                    lo = mid + 1;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        let i = below(v.0);
        let original = if i < pairs && copy_at(i) == v.0 {
            self.copies.at(2 * i + 1)
        } else {
            v.0
        };
        let output = original - below(original) as u32;
        match self.perm {
            Some((vertices, _)) => vertices.at(output as usize),
            None => output,
        }
    }

    /// The input's id of container vertex `v`, when the file stores the input order
    /// (`--keep-order`); `None` otherwise, since the order is then not recorded.
    ///
    /// # Panics
    /// When `v` is not below [`Container::connectivity_vertex_count`].
    pub fn input_vertex(&self, v: Vertex) -> Option<u32> {
        let output = self.output_vertex(v);
        self.perm.map(|_| output)
    }
}
