//! Writing containers: a mesh in, `.lrm` bytes out (layout: `spec/FORMAT.md`), from the mesh
//! alone or from a corner table or LR already built, into a buffer or any writer.
//!
//! Encoding is deterministic: the same mesh and options give the same bytes, and no Cargo
//! feature changes them.

mod assemble;
mod attributes;
mod connectivity;
mod options;
mod positions;

pub use assemble::{assemble, write_sections, SectionBytes};
pub use options::{Connectivity, EncodeOptions, Orient, DEFAULT_LEVEL};

use crate::corner_table::CornerTable;
use crate::error::{Error, Result};
use crate::format::layout::{write_fields, MeshRecord};
use crate::format::{Flags, Tag};
use crate::lr::{CompactLr, CompactOptions, Lr, Zipper};
use crate::mesh::{is_in_order, Order, Oriented, LOCALITY_TRIANGLES};
use crate::strips::Cts;
use crate::Mesh;
use connectivity::Encoded;

/// `mesh` with the values of the attributes `options` quantize replaced by what decoding
/// the container gives back (FORMAT.md §3.9.1): what [`encode`] then
/// [`Container::to_mesh`](crate::Container::to_mesh) return, up to the merging of values
/// equal after quantization. The other attributes are unchanged.
///
/// # Errors
/// [`Error::InvalidArgument`] for quantization bits out of range.
pub fn dequantized(mesh: &Mesh, options: &EncodeOptions) -> Result<Mesh> {
    let mut out = mesh.clone();
    for a in &mut out.attributes {
        let Some(q) = attributes::quantizer(a, options)? else {
            continue;
        };
        let n = usize::from(a.components);
        if let crate::mesh::Values::F32(values) = &mut a.values {
            let mut levels = [0u32; 4];
            for v in values.chunks_exact_mut(n.max(1)) {
                q.quantize(v, &mut levels);
                let back = q.dequantize(&levels);
                v.copy_from_slice(&back[..n]);
            }
        }
    }
    Ok(out)
}

/// A connectivity already built, so that encoding builds nothing twice.
#[derive(Debug, Clone, Copy)]
pub enum Built<'a> {
    /// A corner table of the mesh: the connectivity `options` choose is built from it.
    Table(&'a CornerTable),
    /// A standard LR of the mesh, stored as it is.
    Lr(&'a Lr),
    /// A bit-efficient LR of the mesh, stored as it is.
    LrCompact(&'a CompactLr),
    /// A Zipper of the mesh, stored as it is.
    Zipper(&'a Zipper),
    /// Strips of the mesh, stored as they are.
    Strips(&'a Cts),
}

/// Encodes `mesh` with the connectivity `options` choose.
///
/// # Errors
/// [`Error::InvalidMesh`] for a mesh that breaks [`Mesh::validate`];
/// [`Error::Unsupported`] when it exceeds the representation's limits.
pub fn encode(mesh: &Mesh, options: &EncodeOptions) -> Result<Vec<u8>> {
    Ok(assemble(&table_sections(mesh, options)?))
}

/// Encodes `mesh` as [`encode`], taking it: when no attribute, part or kept order needs them
/// again, its triangles are freed as soon as the corner table holds them (12 bytes per
/// triangle off the peak of a large encode).
///
/// # Errors
/// As [`encode`].
pub fn encode_owned(mut mesh: Mesh, options: &EncodeOptions) -> Result<Vec<u8>> {
    let needs_triangles = !mesh.attributes.is_empty()
        || mesh.parts.is_some()
        || options.keep_order
        || repairs(options.orient);
    if needs_triangles {
        return encode(&mesh, options);
    }
    mesh.validate()?;
    if let Some(order) = valid_encoding_order(&mesh, options) {
        mesh = order.apply_valid(&mesh);
    }
    // The triangles become the table's `V`: held once, not twice.
    let owned = std::mem::take(&mut mesh.triangles);
    let triangles = owned.len();
    let table = CornerTable::from_triangles(mesh.positions.len(), owned)?;
    if options.orient == Orient::Auto && table.conversion().cut_inconsistent_edges > 0 {
        // The repaired mesh is made from the triangles, given back by the table (the mesh is
        // in its encoding order now).
        mesh.triangles = table.input_triangles();
        return Ok(assemble(&table_sections_of_built(
            &mesh, table, options, None,
        )?));
    }
    Ok(assemble(&sections(
        &mesh,
        triangles,
        Source::Table(table),
        options,
        None,
    )?))
}

/// Encodes `mesh` into `out` (a file, a socket, a buffer), as [`encode`].
///
/// # Errors
/// As [`encode`], and [`Error::Io`] (with an empty path) when writing fails.
pub fn encode_to(
    out: &mut impl std::io::Write,
    mesh: &Mesh,
    options: &EncodeOptions,
) -> Result<()> {
    let sections = table_sections(mesh, options)?;
    write_sections(out, &sections).map_err(|source| Error::Io {
        path: Default::default(),
        source,
    })
}

/// Encodes the repaired mesh of `oriented` ([`crate::mesh::orient`] of the mesh to store),
/// as [`encode`] with an [`Orient`] option does, for a caller that has oriented the mesh
/// already (to report what changed) and need not do it twice: its reversed triangles go to
/// `FLIP` when `options.orient` is [`Orient::Repair`], and nowhere otherwise.
///
/// # Errors
/// As [`encode`].
pub fn encode_oriented(oriented: &Oriented, options: &EncodeOptions) -> Result<Vec<u8>> {
    Ok(assemble(&oriented_sections(oriented, options)?))
}

/// Every section of `mesh`, with its corner table built here, oriented first when `options`
/// ask.
fn table_sections(mesh: &Mesh, options: &EncodeOptions) -> Result<Vec<SectionBytes>> {
    mesh.validate()?;
    if repairs(options.orient) {
        return oriented_sections(&crate::mesh::orient(mesh), options);
    }
    table_sections_of(mesh, options, None)
}

/// Whether `orient` always repairs the orientation.
fn repairs(orient: Orient) -> bool {
    matches!(orient, Orient::Repair | Orient::RepairAndKeep)
}

/// The order the encoders put `mesh` in before building its connectivity: a cache-friendly
/// one ([`Order`]) for a mesh of [`LOCALITY_TRIANGLES`] or more whose own order need not be
/// kept, so that the construction walks memory in order; `None` when the mesh is encoded in
/// its own order (small, kept, or in that order already). A tool that reports on what
/// `encode` builds (sizes, rings) builds from `order.apply(mesh)` too
/// ([`in_encoding_order`]).
///
/// # Errors
/// [`Error::InvalidMesh`] for a mesh that would take an order but breaks [`Mesh::validate`].
pub fn encoding_order(mesh: &Mesh, options: &EncodeOptions) -> Result<Option<Order>> {
    if !takes_order(mesh, options) {
        return Ok(None);
    }
    Order::of(mesh).map(Some)
}

/// `mesh` in the order [`encoding_order`] gives, the original freed once the copy is made;
/// the encoders keep the order of what this returns.
///
/// # Errors
/// As [`encoding_order`].
pub fn in_encoding_order(mesh: Mesh, options: &EncodeOptions) -> Result<Mesh> {
    Ok(match encoding_order(&mesh, options)? {
        Some(order) => order.apply_valid(&mesh),
        None => mesh,
    })
}

/// Whether [`encoding_order`] gives an order.
fn takes_order(mesh: &Mesh, options: &EncodeOptions) -> bool {
    mesh.triangles.len() >= LOCALITY_TRIANGLES && !options.keep_order && !is_in_order(mesh)
}

/// [`encoding_order`] of a valid mesh.
fn valid_encoding_order(mesh: &Mesh, options: &EncodeOptions) -> Option<Order> {
    takes_order(mesh, options).then(|| Order::of_valid(mesh))
}

/// Every section of `mesh` (validated) from the corner table built here, owned so that it
/// is freed once the connectivity is built; `flipped` as [`sections`] takes it. A large mesh
/// is put in a cache-friendly order first ([`encoding_order`]).
fn table_sections_of(
    mesh: &Mesh,
    options: &EncodeOptions,
    flipped: Option<&[bool]>,
) -> Result<Vec<SectionBytes>> {
    if let Some(order) = valid_encoding_order(mesh, options) {
        let mesh = order.apply_valid(mesh);
        let flipped = flipped.map(|f| order.per_triangle(f));
        drop(order);
        return ordered_sections(&mesh, options, flipped.as_deref());
    }
    ordered_sections(mesh, options, flipped)
}

/// [`table_sections_of`] in the mesh's order.
fn ordered_sections(
    mesh: &Mesh,
    options: &EncodeOptions,
    flipped: Option<&[bool]>,
) -> Result<Vec<SectionBytes>> {
    table_sections_of_built(mesh, CornerTable::from_mesh(mesh)?, options, flipped)
}

/// The sections of `mesh` from its corner table `table`, `flipped` as [`sections`] takes it;
/// with [`Orient::Auto`], when the table cut an inconsistent edge, those of the repaired mesh
/// too, the smaller kept.
fn table_sections_of_built(
    mesh: &Mesh,
    table: CornerTable,
    options: &EncodeOptions,
    flipped: Option<&[bool]>,
) -> Result<Vec<SectionBytes>> {
    let inconsistent = table.conversion().cut_inconsistent_edges;
    let n = mesh.triangles.len();
    let as_given = sections(mesh, n, Source::Table(table), options, flipped)?;
    if options.orient != Orient::Auto || inconsistent == 0 {
        return Ok(as_given);
    }
    // [`Orient::Auto`]: the repaired mesh too, its reversed triangles in `FLIP`.
    let oriented = crate::mesh::orient(mesh);
    if oriented.flipped_count() == 0 {
        return Ok(as_given);
    }
    let table = CornerTable::from_mesh(&oriented.mesh)?;
    let flipped = Some(oriented.flipped.as_slice());
    let repaired = sections(&oriented.mesh, n, Source::Table(table), options, flipped)?;
    // The files' lengths but for their common header: payloads and section table entries.
    let bytes = |s: &[SectionBytes]| {
        s.iter()
            .map(|s| s.2.len() + crate::format::ENTRY_LEN)
            .sum::<usize>()
    };
    Ok(match bytes(&repaired) < bytes(&as_given) {
        true => repaired,
        false => as_given,
    })
}

/// Every section of the repaired mesh of `oriented`, with `FLIP` as [`encode_oriented`] says.
fn oriented_sections(oriented: &Oriented, options: &EncodeOptions) -> Result<Vec<SectionBytes>> {
    let mesh = &oriented.mesh;
    mesh.validate()?;
    let record = options.orient == Orient::Repair && oriented.flipped_count() > 0;
    let flipped = record.then_some(oriented.flipped.as_slice());
    table_sections_of(mesh, options, flipped)
}

/// Encodes `mesh` with a connectivity already built from it (`built` must come from this
/// mesh: a corner table of its triangles, or an LR or strips built from such a table).
/// With [`Built::Table`], `options.connectivity` chooses what is built; otherwise `built`
/// decides and the construction options are not used.
///
/// # Errors
/// As [`encode`]; [`Error::InvalidArgument`] when `built` does not have the mesh's vertex
/// and triangle counts, or when `options` ask to orient (the connectivity is built already:
/// orient the mesh first with [`crate::mesh::orient`]).
pub fn encode_built(mesh: &Mesh, built: Built, options: &EncodeOptions) -> Result<Vec<u8>> {
    mesh.validate()?;
    if repairs(options.orient) {
        return Err(Error::InvalidArgument(
            "a connectivity built already cannot be oriented: orient the mesh before building"
                .into(),
        ));
    }
    let triangles = mesh.triangles.len();
    let source = Source::Built(built);
    Ok(assemble(&sections(mesh, triangles, source, options, None)?))
}

/// A connectivity built from a corner table for its section (one per encode: the size of the
/// variants does not matter).
#[allow(clippy::large_enum_variant)]
enum Made {
    Lr(Lr),
    LrCompact(CompactLr),
    Zipper(Zipper),
    Strips(Cts),
}

/// The connectivity `options` choose, built from `table`; `None` for Edgebreaker, whose
/// section is written from the table itself.
fn make(table: &CornerTable, options: &EncodeOptions) -> Result<Option<Made>> {
    Ok(match options.connectivity {
        Connectivity::Lr => Some(Made::Lr(Lr::build(table, &options.lr)?)),
        Connectivity::Strips => Some(Made::Strips(Cts::build(table, &options.strips)?)),
        Connectivity::LrCompact => Some(Made::LrCompact(CompactLr::build(
            table,
            &CompactOptions {
                lr: options.lr,
                periods: options.periods.clone(),
                tip_bases: options.tip_bases,
            },
        )?)),
        Connectivity::Zipper => {
            let seeds = zipper_seeds(options.level, table.v_table().len() / 3);
            Some(Made::Zipper(Zipper::build_smallest(
                table,
                &options.lr,
                seeds,
            )?))
        }
        Connectivity::Edgebreaker => None,
    })
}

/// How many ring seeds the `zipper` encoder tries at `level` on a mesh of `triangles`
/// ([`Zipper::build_smallest`]): one below the default level; from it, as many as fit a
/// budget of constructions, 2^19 triangles' worth at level 6 and twice as many at each
/// level above, at most 32 at level 6 and twice as many at each level above. So the search
/// costs a small mesh at most about one 2^19-triangle build at the default level, and a mesh
/// of 2^19 triangles or more is built once.
pub fn zipper_seeds(level: u8, triangles: usize) -> u32 {
    let Some(above) = level.checked_sub(DEFAULT_LEVEL) else {
        return 1;
    };
    let above = u32::from(above.min(3));
    let budget = (1usize << 19) << above;
    (budget / triangles.max(1)).clamp(1, 32 << above) as u32
}

/// The section of a connectivity built here.
fn made_section(made: &Made, shape: bool) -> Encoded {
    match made {
        Made::Lr(lr) => connectivity::lr_section(lr, shape),
        Made::LrCompact(lr) => connectivity::lr_compact_section(lr, shape),
        Made::Zipper(z) => connectivity::zipper_section(z, shape),
        Made::Strips(cts) => connectivity::strips_section(cts, shape),
    }
}

/// The connectivity section of `built`; with `shape`, the triangles as a reader numbers
/// them (for attributes and parts).
fn connectivity(
    built: Built,
    options: &EncodeOptions,
    shape: bool,
    predicted: bool,
) -> Result<Encoded> {
    Ok(match built {
        Built::Lr(lr) => connectivity::lr_section(lr, shape),
        Built::LrCompact(lr) => connectivity::lr_compact_section(lr, shape),
        Built::Zipper(z) => connectivity::zipper_section(z, shape),
        Built::Strips(cts) => connectivity::strips_section(cts, shape),
        Built::Table(table) => match make(table, options)? {
            Some(made) => made_section(&made, shape),
            None => connectivity::edgebreaker_section(table, shape, predicted)?,
        },
    })
}

/// Where the connectivity comes from: built already, or a corner table the encoding owns and
/// frees once the connectivity section is made, before the geometry (24 bytes per triangle).
enum Source<'a> {
    Built(Built<'a>),
    Table(CornerTable),
}

/// Every section of the container, in the order this crate writes them; with `flipped`
/// (per input triangle), the reversed ones in `FLIP`.
fn sections(
    mesh: &Mesh,
    triangles: usize,
    source: Source,
    options: &EncodeOptions,
    flipped: Option<&[bool]>,
) -> Result<Vec<SectionBytes>> {
    // Predicted values need the triangles as a reader numbers them, Edgebreaker's decoder
    // table; attributes and parts need them on every kind.
    let predicted = options.level > 0;
    let edgebreaker_shape = mesh.has_per_corner_attributes()
        || mesh.parts.is_some()
        || (predicted && !mesh.attributes.is_empty());
    // Edgebreaker is written from a corner table; every other kind from what it builds.
    let edgebreaker = options.connectivity == Connectivity::Edgebreaker
        && matches!(source, Source::Table(_) | Source::Built(Built::Table(_)));
    let shape = if edgebreaker {
        edgebreaker_shape
    } else {
        edgebreaker_shape || !mesh.attributes.is_empty()
    };
    let (encoded, kept) = match source {
        Source::Built(built) => {
            let kept = match built {
                Built::Table(t) => t.kept_aside(),
                Built::Lr(lr) => lr.kept_aside(),
                Built::LrCompact(lr) => lr.kept_aside(),
                Built::Zipper(z) => z.kept_aside(),
                Built::Strips(cts) => cts.kept_aside(),
            };
            (
                connectivity(built, options, shape, predicted)?,
                kept.to_vec(),
            )
        }
        Source::Table(table) => {
            let kept = table.kept_aside().to_vec();
            let encoded = if options.connectivity == Connectivity::Lr {
                // The table goes into the builder, which frees it as it goes.
                connectivity::lr_section(&Lr::build_owned(table, &options.lr)?, shape)
            } else if let Some(made) = make(&table, options)? {
                // The table is freed before the section is written, the built connectivity
                // after.
                drop(table);
                made_section(&made, shape)
            } else {
                connectivity::edgebreaker_section(&table, shape, predicted)?
            };
            (encoded, kept)
        }
    };
    let kept = kept.as_slice();
    let m = encoded.input_vertex.len() as u32;
    let per_vertex = |v: u32| encoded.input_vertex[v as usize] as usize;
    let triangle_total = encoded.input_triangle.len() + kept.len();
    if encoded
        .input_vertex
        .iter()
        .any(|&v| v as usize >= mesh.positions.len())
        || triangle_total != triangles
    {
        return Err(Error::InvalidArgument(format!(
            "the connectivity given has {triangle_total} triangles over input vertices up to {}, the mesh {} triangles and {} vertices",
            encoded.input_vertex.iter().max().map_or(0, |&v| v + 1),
            triangles,
            mesh.positions.len()
        )));
    }

    // The first container vertex of each input vertex is its original; later ones are copies.
    let mut primary = vec![u32::MAX; mesh.positions.len()];
    for (v, &input) in encoded.input_vertex.iter().enumerate() {
        if primary[input as usize] == u32::MAX {
            primary[input as usize] = v as u32;
        }
    }
    let copies: Vec<(u32, u32)> = (0..m)
        .map(|v| (v, primary[per_vertex(v)]))
        .filter(|&(v, original)| original != v)
        .collect();

    let mut sections: Vec<SectionBytes> = Vec::new();
    let meta = serde_json::to_vec(&options.metadata)
        .map_err(|e| Error::Internal(format!("metadata does not serialise: {e}")))?;
    sections.push((Tag::META, Flags::NONE, meta));

    let output_vertices = m - copies.len() as u32;
    let record = MeshRecord {
        vertices: m,
        output_vertices,
        triangles: encoded.input_triangle.len() as u32,
        kept: kept.len() as u32,
        kind: encoded.kind,
        reserved: 0,
    };
    sections.push((Tag::MESH, Flags::REQUIRED, record.to_bytes()));
    let container_positions: Vec<[f32; 3]> =
        (0..m).map(|v| mesh.positions[per_vertex(v)]).collect();
    sections.push((
        Tag::GEOM,
        Flags::REQUIRED,
        positions::section(
            &container_positions,
            options,
            encoded.decoder_table.as_ref(),
        )?,
    ));

    if !mesh.attributes.is_empty() || mesh.parts.is_some() {
        let corners = attributes::Corners::new(mesh, &encoded, kept, &primary)?;
        if !mesh.attributes.is_empty() {
            // Predicted values need the positions a reader decodes: Edgebreaker's, coded.
            let decoded = encoded
                .decoder_table
                .as_ref()
                .filter(|_| options.level > 0)
                .map(|table| (positions::as_decoded(&container_positions, options), table));
            let payload = attributes::attr_section(
                mesh,
                &corners,
                &encoded.input_vertex,
                options,
                decoded.as_ref().map(|(p, t)| (p.as_slice(), *t)),
            )?;
            sections.push((Tag::ATTR, Flags::NONE, payload));
        }
        let runs = encoded.kind == crate::format::Kind::EDGEBREAKER && options.level > 0;
        if let Some(payload) = attributes::part_section(mesh, &corners, runs, options.level > 0)? {
            sections.push((Tag::PART, Flags::NONE, payload));
        }
    }

    sections.push((encoded.tag, Flags::REQUIRED, encoded.payload));

    // Edgebreaker from level 1: copies and kept triangles range coded (FORMAT.md §3.6.1,
    // §3.7.1), when shorter.
    let coding = encoded.kind == crate::format::Kind::EDGEBREAKER && options.level > 0;
    if !copies.is_empty() {
        let mut p = Vec::new();
        write_fields(&mut p, &[copies.len() as u32]);
        for &(copy, original) in &copies {
            write_fields(&mut p, &[copy, original]);
        }
        let stream = (coding && crate::format::copied::codable(&copies))
            .then(|| crate::format::copied::encode(&copies));
        let coded = (Tag::COPC, copies.len(), stream);
        sections.push(plain_or_coded((Tag::COPY, p), coded));
    }
    if !kept.is_empty() {
        let tris: Vec<[u32; 3]> = kept
            .iter()
            .map(|(_, tri)| tri.map(|x| primary[x as usize]))
            .collect();
        let mut p = Vec::new();
        write_fields(&mut p, &[kept.len() as u32]);
        for tri in &tris {
            write_fields(&mut p, tri);
        }
        let stream = coding.then(|| crate::format::kept::encode(&tris));
        sections.push(plain_or_coded(
            (Tag::KEPT, p),
            (Tag::KEPC, kept.len(), stream),
        ));
    }
    if options.keep_order {
        // Output order: non-copy vertices in container order; the connectivity's triangles in
        // its order, then the kept ones.
        let mut p = Vec::new();
        write_fields(&mut p, &[output_vertices, triangle_total as u32]);
        let vertices: Vec<u32> = (0..m)
            .filter(|&v| primary[per_vertex(v)] == v)
            .map(|v| per_vertex(v) as u32)
            .collect();
        write_fields(&mut p, &vertices);
        write_fields(&mut p, &encoded.input_triangle);
        let kept_inputs: Vec<u32> = kept.iter().map(|&(input, _)| input).collect();
        write_fields(&mut p, &kept_inputs);
        sections.push((Tag::PERM, Flags::NONE, p));
    }
    if let Some(flipped) = flipped {
        // Output triangles (FORMAT.md §4 step 2, before PERM): the connectivity's, then kept.
        let inputs = encoded.input_triangle.iter().copied();
        let inputs = inputs.chain(kept.iter().map(|&(input, _)| input));
        let mut p = Vec::new();
        write_fields(&mut p, &[triangle_total as u32]);
        let mut bits = vec![0u8; triangle_total.div_ceil(8)];
        for (j, input) in inputs.enumerate() {
            if flipped[input as usize] {
                bits[j / 8] |= 1 << (j % 8);
            }
        }
        p.extend(bits);
        sections.push((Tag::FLIP, Flags::REQUIRED, p));
    }
    Ok(sections)
}

/// The required section `plain`, or `coded` (its tag, its entry count `k` and a range-coded
/// stream of the entries) when that is shorter: u32 `k`, u32 `n`, then the `n` bytes of the
/// stream (`COPC`, `KEPC`).
fn plain_or_coded(
    (plain, payload): (Tag, Vec<u8>),
    (coded, k, stream): (Tag, usize, Option<Vec<u8>>),
) -> SectionBytes {
    const _: () = assert!(crate::format::copied::HEADER_LEN == 8);
    const _: () = assert!(crate::format::kept::HEADER_LEN == 8);
    match stream {
        Some(stream) if 8 + stream.len() < payload.len() => {
            let mut c = Vec::new();
            write_fields(&mut c, &[k as u32, stream.len() as u32]);
            c.extend_from_slice(&stream);
            (coded, Flags::REQUIRED, c)
        }
        _ => (plain, Flags::REQUIRED, payload),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The order is taken from 2^17 triangles on, and never when the input's order is kept.
    #[test]
    fn large_meshes_take_the_locality_order_unless_theirs_is_kept() {
        let options = EncodeOptions::default();
        let keep = EncodeOptions {
            keep_order: true,
            ..EncodeOptions::default()
        };
        let large = crate::generate::irregular_torus(LOCALITY_TRIANGLES as u32, 1);
        let small = crate::generate::irregular_torus(LOCALITY_TRIANGLES as u32 - 1000, 1);
        assert!(small.triangles.len() < LOCALITY_TRIANGLES);
        assert!(encoding_order(&large, &options).unwrap().is_some());
        assert!(encoding_order(&large, &keep).unwrap().is_none());
        assert!(encoding_order(&small, &options).unwrap().is_none());
        // One in that order already is encoded as it is.
        let ordered = in_encoding_order(large.clone(), &options).unwrap();
        assert_ne!(ordered, large);
        assert!(encoding_order(&ordered, &options).unwrap().is_none());
        // A large mesh that is not valid gets an error, not an order.
        let mut broken = large.clone();
        broken.triangles[7][1] = broken.positions.len() as u32;
        assert!(matches!(
            encoding_order(&broken, &options),
            Err(Error::InvalidMesh(_))
        ));
    }
}
