//! Bad glTF files, one kind of damage a test: each is refused with an error that names what
//! is wrong and where (JSON path or byte offset), never a panic.

mod gltf_support;

use gltf_support::*;
use lrmesh::io::{gltf, ReadOptions};
use lrmesh::Error;
use serde_json::{json, Value};

/// The error of reading `bytes`, which must be a parse error.
fn error(bytes: &[u8]) -> String {
    match gltf::read(bytes, &ReadOptions::default()) {
        Ok(l) => panic!("read: {} triangles", l.mesh.triangle_count()),
        Err(e @ Error::Parse(_)) => e.to_string(),
        Err(other) => panic!("not a parse error: {other}"),
    }
}

fn assert_error(bytes: &[u8], parts: &[&str]) {
    let e = error(bytes);
    for p in parts {
        assert!(e.contains(p), "`{p}` not in: {e}");
    }
}

/// A one-triangle document over `builder`'s accessors: `attributes` and `extra` fields of the
/// primitive.
fn triangle(attributes: Value, primitive_extra: Value) -> Value {
    let mut primitive = json!({ "attributes": attributes });
    if let Value::Object(extra) = primitive_extra {
        for (k, v) in extra {
            primitive[k] = v;
        }
    }
    json!({
        "meshes": [{ "primitives": [primitive] }],
        "nodes": [{ "mesh": 0 }],
        "scenes": [{ "nodes": [0] }],
    })
}

const TRIANGLE: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

#[test]
fn index_out_of_range() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let i = b.indices(&[0, 1, 5], UNSIGNED_SHORT);
    let doc = triangle(json!({ "POSITION": p }), json!({ "indices": i }));
    assert_error(
        &b.glb(doc),
        &[
            "meshes[0].primitives[0].indices",
            "index 5 at entry 2 is out of range",
            "3 vertices",
        ],
    );
}

#[test]
fn accessor_index_out_of_range() {
    let mut b = Builder::default();
    b.floats(&TRIANGLE, 3);
    let doc = triangle(json!({ "POSITION": 42 }), json!({}));
    assert_error(
        &b.embedded(doc),
        &[
            "attributes.POSITION",
            "index 42 is out of range",
            "1 accessors",
        ],
    );
    let doc = json!({ "scenes": [{ "nodes": [3] }], "nodes": [] });
    assert_error(&b.embedded(doc), &["scenes[0].nodes[0]", "index 3"]);
    let mut doc = triangle(json!({ "POSITION": 0 }), json!({ "material": 2 }));
    doc["materials"] = json!([{}]);
    assert_error(&b.embedded(doc), &["primitives[0].material", "index 2"]);
}

#[test]
fn wrong_types_for_a_semantic() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let two = b.floats(&[0.0; 6], 2);
    let bytes3 = b.integers(&[0; 9], UNSIGNED_BYTE, 3, false);
    let bytes2 = b.integers(&[0; 6], UNSIGNED_BYTE, 2, false);
    let floats = b.floats(&[0.0, 1.0, 2.0], 1);
    let cases = [
        (
            json!({ "POSITION": p, "NORMAL": two }),
            json!({}),
            "NORMAL must be VEC3 of FLOAT",
        ),
        (
            json!({ "POSITION": bytes3 }),
            json!({}),
            "POSITION must be VEC3 of FLOAT",
        ),
        (
            json!({ "POSITION": p, "COLOR_0": two }),
            json!({}),
            "COLOR_0 must be VEC3 or VEC4",
        ),
        (
            json!({ "POSITION": p, "TEXCOORD_0": bytes2 }),
            json!({}),
            "TEXCOORD_0 must be VEC2 of FLOAT, or of normalized",
        ),
        (
            json!({ "POSITION": p }),
            json!({ "indices": floats }),
            "indices must be SCALAR of unsigned",
        ),
    ];
    for (attributes, extra, message) in cases {
        let e = error(&b.glb(triangle(attributes, extra)));
        assert!(e.contains(message), "{e}");
        assert!(
            e.contains("meshes[0].primitives[0]") && e.contains("accessors["),
            "{e}"
        );
    }
    // Normalized floats are no type at all.
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    b.accessors[p]["normalized"] = json!(true);
    assert_error(
        &b.glb(doc),
        &["accessors[0].normalized", "cannot be normalized"],
    );
}

#[test]
fn missing_buffer() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let doc = b.document(triangle(json!({ "POSITION": p }), json!({})), None);
    let text = serde_json::to_vec(&doc).unwrap();
    assert_error(&text, &["buffers[0]", "no `uri` and no GLB BIN chunk"]);
    // A GLB without its BIN chunk.
    assert_error(&glb(&text, &[]), &["buffers[0]", "no `uri`"]);
}

#[test]
fn short_buffer() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let mut doc = b.document(triangle(json!({ "POSITION": p }), json!({})), None);
    doc["buffers"][0]["byteLength"] = json!(1000);
    doc["bufferViews"][0]["byteLength"] = json!(1000);
    let text = serde_json::to_vec(&doc).unwrap();
    assert_error(
        &glb(&text, &b.bin),
        &["buffers[0]", "byteLength is 1000", "only 36 bytes"],
    );
}

#[test]
fn buffer_view_out_of_range() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    b.views[0]["byteOffset"] = json!(20);
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    assert_error(
        &b.glb(doc),
        &[
            "bufferViews[0]",
            "byteOffset 20 + byteLength 36",
            "outside buffers[0] of 36 bytes",
        ],
    );
    b.views[0]["byteOffset"] = json!(0);
    b.views[0]["byteStride"] = json!(6);
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    assert_error(&b.glb(doc), &["bufferViews[0].byteStride", "multiple of 4"]);
    b.views[0]["byteStride"] = json!(8);
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    assert_error(
        &b.glb(doc),
        &["accessors[0]", "byteStride 8 is smaller than the 12-byte"],
    );
}

#[test]
fn accessor_outside_its_view() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    b.accessors[p]["count"] = json!(4);
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    assert_error(
        &b.glb(doc.clone()),
        &[
            "accessors[0]",
            "4 elements of 12 bytes",
            "bufferViews[0] of 36 bytes",
        ],
    );
    // A count that overflows every multiplication.
    b.accessors[p]["count"] = json!(u64::MAX);
    assert_error(&b.glb(doc), &["accessors[0]", "do not fit"]);
}

#[test]
fn non_finite_values() {
    for bad in [f32::NAN, f32::INFINITY] {
        let mut b = Builder::default();
        let p = b.floats(&[0.0, 0.0, 0.0, 1.0, bad, 0.0, 0.0, 1.0, 0.0], 3);
        let doc = triangle(json!({ "POSITION": p }), json!({}));
        assert_error(
            &b.glb(doc),
            &["accessors[0]", "element 1 has a non-finite component"],
        );
    }
    // Finite values that a node's scale takes beyond f32.
    let mut b = Builder::default();
    let p = b.floats(&[0.0, 0.0, 0.0, 3e38, 0.0, 0.0, 0.0, 1.0, 0.0], 3);
    let mut doc = triangle(json!({ "POSITION": p }), json!({}));
    doc["nodes"][0]["scale"] = json!([10.0, 1.0, 1.0]);
    assert_error(
        &b.glb(doc),
        &[
            "meshes[0].primitives[0]",
            "vertex 1 to a non-finite position",
        ],
    );
}

#[test]
fn bad_base64() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    let uri = format!("data:application/octet-stream;base64,{}", base64(&b.bin)).replace('A', "*");
    let text = serde_json::to_vec(&b.document(doc.clone(), Some(uri))).unwrap();
    assert_error(&text, &["buffers[0].uri", "invalid base64 character `*`"]);
    let text = serde_json::to_vec(&b.document(doc, Some("data:text/plain,abc".into()))).unwrap();
    assert_error(&text, &["buffers[0].uri", "not base64"]);
}

#[test]
fn bad_glb_header_and_chunks() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let good = b.glb(triangle(json!({ "POSITION": p }), json!({})));
    assert!(gltf::read(&good, &ReadOptions::default()).is_ok());
    let mut v1 = good.clone();
    v1[4] = 1;
    assert_error(&v1, &["byte offset 4", "version 1"]);
    let mut long = good.clone();
    long.extend_from_slice(&[0; 4]);
    assert_error(&long, &["byte offset 8", "declared length"]);
    assert_error(&good[..10], &["byte offset 0", "header needs 12"]);
    let mut chunk = good.clone();
    chunk[12..16].copy_from_slice(&10_000u32.to_le_bytes());
    assert_error(&chunk, &["byte offset 12", "chunk 0", "runs past the end"]);
    let mut kind = good.clone();
    kind[16..20].copy_from_slice(b"BIN\0");
    assert_error(&kind, &["byte offset 16", "must be JSON"]);
    let mut cut = good.clone();
    let len = cut.len();
    cut.truncate(len - 30);
    let total = cut.len() as u32;
    cut[8..12].copy_from_slice(&total.to_le_bytes());
    assert_error(&cut, &["chunk 1", "runs past the end"]);
    assert_error(
        &glb(b"{ not json", &[]),
        &["byte offset 20", "invalid JSON"],
    );
}

#[test]
fn bad_documents() {
    assert_error(
        b"{\"asset\": {\"version\": \"2.0\"},\n \"meshes\": [}",
        &["glTF line 2", "invalid JSON"],
    );
    assert_error(b"[1, 2]", &["the document", "expected an object"]);
    assert_error(b"{}", &["`asset` is missing"]);
    assert_error(
        br#"{"asset": {"version": "1.0"}}"#,
        &["asset.version", "only glTF 2.x"],
    );
    assert_error(
        br#"{"asset": {"version": "2.0"}, "accessors": [{"componentType": 5124, "count": 1, "type": "SCALAR"}]}"#,
        &["accessors[0].componentType", "unknown component type 5124"],
    );
    assert_error(
        br#"{"asset": {"version": "2.0"}, "accessors": [{"componentType": 5126, "count": -1, "type": "SCALAR"}]}"#,
        &["accessors[0].count", "non-negative integer"],
    );
    assert_error(
        br#"{"asset": {"version": "2.0"}, "extensionsRequired": ["KHR_draco_mesh_compression"]}"#,
        &["extensionsRequired[0]", "KHR_draco_mesh_compression"],
    );
}

#[test]
fn bad_sparse_accessors() {
    for (indices, count, message) in [
        (
            vec![2u8, 1],
            2,
            "entry 1 is 1: sparse indices must increase strictly",
        ),
        (vec![0u8, 3], 2, "entry 1 is 3"),
        (
            vec![0u8, 1, 2, 0],
            4,
            "count 4 exceeds the accessor's count 3",
        ),
    ] {
        let mut b = Builder::default();
        let view = b.view(&f32_bytes(&TRIANGLE), None);
        let iv = b.view(&indices, None);
        let vv = b.view(&f32_bytes(&[1.0; 12]), None);
        let p = b.accessor(json!({
            "bufferView": view, "componentType": FLOAT, "count": 3, "type": "VEC3",
            "sparse": { "count": count,
                "indices": { "bufferView": iv, "componentType": UNSIGNED_BYTE },
                "values": { "bufferView": vv } },
        }));
        let doc = triangle(json!({ "POSITION": p }), json!({}));
        assert_error(&b.glb(doc), &["accessors[0].sparse", message]);
    }
}

#[test]
fn node_cycles() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let mut doc = triangle(json!({ "POSITION": p }), json!({}));
    doc["nodes"] = json!([{ "mesh": 0, "children": [1] }, { "children": [0] }]);
    assert_error(&b.glb(doc.clone()), &["nodes[0]", "reached twice"]);
    doc["nodes"] = json!([{ "mesh": 0 }]);
    doc["scenes"] = json!([{ "nodes": [0, 0] }]);
    assert_error(&b.glb(doc), &["nodes[0]", "reached twice from scenes[0]"]);
}

#[test]
fn output_beyond_what_the_input_backs() {
    // A data-less accessor of a billion zeros: refused before anything is allocated.
    let mut b = Builder::default();
    let p =
        b.accessor(json!({ "componentType": FLOAT, "count": 1_000_000_000u64, "type": "VEC3" }));
    let doc = triangle(json!({ "POSITION": p }), json!({}));
    assert_error(&b.embedded(doc), &["accessors[0]", "would grow past"]);
    // A mesh of 9,999 vertices instanced by 2,000 nodes, each placed elsewhere: a small
    // document asking for far more than its size.
    let mut b = Builder::default();
    let q = b.floats(&[0.0; 29_997], 3);
    let n = 2_000;
    let nodes: Vec<Value> = (0..n)
        .map(|i| json!({ "mesh": 0, "translation": [i as f64, 0.0, 0.0] }))
        .collect();
    let mut doc = triangle(json!({ "POSITION": q }), json!({}));
    doc["nodes"] = json!(nodes);
    doc["scenes"] = json!([{ "nodes": (0..n).collect::<Vec<_>>() }]);
    let e = error(&b.glb(doc));
    assert!(e.contains("would grow past"), "{e}");
}

#[test]
fn bad_primitives() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let two = b.floats(&[0.0; 4], 2);
    let four = b.indices(&[0, 1, 2, 0], UNSIGNED_BYTE);
    let cases = [
        (
            json!({ "POSITION": p }),
            json!({ "indices": four }),
            "TRIANGLES with 4 indices",
        ),
        (
            json!({ "POSITION": p }),
            json!({ "mode": 7 }),
            "mode: unknown mode 7",
        ),
        (
            json!({ "POSITION": p, "TEXCOORD_0": two }),
            json!({}),
            "has 2 elements, another attribute of the primitive 3",
        ),
    ];
    for (attributes, extra, message) in cases {
        assert_error(
            &b.glb(triangle(attributes, extra)),
            &["meshes[0].primitives[0]", message],
        );
    }
}

#[test]
fn names_from_the_file_are_printed_safely() {
    let mut b = Builder::default();
    let p = b.floats(&TRIANGLE, 3);
    let weird = b.floats(&[0.0; 3], 1);
    let doc = triangle(json!({ "POSITION": p, "\u{1b}[31mRED": weird }), json!({}));
    let loaded = gltf::read(&b.glb(doc), &ReadOptions::default()).unwrap();
    let text = loaded.warnings.join("\n");
    assert!(text.contains("\\u{1b}[31mRED"), "{text}");
    assert!(!text.chars().any(|c| c.is_control() && c != '\n'), "{text}");
    let doc = triangle(json!({ "POSITION": p, "\u{7}BELL": 99 }), json!({}));
    let e = error(&b.glb(doc));
    assert!(!e.chars().any(char::is_control), "{e}");
}
