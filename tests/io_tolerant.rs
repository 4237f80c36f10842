//! The readers are tolerant where real files differ from the letter of a format and honest
//! everywhere else: a UTF-8 byte-order mark is skipped, a PLY header line with no known
//! keyword (Blender 2.4's `Created by Blender3D 247 ...`) is skipped with a warning, random
//! bytes are never an empty mesh, and no message prints a raw control byte.

mod common;

use common::io_helpers::*;
use lrmesh::io::{read_mesh, read_mesh_bytes, MeshFormat, ReadOptions};
use lrmesh::{Error, Location};

const BOM: &[u8] = b"\xEF\xBB\xBF";

fn with_bom(text: &[u8]) -> Vec<u8> {
    [BOM, text].concat()
}

/// A reader's error message or warnings hold no control character (the escapes, such as
/// `\u{1b}`, are printable).
#[track_caller]
fn printable(message: &str) {
    assert!(
        !message.chars().any(char::is_control),
        "a control character in: {message:?}"
    );
}

#[test]
fn byte_order_mark_is_skipped_in_every_text_format() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let ply = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let stl = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    for (format, text) in [
        (MeshFormat::Obj, &obj[..]),
        (MeshFormat::Off, &off[..]),
        (MeshFormat::Ply, &ply[..]),
        (MeshFormat::Stl, &stl[..]),
    ] {
        let plain = read(text, format);
        let marked = read(&with_bom(text), format);
        assert_eq!(marked.mesh, plain.mesh, "{format}");
        assert_eq!(marked.mesh.triangle_count(), 1, "{format}");
        assert_eq!(marked.warnings, plain.warnings, "{format}");
    }
    // The case: a BOM before `v` was read as an unknown statement, and the face then
    // pointed past the vertices.
    let mut tail = obj.to_vec();
    tail.splice(0..0, b"# comment\n".iter().copied());
    assert_eq!(
        read(&with_bom(&tail), MeshFormat::Obj).mesh.vertex_count(),
        3
    );
    // Lines are still counted from the start of the file.
    let e = parse_err(&with_bom(b"v 0 0 0\nv 1 x 0\n"), MeshFormat::Obj);
    assert_eq!(e.location, Location::Line(2));
    // Only at the start: elsewhere it is content (here an unknown keyword, shown escaped).
    let l = read(&[&obj[..], BOM, b"v 1 1 1\n"].concat(), MeshFormat::Obj);
    assert_eq!(l.mesh.vertex_count(), 3);
    assert!(l.warnings[0].contains("`\\u{feff}v`"), "{:?}", l.warnings);
}

/// A small generator, so that the random bytes are the same on every run.
fn random_bytes(seed: u64, len: usize) -> Vec<u8> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..len)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

#[test]
fn random_bytes_are_no_mesh() {
    for seed in 0..200 {
        let bytes = random_bytes(seed, 64 + 37 * seed as usize);
        for format in [
            MeshFormat::Obj,
            MeshFormat::Off,
            MeshFormat::Ply,
            MeshFormat::Stl,
        ] {
            match read_mesh_bytes(&bytes, format, &ReadOptions::default()) {
                Err(Error::Parse(e)) => printable(&e.to_string()),
                Err(e) => panic!("{format} seed {seed}: not a parse error: {e}"),
                Ok(l) => panic!(
                    "{format} seed {seed}: random bytes read as {} vertices",
                    l.mesh.vertex_count()
                ),
            }
        }
    }
    // As a file named .obj, the way the issue found it.
    let path = std::env::temp_dir().join(format!("lrmesh-random-{}.obj", std::process::id()));
    std::fs::write(&path, random_bytes(7, 4096)).unwrap();
    let result = read_mesh(&path, &ReadOptions::default());
    std::fs::remove_file(&path).unwrap();
    match result {
        Err(Error::Parse(e)) => {
            assert_eq!(e.location, Location::Whole, "{e}");
            assert!(e.message.contains("no vertex or face statement"), "{e}");
            printable(&e.to_string());
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn file_content_in_messages_is_escaped() {
    // OBJ: unknown statements (a warning) and a bad number (an error).
    let l = read(
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\x1b[2J\x07bell 1\nx\xff\x9b 2\nf 1 2 3\n",
        MeshFormat::Obj,
    );
    l.warnings.iter().for_each(|w| printable(w));
    let w = l.warnings.join("\n");
    assert!(
        w.contains("`\\u{1b}[2J\\u{7}bell`") && w.contains("`x\\xff\\x9b`"),
        "{w}"
    );
    let e = parse_err(b"v 0 0 \x1b]0;pwned\x07\n", MeshFormat::Obj);
    printable(&e.to_string());
    assert!(e.message.contains("\\u{1b}]0;pwned\\u{7}"), "{e}");
    let e = parse_err(b"\x1b[2J\n", MeshFormat::Obj);
    printable(&e.to_string());
    assert!(e.message.contains("`\\u{1b}[2J`"), "{e}");
    // OFF, STL and PLY errors.
    for (format, text) in [
        (MeshFormat::Off, &b"\x1bOFF\n"[..]),
        (MeshFormat::Stl, b"solid x\nfacet\x1b normal\n"),
        (MeshFormat::Ply, b"ply\nformat \x1b[1m 1.0\nend_header\n"),
        (
            MeshFormat::Ply,
            b"ply\nformat ascii 1.0\nelement \x1b 1\nelement \x1b 2\n",
        ),
    ] {
        let e = parse_err(text, format);
        printable(&e.to_string());
        assert!(e.message.contains("\\u{1b}"), "{e}");
    }
    // PLY warnings: a skipped element and a skipped header line.
    let l = read(
        b"ply\nformat ascii 1.0\nmade\x1b[31m by hand\nelement \x07x 0\nelement vertex 0\n\
property float x\nproperty float y\nproperty float z\nend_header\n",
        MeshFormat::Ply,
    );
    l.warnings.iter().for_each(|w| printable(w));
    let w = l.warnings.join("\n");
    assert!(
        w.contains("`made\\u{1b}[31m by hand`") && w.contains("`\\u{7}x`"),
        "{w}"
    );
}

#[test]
fn blender_ply_header_line_is_skipped_with_a_warning() {
    let text = b"ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org, source file: 'x.blend'\n\
element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar uint vertex_indices\nend_header\n\
0 0 0 \n1 0 0 \n0 1 0 \n3 0 1 2 \n";
    let l = read(text, MeshFormat::Ply);
    assert_eq!(l.mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(
        l.warnings,
        vec![
            "skipped 1 header line(s) with no known keyword, the first on line 3: \
             `Created by Blender3D 247 - www.blender.org, source file: 'x.blend'`"
        ]
    );
    // Everything else stays strict: a known keyword with a bad form is still an error.
    assert_err(
        b"ply\nformat ascii 1.0\nCreated by Blender\nelement vertex\nend_header\n",
        MeshFormat::Ply,
        Location::Line(4),
        &["expected `element <name> <count>`"],
    );
    assert_err(
        b"Created by Blender\nply\n",
        MeshFormat::Ply,
        Location::Line(1),
        &["not a PLY file"],
    );

    // The real file, shortened (corpus/assets/SOURCES.md): 400 faces on 1200 vertices with
    // normals and texture coordinates.
    let path = repo().join("corpus/assets/ply/Wuson_first400faces.ply");
    let l = read(&std::fs::read(path).unwrap(), MeshFormat::Ply);
    assert_eq!(
        (l.mesh.vertex_count(), l.mesh.triangle_count()),
        (1200, 400)
    );
    assert!(
        l.warnings[0].contains("line 3: `Created by Blender3D 247"),
        "{:?}",
        l.warnings
    );
}

#[test]
fn ascii_stl_with_nothing_after_solid_is_an_error() {
    assert_err(
        b"solid but then nothing\n",
        MeshFormat::Stl,
        Location::Line(2),
        &["ends after `solid`"],
    );
    // A declared empty solid is an empty mesh.
    let l = read(b"solid empty\nendsolid empty\n", MeshFormat::Stl);
    assert_eq!(l.mesh.triangle_count(), 0);
}
