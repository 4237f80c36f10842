//! What each fuzz target checks, written once for the targets in `fuzz/` and for the tests
//! that replay their seeds (`corpus/fuzz/<target>/`) and findings
//! (`corpus/fuzz/regressions/<target>/`) on every `cargo test`. Each function panics when
//! the library misbehaves on its input; an input the library rightly refuses passes.
#![allow(missing_docs, clippy::missing_panics_doc)]

mod gltf;
mod obj;
mod round_trip;

pub use gltf::import_gltf;
pub use obj::import_obj;
pub use round_trip::{
    assert_same_in_order, assert_same_up_to_order, rotated, round_trip, round_trip_every_kind,
    round_trip_every_kind_with,
};

use crate::format::Tag;
use crate::io::{read_mesh_bytes, MeshFormat, ReadOptions};
use crate::lr::LrLayout;
use crate::ops::{self, CornerOps, Plane};
use crate::read::{open, open_verified, Limits};
use crate::write::{assemble, encode, Connectivity, EncodeOptions, DEFAULT_LEVEL};
use crate::{generate, Corner, Vertex};

/// The fuzz targets, by name.
pub const TARGETS: [&str; 10] = [
    "import_obj",
    "import_off",
    "import_ply",
    "import_stl",
    "import_gltf",
    "container",
    "container_forged",
    "operators",
    "edgebreaker",
    "round_trip",
];

/// Runs target `name` on `data`.
pub fn run(name: &str, data: &[u8]) {
    match name {
        "import_obj" => import_obj(data),
        "import_off" => import(MeshFormat::Off, data),
        "import_ply" => import(MeshFormat::Ply, data),
        "import_stl" => import(MeshFormat::Stl, data),
        "import_gltf" => import_gltf(data),
        "container" => container(data),
        "container_forged" => container_forged(data),
        "operators" => operators(data),
        "edgebreaker" => edgebreaker(data),
        "round_trip" => round_trip(data),
        other => panic!("no fuzz target {other}"),
    }
}

/// An importer: an error, or a mesh that validates (STL: welded or not alike).
pub fn import(format: MeshFormat, data: &[u8]) {
    let plain = read_mesh_bytes(data, format, &ReadOptions { weld: false });
    if let Ok(l) = &plain {
        l.mesh
            .validate()
            .expect("a mesh the importer returns validates");
    }
    if format == MeshFormat::Stl {
        let welded = read_mesh_bytes(data, format, &ReadOptions { weld: true });
        if let Ok(l) = &welded {
            l.mesh.validate().expect("a welded mesh validates");
        }
        assert_eq!(plain.is_ok(), welded.is_ok());
        if let (Ok(a), Ok(b)) = (&plain, &welded) {
            assert_eq!(a.mesh.triangle_count(), b.mesh.triangle_count());
            assert!(b.mesh.vertex_count() <= a.mesh.vertex_count());
        }
    }
}

/// The Edgebreaker decoder on any bytes: an error, or triangles over declared vertices.
pub fn edgebreaker(data: &[u8]) {
    let limits = crate::edgebreaker::Limits {
        max_triangles: 1 << 20,
        max_vertices: 1 << 20,
    };
    if let Ok(decoded) = crate::edgebreaker::decode(data, &limits) {
        assert!(decoded
            .triangles
            .iter()
            .all(|t| t.iter().all(|&v| v < decoded.vertex_count)));
    }
}

/// Any bytes given to the container reader. [`open`]: an error, or a container whose
/// connectivity, of whatever kind, answers every operator of every corner with an id in range
/// and whose walks end ([`walk_in_range`]), and that decodes to a mesh without panicking.
/// [`open_verified`]: the same error when [`open`] fails; else an error of a semantic rule,
/// or a container that decodes to a mesh that validates and whose opposites face each other
/// (`walk`). (Checksums are skipped under `cfg(fuzzing)` so that the fuzzer reaches the
/// section parsers.)
pub fn container(data: &[u8]) {
    let limits = Limits::default();
    // The headers-only summary: never a panic, and on a well-formed file the summary of
    // the whole open.
    let summary = crate::read::summarize(data, &limits);
    let quick = open(data, &limits);
    if let Ok(file) = &quick {
        match &summary {
            Ok(summary) => assert_eq!(summary, &file.summary(), "summarize and open agree"),
            Err(e) => panic!("summarize refuses a well-formed file: {e}"),
        }
    }
    let verified = open_verified(data, &limits);
    let file = match (quick, &verified) {
        (Err(e), Err(f)) => {
            assert_eq!(
                e.to_string(),
                f.to_string(),
                "both levels report the first error"
            );
            return;
        }
        (Err(e), Ok(_)) => panic!("a file that is not well formed verifies: {e}"),
        (Ok(file), _) => file,
    };
    walk_in_range(&file);
    file.to_mesh();
    match verified {
        Ok(file) => {
            file.to_mesh().validate().expect("a decoded mesh validates");
            walk(&file);
        }
        Err(crate::Error::Format(e)) => assert!(
            crate::read::SEMANTIC_RULES.contains(&e.rule),
            "only a semantic rule fails after a well-formed open: {e}"
        ),
        Err(e) => panic!("only a semantic rule fails after a well-formed open: {e}"),
    }
}

/// A valid container of a small generated mesh, in the kind and with the options the first
/// byte chooses, with fields of one section overwritten by the following bytes (section
/// index, offset, value) and the checksums recomputed: the rules behind the checksums are
/// reached even without `cfg(fuzzing)`.
pub fn container_forged(data: &[u8]) {
    let Some((&choice, edits)) = data.split_first() else {
        return;
    };
    let mut sections = base_sections(choice);
    for edit in edits.chunks_exact(4) {
        let index = edit[0] as usize % sections.len();
        let section = &mut sections[index].2;
        if section.is_empty() {
            continue;
        }
        let at = u16::from_le_bytes([edit[1], edit[2]]) as usize % section.len();
        section[at] = edit[3];
    }
    container(&assemble(&sections));
}

/// A valid container of the LR, bit-efficient LR, Zipper or strips kind ([`forged_base`], its
/// kind from bits 0–2 of the first byte, bits 0–1 modulo 3), whose connectivity section has 16-bit units
/// copied over others (each following 4 bytes: the unit to copy, the unit to overwrite) and
/// its checksums recomputed. Copies of ids, offsets and corners that the file already holds
/// stay in range far more often than random bytes do, so the files reach the operators while
/// well formed but not valid: [`container`] then requires every answer in range, every walk
/// to end, and the verifying reader to name a semantic rule (FORMAT.md §5.1).
pub fn operators(data: &[u8]) {
    let Some((&choice, edits)) = data.split_first() else {
        return;
    };
    let choice = (choice & !3) | ((choice & 3) % 3);
    let mut sections = base_sections(choice);
    let connectivity = [Tag::LRTB, Tag::LRBE, Tag::ZIPR, Tag::STRP];
    let Some(section) = sections
        .iter_mut()
        .find(|s| connectivity.contains(&s.0))
        .map(|s| &mut s.2)
    else {
        return;
    };
    let units = section.len() / 2;
    for edit in edits.chunks_exact(4) {
        let from = u16::from_le_bytes([edit[0], edit[1]]) as usize % units;
        let to = u16::from_le_bytes([edit[2], edit[3]]) as usize % units;
        let unit = [section[2 * from], section[2 * from + 1]];
        section[2 * to..2 * to + 2].copy_from_slice(&unit);
    }
    container(&assemble(&sections));
}

/// The sections of [`forged_base`]`(choice)`, to forge and assemble again.
fn base_sections(choice: u8) -> Vec<crate::write::SectionBytes> {
    let bytes = forged_base(choice);
    open(&bytes, &Limits::default())
        .expect("what we write opens")
        .sections
        .to_section_bytes()
}

/// The valid container [`container_forged`] starts from: bits 0–1 of `choice` the kind
/// (LR, bit-efficient LR or with bit 2 set Zipper, strips, Edgebreaker), 2–3 the torus's size, 4 holes and defects and every fifth triangle reversed (the
/// orientation repaired, section `FLIP`), 5 the input order kept (and for the bit-efficient
/// LR, tip bases: `LRBE` flag `TIP_BASES`), 6 positions and
/// attribute values quantized (predicted values in Edgebreaker; with bit 2 set, level 1:
/// positions in `GEOM` encoding 6), 7 seams and parts (with JSON labels at level 0 on the
/// smallest torus without holes, else coded).
pub fn forged_base(choice: u8) -> Vec<u8> {
    thread_local! {
        /// The bases made so far, by choice: a base is the same every time, and encoding it
        /// was most of a run of the forging targets (the Zipper's from 32 seeds' rings).
        static MADE: std::cell::RefCell<Vec<Option<Vec<u8>>>> =
            std::cell::RefCell::new(vec![None; 256]);
    }
    MADE.with_borrow_mut(|made| {
        made[choice as usize]
            .get_or_insert_with(|| make_forged_base(choice))
            .clone()
    })
}

/// [`forged_base`], made.
fn make_forged_base(choice: u8) -> Vec<u8> {
    let kind = match choice & 3 {
        0 => Connectivity::Lr,
        1 if choice & 4 != 0 => Connectivity::Zipper,
        1 => Connectivity::LrCompact,
        2 => Connectivity::Strips,
        _ => Connectivity::Edgebreaker,
    };
    let mut mesh = generate::torus(3 + (choice >> 2 & 3) as u32, 4);
    if choice & 0x10 != 0 {
        let mut rng = generate::Rng::new(choice as u64);
        generate::punch_holes(&mut mesh, 1, &mut rng);
        generate::add_defects(&mut mesh, 1, &mut rng);
    }
    if choice & 0x80 != 0 {
        with_seams_and_parts(&mut mesh);
    }
    if choice & 0x10 != 0 {
        let every_fifth: Vec<bool> = (0..mesh.triangles.len()).map(|t| t % 5 == 2).collect();
        mesh = crate::mesh::reversed(&mesh, &every_fifth);
    }
    let options = EncodeOptions {
        connectivity: kind,
        orient: if choice & 0x10 != 0 {
            crate::write::Orient::Repair
        } else {
            crate::write::Orient::AsGiven
        },
        keep_order: choice & 0x20 != 0,
        tip_bases: (choice & 0x20 != 0).then_some(true),
        position_bits: (choice & 0x40 != 0).then_some(12),
        // Quantized attribute values (ATTR value encoding 1, or 2 in Edgebreaker) with the
        // quantized positions.
        normal_bits: (choice & 0x40 != 0).then_some(10),
        texcoord_bits: (choice & 0x40 != 0).then_some(12),
        // Level 0 (JSON labels in `PART`, exact or 16-bit raw positions) for the smallest
        // torus with parts and without holes; level 1 (the anchored grid) for half the
        // quantized Edgebreaker files; the default level (coded labels) otherwise.
        level: if choice & 0x9C == 0x80 {
            0
        } else if choice & 0x47 == 0x47 {
            1
        } else {
            DEFAULT_LEVEL
        },
        ..EncodeOptions::default()
    };
    encode(&mesh, &options).expect("a generated mesh encodes")
}

/// Per-corner texture coordinates that break along every third triangle, per-vertex normals,
/// a per-vertex custom attribute and parts: so that forged `ATTR` and `PART` sections are reached.
fn with_seams_and_parts(mesh: &mut crate::Mesh) {
    use crate::mesh::{Attribute, Part, Parts, Semantic, Values};
    let corners: Vec<u32> = (0..3 * mesh.triangles.len() as u32)
        .map(|c| if c % 9 == 0 { c % 4 + 3 } else { c % 3 })
        .collect();
    let uv: Vec<[f32; 2]> = (0..7).map(|i| [i as f32 / 7.0, 0.5]).collect();
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
    let normals: Vec<[f32; 3]> = mesh.positions.iter().map(|p| [p[0], p[1], -p[2]]).collect();
    mesh.attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    mesh.attributes.push(Attribute {
        semantic: Semantic::Custom("weight".into()),
        components: 1,
        normalized: true,
        values: Values::U16((0..mesh.positions.len() as u16).collect()),
        corners: None,
    });
    // Alternating on the smallest torus (packed indices); on the others, five parts of which
    // the first triangle has one and every other triangle another (runs in Edgebreaker).
    let mut parts = Parts::default();
    let n = mesh.triangles.len();
    let ids: Vec<u32> = ["a", "b", "c", "d", "e"]
        .iter()
        .map(|m| {
            parts.intern(Part {
                material: Some((*m).into()),
                ..Part::default()
            })
        })
        .collect();
    for t in 0..n {
        let i = match (n > 30, t) {
            (false, t) => ids[t % 2],
            (true, 0) => ids[4],
            (true, _) => ids[0],
        };
        parts.of_triangle.push(i);
    }
    mesh.parts = Some(parts);
}

/// On a container that is only well formed: every operator of every corner answers an id in
/// range (a corner of the mesh, a vertex below the bound), every attribute index is in range,
/// and stars, valences, normals and contours end; so too through a Zipper's cursor.
pub fn walk_in_range(file: &crate::Container) {
    let mesh = file.connectivity();
    let m = mesh.vertex_id_bound();
    let positions: Vec<[f32; 3]> = (0..m).map(|v| file.position(Vertex(v))).collect();
    ops_in_range(mesh, |c| mesh.is_corner(c), &positions);
    if let Some(tables) = file.zipper() {
        let cursor = tables.cursor();
        ops_in_range(&cursor, |c| cursor.is_corner(c), &positions);
    }
    for c in mesh.corners() {
        for a in file.attributes() {
            assert!(file.value_index(a, c) < a.value_count());
        }
    }
    for v in mesh.vertices() {
        file.output_vertex(v);
    }
}

/// [`walk_in_range`]'s walk of the operators of `mesh`, whose corners are those `is_corner`
/// accepts and whose vertex `v` is at `positions[v]`.
fn ops_in_range<M: CornerOps>(
    mesh: &M,
    is_corner: impl Fn(Corner) -> bool,
    positions: &[[f32; 3]],
) {
    let m = mesh.vertex_id_bound();
    for c in mesh.corners() {
        assert!(mesh.vertex(c).0 < m);
        assert!(mesh.triangle(c).0 < mesh.triangle_id_bound());
        for d in [mesh.next(c), mesh.prev(c)]
            .into_iter()
            .chain(mesh.opposite(c))
            .chain(
                [mesh.swing(c), mesh.unswing(c), mesh.left(c), mesh.right(c)]
                    .into_iter()
                    .flatten(),
            )
        {
            assert!(is_corner(d), "corner {c} leads to {d}, not a corner");
        }
    }
    for v in mesh.vertices() {
        if let Some(c) = mesh.vertex_corner(v) {
            assert!(is_corner(c));
        }
        if let Some(c) = mesh.any_corner(v) {
            assert!(is_corner(c));
        }
        assert!(ops::star(mesh, v).all(&is_corner));
        ops::valence(mesh, v);
        ops::vertex_normal(mesh, positions, v);
    }
    let plane = Plane {
        normal: [0.3, -0.2, 1.0],
        offset: 0.1,
    };
    ops::contours(mesh, positions, &plane);
}

/// Every operator of every corner answers with a valid id, and every attribute a value in
/// range; stars, valences, normals and contours terminate.
fn walk(file: &crate::Container) {
    let mesh = file.connectivity();
    let m = mesh.vertex_id_bound();
    assert_eq!(m, file.connectivity_vertex_count());
    let positions: Vec<[f32; 3]> = (0..m).map(|v| file.position(Vertex(v))).collect();
    for c in mesh.corners() {
        assert!(mesh.vertex(c).0 < m);
        assert!(mesh.is_corner(mesh.next(c)) && mesh.is_corner(mesh.prev(c)));
        if let Some(o) = mesh.opposite(c) {
            assert!(mesh.is_corner(o));
            assert_eq!(mesh.opposite(o), Some(c));
        }
        for d in [mesh.swing(c), mesh.unswing(c), mesh.left(c), mesh.right(c)]
            .into_iter()
            .flatten()
        {
            assert!(mesh.is_corner(d));
        }
    }
    for a in file.attributes() {
        for c in mesh.corners() {
            let i = file.value_index(a, c);
            assert!(i < a.value_count());
            a.value_f32(i);
        }
        for j in 0..file.kept_triangle_count() {
            for k in 0..3 {
                assert!(file.kept_value_index(a, j, k) < a.value_count());
            }
        }
    }
    if let Some(parts) = file.parts() {
        for t in mesh.triangles() {
            let p = file.part_index(t).expect("the file has parts");
            assert!((p as usize) < parts.labels.parts.len());
        }
    }
    let mut corners_seen = 0usize;
    for v in mesh.vertices() {
        let star: Vec<_> = ops::star(mesh, v).collect();
        assert!(star.iter().all(|&c| mesh.vertex(c) == v));
        // Valence and normals start from any corner of `v`: one of the star's, the
        // vertex having one fan ([V38]).
        assert_eq!(mesh.any_corner(v).is_some(), !star.is_empty());
        assert!(mesh.any_corner(v).is_none_or(|c| star.contains(&c)));
        corners_seen += star.len();
        ops::valence(mesh, v);
        ops::vertex_normal(mesh, &positions, v);
    }
    // One fan per vertex ([V38]): the stars meet every corner.
    assert_eq!(corners_seen, mesh.corners().count());
    if let Some(tables) = file.zipper() {
        // A cursor answers as its tables do.
        let cursor = tables.cursor();
        for c in tables.corners() {
            assert_eq!(cursor.vertex(c), tables.vertex(c));
            assert_eq!(cursor.opposite(c), tables.opposite(c));
        }
        for v in tables.vertices() {
            assert_eq!(cursor.vertex_corner(v), tables.vertex_corner(v));
            assert_eq!(cursor.any_corner(v), tables.any_corner(v));
        }
    }
    let plane = Plane {
        normal: [0.3, -0.2, 1.0],
        offset: 0.1,
    };
    ops::contours(mesh, &positions, &plane);
}
