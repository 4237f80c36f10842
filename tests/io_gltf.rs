//! glTF 2.0 reading and writing on files made here by hand (`gltf_support`): a textured box
//! split at its seams, several primitives and materials under transformed nodes, every index
//! width, strips and fans, sparse and interleaved accessors, every attribute type; round trips
//! through `.gltf`, `.glb` and, welded, through the container with every connectivity.

mod gltf_support;

use gltf_support::*;
use lrmesh::fuzz_checks::{assert_same_in_order, assert_same_up_to_order, round_trip_every_kind};
use lrmesh::io::{
    self, gltf, read_mesh, read_mesh_bytes, write_mesh_to, Loaded, MeshFormat, ReadOptions,
};
use lrmesh::mesh::{Attribute, ComponentType, Part, Parts, Semantic, Values};
use lrmesh::Mesh;
use serde_json::json;

fn read(bytes: &[u8]) -> Loaded {
    gltf::read(bytes, &ReadOptions::default()).unwrap()
}

fn welded(bytes: &[u8]) -> Mesh {
    gltf::read(bytes, &ReadOptions { weld: true }).unwrap().mesh
}

/// The mesh written in `format` and read back.
fn through(mesh: &Mesh, format: MeshFormat) -> Mesh {
    let mut bytes = Vec::new();
    write_mesh_to(&mut bytes, mesh, format).unwrap();
    read_mesh_bytes(&bytes, format, &ReadOptions::default())
        .unwrap()
        .mesh
}

/// Written as `.gltf` and as `.glb`, read back: the same mesh (seams split), in order.
fn assert_round_trips(mesh: &Mesh) {
    let want = mesh.split_seams();
    for format in [MeshFormat::Gltf, MeshFormat::Glb] {
        assert_same_in_order(&through(mesh, format), &want);
    }
}

/// The position and attribute bytes of corner `k` of triangle `t`, by semantic.
fn corner(m: &Mesh, t: usize, k: usize) -> ([u32; 3], Vec<(Semantic, Vec<u8>)>) {
    let tri = m.triangles[t];
    let mut values: Vec<_> = m
        .attributes
        .iter()
        .map(|a| (a.semantic.clone(), a.corner_bytes(t, k, tri)))
        .collect();
    values.sort();
    (m.positions[tri[k] as usize].map(f32::to_bits), values)
}

/// Same triangles in the same order, each corner with the same position and values, whatever
/// the vertex numbering and binding.
fn assert_same_corners(got: &Mesh, want: &Mesh) {
    assert_eq!(got.triangles.len(), want.triangles.len());
    for t in 0..want.triangles.len() {
        for k in 0..3 {
            assert_eq!(
                corner(got, t, k),
                corner(want, t, k),
                "triangle {t} corner {k}"
            );
        }
    }
}

fn f32_values(a: &Attribute) -> Vec<f32> {
    match &a.values {
        Values::F32(v) => v.clone(),
        other => panic!("{} is {:?}, not f32", a.semantic, other.component_type()),
    }
}

#[test]
fn textured_box_keeps_its_24_split_vertices() {
    let mut b = Builder::default();
    let doc = box_document(&mut b, UNSIGNED_SHORT);
    let expected = split_box();
    for bytes in [b.embedded(doc.clone()), b.glb(doc)] {
        let loaded = read(&bytes);
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        let m = loaded.mesh;
        assert_eq!(m.vertex_count(), 24);
        assert_eq!(m.triangle_count(), 12);
        let flat: Vec<f32> = m.positions.iter().flatten().copied().collect();
        assert_eq!(flat, expected.positions);
        let tris: Vec<u32> = m.triangles.iter().flatten().copied().collect();
        assert_eq!(tris, expected.indices);
        let normal = m.attribute(&Semantic::Normal).unwrap();
        assert!(!normal.is_per_corner());
        assert_eq!(f32_values(normal), expected.normals);
        let uv = m.attribute(&Semantic::TexCoord(0)).unwrap();
        assert_eq!((uv.components, uv.normalized), (2, false));
        assert_eq!(f32_values(uv), expected.texcoords);
        let parts = m.parts.as_ref().unwrap();
        assert_eq!(
            parts.parts,
            vec![Part {
                object: Some("box".into()),
                group: None,
                material: Some("crate".into()),
            }]
        );
        assert_round_trips(&m);
    }
}

#[test]
fn welded_box_has_8_positions_and_every_corner_value() {
    let mut b = Builder::default();
    let doc = box_document(&mut b, UNSIGNED_BYTE);
    let bytes = b.glb(doc);
    let split = read(&bytes).mesh;
    let w = welded(&bytes);
    assert_eq!(w.vertex_count(), 8);
    assert_eq!(w.triangle_count(), 12);
    for semantic in [Semantic::Normal, Semantic::TexCoord(0)] {
        assert!(
            w.attribute(&semantic).unwrap().is_per_corner(),
            "{semantic}"
        );
    }
    assert_same_corners(&w, &split);
    // The welded box is closed: every edge has two triangles.
    let report = lrmesh::TopologyReport::of(&w);
    assert_eq!(report.boundary_edges, 0);
    // Written, the seams are split again: 24 vertices with the same corners.
    for format in [MeshFormat::Gltf, MeshFormat::Glb] {
        let back = through(&w, format);
        assert_eq!(back.vertex_count(), 24);
        assert_same_in_order(&back, &w.split_seams());
        assert_same_corners(&back, &split);
    }
}

#[test]
fn welded_box_keeps_every_corner_through_the_container() {
    let mut b = Builder::default();
    let doc = box_document(&mut b, UNSIGNED_INT);
    let w = welded(&b.embedded(doc));
    round_trip_every_kind(&w, "welded box", |_, _, _| {});
}

/// Two primitives (materials `red` and an unnamed one) of one mesh under a translated parent
/// and a rotated, scaled child; a non-indexed triangle under a mirroring matrix.
fn scene_with_transforms() -> Vec<u8> {
    let mut b = Builder::default();
    let positions = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let normals = [0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.6, 0.0, 0.8];
    let p = b.floats(&positions, 3);
    let n = b.floats(&normals, 3);
    let first = b.indices(&[0, 1, 2], UNSIGNED_BYTE);
    let second = b.indices(&[0, 1, 3, 0, 3, 2], UNSIGNED_SHORT);
    let tri = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], 3);
    let tri_n = b.floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0], 3);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    b.glb(json!({
        "scene": 0,
        "scenes": [{ "nodes": [0, 2] }],
        "nodes": [
            { "name": "root", "translation": [10.0, 0.0, 0.0], "children": [1] },
            { "name": "child", "mesh": 0, "rotation": [0.0, 0.0, h, h], "scale": [2.0, 2.0, 2.0] },
            { "name": "mirror", "mesh": 1,
              "matrix": [-1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 5.0, 1.0] },
        ],
        "meshes": [
            { "name": "pair", "primitives": [
                { "attributes": { "POSITION": p, "NORMAL": n }, "indices": first, "material": 0 },
                { "attributes": { "POSITION": p, "NORMAL": n }, "indices": second, "material": 1 },
            ]},
            { "name": "single", "primitives": [{ "attributes": { "POSITION": tri, "NORMAL": tri_n } }] },
        ],
        "materials": [{ "name": "red" }, {}],
    }))
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-5)
}

#[test]
fn node_transforms_primitives_and_materials() {
    let loaded = read(&scene_with_transforms());
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let m = loaded.mesh;
    // The two primitives share their 4 vertices; the mirrored triangle adds 3.
    assert_eq!(m.vertex_count(), 7);
    assert_eq!(
        m.triangles,
        vec![[0, 1, 2], [0, 1, 3], [0, 3, 2], [4, 6, 5]]
    );
    // child: x' = 10 - 2y, y' = 2x, z' = 2z (a quarter turn about z, scale 2, then the
    // parent's translation).
    let place = |[x, y, z]: [f32; 3]| [10.0 - 2.0 * y, 2.0 * x, 2.0 * z];
    let sources = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    for (v, s) in sources.iter().enumerate() {
        assert!(
            close(m.positions[v], place(*s)),
            "vertex {v}: {:?}",
            m.positions[v]
        );
    }
    // mirror: x' = -x, z' = z + 5; its triangle turns clockwise, so two corners swap.
    assert_eq!(
        m.positions[4..],
        [[-0.0, 0.0, 5.0], [-1.0, 0.0, 5.0], [0.0, 1.0, 5.0]]
    );
    let normals = m.vertex_values::<3>(&Semantic::Normal).unwrap();
    let turned = [
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 0.6, 0.8],
    ];
    for v in 0..4 {
        assert!(close(normals[v], turned[v]), "normal {v}: {:?}", normals[v]);
    }
    assert!(normals[4..].iter().all(|&n| close(n, [0.0, 0.0, 1.0])));
    let parts = m.parts.as_ref().unwrap();
    let labels: Vec<(Option<&str>, Option<&str>)> = (0..4)
        .map(|t| {
            let p = parts.of(t);
            (p.object.as_deref(), p.material.as_deref())
        })
        .collect();
    assert_eq!(
        labels,
        [
            (Some("child"), Some("red")),
            (Some("child"), Some("material1")),
            (Some("child"), Some("material1")),
            (Some("mirror"), None),
        ]
    );
    assert_round_trips(&m);
}

#[test]
fn every_index_width_and_no_indices_give_the_same_triangles() {
    let b0 = split_box();
    let meshes: Vec<Mesh> = [UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT]
        .iter()
        .map(|&t| {
            let mut b = Builder::default();
            let doc = box_document(&mut b, t);
            read(&b.glb(doc)).mesh
        })
        .collect();
    assert_same_in_order(&meshes[1], &meshes[0]);
    assert_same_in_order(&meshes[2], &meshes[0]);
    // Non-indexed: the corners one after another.
    let mut b = Builder::default();
    let corners: Vec<f32> = b0
        .indices
        .iter()
        .flat_map(|&i| b0.positions[3 * i as usize..3 * i as usize + 3].to_vec())
        .collect();
    let p = b.floats(&corners, 3);
    let m = read(&b.embedded(json!({
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": p } }] }],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })))
    .mesh;
    assert_eq!(m.vertex_count(), 36);
    assert_eq!(m.triangle_count(), 12);
    for t in 0..12 {
        for k in 0..3 {
            assert_eq!(m.triangles[t][k] as usize, 3 * t + k);
            let want = meshes[0].positions[meshes[0].triangles[t][k] as usize];
            assert_eq!(m.positions[3 * t + k], want);
        }
    }
    assert_round_trips(&m);
}

#[test]
fn strips_fans_points_and_lines() {
    let mut b = Builder::default();
    let positions: Vec<f32> = (0..5)
        .flat_map(|i| [i as f32, (i % 2) as f32, 0.0])
        .collect();
    let p = b.floats(&positions, 3);
    let strip = b.indices(&[0, 1, 2, 3, 4], UNSIGNED_BYTE);
    let q = b.floats(&positions.iter().map(|x| x + 100.0).collect::<Vec<_>>(), 3);
    let r = b.floats(&[7.0, 7.0, 7.0, 8.0, 8.0, 8.0], 3);
    let loaded = read(&b.embedded(json!({
        "meshes": [{ "primitives": [
            { "attributes": { "POSITION": p }, "indices": strip, "mode": 5 },
            { "attributes": { "POSITION": q }, "mode": 6 },
            { "attributes": { "POSITION": r }, "mode": 1 },
        ]}],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })));
    let m = loaded.mesh;
    assert_eq!(
        m.triangles,
        [
            [0, 1, 2],
            [1, 3, 2],
            [2, 3, 4],
            [6, 7, 5],
            [7, 8, 5],
            [8, 9, 5]
        ]
    );
    // The line's two vertices stay, unreferenced.
    assert_eq!(m.vertex_count(), 12);
    assert_eq!(m.positions[10], [7.0, 7.0, 7.0]);
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("line primitives")),
        "{:?}",
        loaded.warnings
    );
    assert_round_trips(&m);
}

#[test]
fn sparse_and_interleaved_accessors() {
    let mut b = Builder::default();
    // Interleaved: position then normal, 24 bytes a vertex.
    let mut interleaved = Vec::new();
    let base = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    for p in base {
        interleaved.extend_from_slice(&f32_bytes(&p));
        interleaved.extend_from_slice(&f32_bytes(&[0.0, 0.0, 1.0]));
    }
    let view = b.view(&interleaved, Some(24));
    let sparse_indices = b.view(&[1u8, 3], None);
    let sparse_values = b.view(&f32_bytes(&[5.0, 5.0, 5.0, 6.0, 6.0, 6.0]), None);
    let position = b.accessor(json!({
        "bufferView": view, "componentType": FLOAT, "count": 4, "type": "VEC3",
        "sparse": { "count": 2,
            "indices": { "bufferView": sparse_indices, "componentType": UNSIGNED_BYTE },
            "values": { "bufferView": sparse_values } },
    }));
    let normal = b.accessor(json!({
        "bufferView": view, "byteOffset": 12, "componentType": FLOAT, "count": 4, "type": "VEC3",
    }));
    // Sparse without a bufferView: zeros, then one value at index 2.
    let zero_index = b.view(&2u16.to_le_bytes(), None);
    let zero_value = b.view(&f32_bytes(&[0.5]), None);
    let custom = b.accessor(json!({
        "componentType": FLOAT, "count": 4, "type": "SCALAR",
        "sparse": { "count": 1,
            "indices": { "bufferView": zero_index, "componentType": UNSIGNED_SHORT },
            "values": { "bufferView": zero_value } },
    }));
    let indices = b.indices(&[0, 1, 2, 2, 1, 3], UNSIGNED_SHORT);
    let m = read(&b.glb(json!({
        "meshes": [{ "primitives": [{
            "attributes": { "POSITION": position, "NORMAL": normal, "_WEIGHT": custom },
            "indices": indices }] }],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })))
    .mesh;
    assert_eq!(
        m.positions,
        [
            [0.0, 0.0, 0.0],
            [5.0, 5.0, 5.0],
            [0.0, 1.0, 0.0],
            [6.0, 6.0, 6.0]
        ]
    );
    assert_eq!(
        m.vertex_values::<3>(&Semantic::Normal).unwrap(),
        vec![[0.0, 0.0, 1.0]; 4]
    );
    let weight = m.attribute(&Semantic::Custom("WEIGHT".into())).unwrap();
    assert_eq!(f32_values(weight), [0.0, 0.0, 0.5, 0.0]);
    assert_round_trips(&m);
}

#[test]
fn attribute_types_are_kept_as_given() {
    let mut b = Builder::default();
    let p = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], 3);
    let color0 = b.integers(&[255, 0, 0, 0, 255, 0, 0, 0, 255], UNSIGNED_BYTE, 3, true);
    let color1 = b.integers(
        &[65535, 0, 0, 65535, 1, 2, 3, 4, 5, 6, 7, 8],
        UNSIGNED_SHORT,
        4,
        true,
    );
    let uv0 = b.integers(&[0, 0, 65535, 0, 0, 65535], UNSIGNED_SHORT, 2, true);
    let uv1 = b.floats(&[0.25, 0.5, 0.75, 1.0, -1.0, 2.0], 2);
    let temperature = b.floats(&[20.5, 21.0, -3.0], 1);
    let id = b.integers(&[7, 8, 9], UNSIGNED_SHORT, 1, false);
    let signed = b.integers(&[0xff, 1, 0x80, 2, 3, 4], BYTE, 2, true);
    let m = read(&b.glb(json!({
        "meshes": [{ "primitives": [{ "attributes": {
            "POSITION": p, "COLOR_0": color0, "COLOR_1": color1, "TEXCOORD_0": uv0,
            "TEXCOORD_1": uv1, "_TEMPERATURE": temperature, "_ID": id, "_SIGNED": signed } }] }],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })))
    .mesh;
    let shape = |s: Semantic| {
        let a = m.attribute(&s).unwrap();
        (a.values.component_type(), a.components, a.normalized)
    };
    assert_eq!(shape(Semantic::Color(0)), (ComponentType::U8, 3, true));
    assert_eq!(shape(Semantic::Color(1)), (ComponentType::U16, 4, true));
    assert_eq!(shape(Semantic::TexCoord(0)), (ComponentType::U16, 2, true));
    assert_eq!(shape(Semantic::TexCoord(1)), (ComponentType::F32, 2, false));
    assert_eq!(
        shape(Semantic::Custom("TEMPERATURE".into())),
        (ComponentType::F32, 1, false)
    );
    assert_eq!(
        shape(Semantic::Custom("ID".into())),
        (ComponentType::U16, 1, false)
    );
    assert_eq!(
        shape(Semantic::Custom("SIGNED".into())),
        (ComponentType::I8, 2, true)
    );
    assert_eq!(
        m.attribute(&Semantic::Color(0)).unwrap().values,
        Values::U8(vec![255, 0, 0, 0, 255, 0, 0, 0, 255])
    );
    assert_eq!(
        m.attribute(&Semantic::Custom("SIGNED".into()))
            .unwrap()
            .values,
        Values::I8(vec![-1, 1, -128, 2, 3, 4])
    );
    // Without indices, the three vertices are one triangle.
    assert_eq!(m.triangles, [[0, 1, 2]]);
    assert_round_trips(&m);
}

#[test]
fn attributes_missing_or_typed_differently_across_primitives() {
    let mut b = Builder::default();
    let p = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], 3);
    let q = b.floats(&[0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0], 3);
    let bytes = b.integers(&[255, 0, 0, 0, 255, 0, 0, 0, 255], UNSIGNED_BYTE, 3, true);
    let floats = b.floats(
        &[0.5, 0.5, 0.5, 0.25, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        4,
    );
    let uv = b.floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], 2);
    let loaded = read(&b.embedded(json!({
        "meshes": [{ "primitives": [
            { "attributes": { "POSITION": p, "COLOR_0": bytes, "TEXCOORD_0": uv } },
            { "attributes": { "POSITION": q, "COLOR_0": floats } },
        ]}],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })));
    let m = &loaded.mesh;
    let color = m.attribute(&Semantic::Color(0)).unwrap();
    assert_eq!(
        (color.values.component_type(), color.components),
        (ComponentType::F32, 4)
    );
    let c = f32_values(color);
    // u8 red converted to 1.0 with alpha 1; the float colors as given.
    assert_eq!(&c[..4], [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(&c[12..16], [0.5, 0.5, 0.5, 0.25]);
    // The second primitive has no texture coordinates: zeros.
    let uv = f32_values(m.attribute(&Semantic::TexCoord(0)).unwrap());
    assert_eq!(&uv[6..], [0.0; 6]);
    let text = loaded.warnings.join("\n");
    assert!(text.contains("converted to f32"), "{text}");
    assert!(
        text.contains("texcoord0 is missing in 1 primitives"),
        "{text}"
    );
    assert_round_trips(m);
}

#[test]
fn colors_missing_in_a_primitive_are_white() {
    let mut b = Builder::default();
    let p = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], 3);
    let q = b.floats(&[0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0], 3);
    let bytes = b.integers(&[1, 2, 3, 4, 5, 6, 7, 8, 9], UNSIGNED_BYTE, 3, true);
    let m = read(&b.glb(json!({
        "meshes": [{ "primitives": [
            { "attributes": { "POSITION": p, "COLOR_0": bytes } },
            { "attributes": { "POSITION": q } },
        ]}],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })))
    .mesh;
    assert_eq!(
        m.attribute(&Semantic::Color(0)).unwrap().values,
        Values::U8(vec![
            1, 2, 3, 4, 5, 6, 7, 8, 9, 255, 255, 255, 255, 255, 255, 255, 255, 255
        ])
    );
}

#[test]
fn external_buffers_are_read_next_to_the_file() {
    let dir = std::env::temp_dir().join(format!("lrmesh-gltf-ext-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut b = Builder::default();
    let doc = box_document(&mut b, UNSIGNED_SHORT);
    let json = serde_json::to_vec(&b.document(doc, Some("box%20data.bin".into()))).unwrap();
    let path = dir.join("box.gltf");
    std::fs::write(&path, &json).unwrap();
    std::fs::write(dir.join("box data.bin"), &b.bin).unwrap();
    let m = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
    assert_eq!((m.vertex_count(), m.triangle_count()), (24, 12));
    assert_eq!(lrmesh::load(&path).unwrap(), m);
    // From bytes alone, the external buffer cannot be found: the error says so.
    let e = read_mesh_bytes(&json, MeshFormat::Gltf, &ReadOptions::default()).unwrap_err();
    assert!(
        e.to_string().contains("buffers[0]") && e.to_string().contains("external file"),
        "{e}"
    );
    // A resolver supplies it.
    let mut asked = Vec::new();
    let with = gltf::read_with(&json, &ReadOptions::default(), &mut |uri: &str| {
        asked.push(uri.to_string());
        Ok(b.bin.clone())
    })
    .unwrap();
    assert_eq!(with.mesh, m);
    assert_eq!(asked, ["box data.bin"]);
    // A missing file is named.
    std::fs::remove_file(dir.join("box data.bin")).unwrap();
    let e = read_mesh(&path, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("buffers[0]") && e.contains("box data.bin") && e.contains("box.gltf"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn written_files_round_trip_parts_seams_and_quantized_texcoords() {
    // Interleaved parts (the writer groups triangles by part), per-corner attributes, a
    // custom attribute, objects and groups, signed texture coordinates, an unreferenced
    // vertex and a negative zero.
    let positions = vec![
        [-0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [9.0, 9.0, 9.0],
    ];
    let triangles = vec![[0, 1, 2], [2, 1, 3], [0, 2, 3], [3, 1, 0]];
    let mut m = Mesh::new(positions, triangles);
    let uv: Vec<[f32; 2]> = (0..6).map(|i| [i as f32 / 8.0, 0.5]).collect();
    let corners = vec![0, 1, 2, 3, 1, 4, 0, 5, 4, 4, 1, 0];
    m.set_attribute(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
    m.set_attribute(Attribute {
        semantic: Semantic::TexCoord(1),
        components: 2,
        normalized: true,
        values: Values::I16(vec![-32767, 0, 1, 2, 3, 4, 5, 6, 32767, 7]),
        corners: None,
    });
    m.set_attribute(Attribute::per_vertex(
        Semantic::Custom("pressure".into()),
        &[[1.0f32], [2.0], [3.0], [4.0], [5.0]],
    ));
    let mut parts = Parts::default();
    let a = Part {
        object: Some("lid".into()),
        group: Some("top side".into()),
        material: Some("wood".into()),
    };
    let b = Part {
        object: None,
        group: None,
        material: Some("metal".into()),
    };
    for part in [a.clone(), b, a, Part::default()] {
        let i = parts.intern(part);
        parts.of_triangle.push(i);
    }
    m.parts = Some(parts);
    m.validate().unwrap();
    for format in [MeshFormat::Gltf, MeshFormat::Glb] {
        let back = through(&m, format);
        assert_same_up_to_order(&back, &m.split_seams());
        assert_eq!(back.positions[0][0].to_bits(), (-0.0f32).to_bits());
    }
    // In an order the writer keeps (parts in order, one object after another), in order.
    let mut sorted = m.clone();
    let parts = sorted.parts.as_mut().unwrap();
    parts.of_triangle = vec![0, 0, 1, 2];
    sorted.validate().unwrap();
    assert_round_trips(&sorted);
}

#[test]
fn empty_and_point_meshes_round_trip() {
    assert_round_trips(&Mesh::default());
    let points = Mesh::new(vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], Vec::new());
    assert_round_trips(&points);
    let empty = read(&serde_json::to_vec(&json!({ "asset": { "version": "2.0" } })).unwrap());
    assert_eq!(empty.mesh, Mesh::default());
    assert!(empty.warnings.iter().any(|w| w.contains("no triangle")));
}

#[test]
fn stl_is_written_by_extension() {
    let mut b = Builder::default();
    let doc = box_document(&mut b, UNSIGNED_SHORT);
    let m = read(&b.glb(doc)).mesh;
    let mut bytes = Vec::new();
    write_mesh_to(&mut bytes, &m, MeshFormat::Stl).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * 12);
    let back = read_mesh_bytes(&bytes, MeshFormat::Stl, &ReadOptions { weld: true })
        .unwrap()
        .mesh;
    assert_eq!((back.vertex_count(), back.triangle_count()), (8, 12));
    let mut ascii = Vec::new();
    io::stl::write_ascii(&mut ascii, &m).unwrap();
    assert!(ascii.starts_with(b"solid"));
}

/// Every `.gltf` and `.glb` under `corpus/assets/` (see its SOURCES.md).
fn asset_files() -> Vec<std::path::PathBuf> {
    fn walk(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
            {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/assets"),
        &mut out,
    );
    out.sort();
    out
}

/// The JSON of a `.gltf` or `.glb` file, parsed here without the crate's reader.
fn asset_json(bytes: &[u8]) -> serde_json::Value {
    if bytes.starts_with(b"glTF") {
        let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        serde_json::from_slice(&bytes[20..20 + len]).unwrap()
    } else {
        serde_json::from_slice(bytes).unwrap()
    }
}

/// Triangles and vertices by a walk of the JSON written for this test: the default scene's
/// nodes, each mesh instance's triangle primitives (index count / 3), and its vertices once per
/// distinct set of attribute accessors (primitives sharing all accessors share vertices).
fn independent_counts(doc: &serde_json::Value) -> (u64, u64) {
    let scene = doc["scene"].as_u64().unwrap_or(0) as usize;
    let mut stack: Vec<u64> = doc["scenes"][scene]["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_u64().unwrap())
        .collect();
    let (mut triangles, mut vertices) = (0, 0);
    while let Some(n) = stack.pop() {
        let node = &doc["nodes"][n as usize];
        if let Some(children) = node["children"].as_array() {
            stack.extend(children.iter().map(|c| c.as_u64().unwrap()));
        }
        let Some(mesh) = node["mesh"].as_u64() else {
            continue;
        };
        let mut seen = Vec::new();
        for p in doc["meshes"][mesh as usize]["primitives"]
            .as_array()
            .unwrap()
        {
            let count = |a: &serde_json::Value| {
                doc["accessors"][a.as_u64().unwrap() as usize]["count"]
                    .as_u64()
                    .unwrap()
            };
            let attributes = &p["attributes"];
            if !seen.contains(attributes) {
                seen.push(attributes.clone());
                vertices += count(&attributes["POSITION"]);
            }
            assert_eq!(
                p["mode"].as_u64().unwrap_or(4),
                4,
                "the assets hold triangle lists only"
            );
            let corners = match p.get("indices") {
                Some(i) => count(i),
                None => count(&attributes["POSITION"]),
            };
            triangles += corners / 3;
        }
    }
    (triangles, vertices)
}

#[test]
fn corpus_assets_load_count_and_round_trip() {
    let files = asset_files();
    assert!(!files.is_empty(), "no glTF file under corpus/assets");
    for path in &files {
        let name = path.display();
        let loaded = read_mesh(path, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        let m = loaded.mesh;
        let (triangles, vertices) = independent_counts(&asset_json(&std::fs::read(path).unwrap()));
        assert_eq!(m.triangle_count() as u64, triangles, "{name}");
        assert_eq!(m.vertex_count() as u64, vertices, "{name}");
        assert_round_trips(&m);
        // Welded: fewer vertices, the same values at every corner, through glTF and back.
        let w = read_mesh(path, &ReadOptions { weld: true }).unwrap().mesh;
        assert!(w.vertex_count() <= m.vertex_count(), "{name}");
        assert_same_corners(&w, &m);
        assert_same_corners(&through(&w, MeshFormat::Glb), &m);
        eprintln!(
            "{name}: {} triangles, {} vertices, {} welded",
            m.triangle_count(),
            m.vertex_count(),
            w.vertex_count()
        );
    }
}

#[test]
fn corpus_boxes_weld_to_8_positions() {
    let boxes: Vec<_> = asset_files()
        .into_iter()
        .filter(|p| p.to_string_lossy().contains("Box") || p.to_string_lossy().contains("cube"))
        .collect();
    assert!(boxes.len() >= 4, "{boxes:?}");
    for path in boxes {
        let w = read_mesh(&path, &ReadOptions { weld: true }).unwrap().mesh;
        assert_eq!(
            (w.vertex_count(), w.triangle_count()),
            (8, 12),
            "{}",
            path.display()
        );
        assert_eq!(
            lrmesh::TopologyReport::of(&w).boundary_edges,
            0,
            "{}",
            path.display()
        );
        assert!(w.attribute(&Semantic::TexCoord(0)).unwrap().is_per_corner());
    }
}
