//! A triangle soup with attributes, made from the fuzzer's bytes, encoded with arbitrary
//! options and decoded: the same triangles (oriented, up to rotation) on the same positions
//! with the same attributes, in the input order (the target always keeps it). Encoding never
//! fails on a valid mesh.
#![no_main]

use libfuzzer_sys::arbitrary::{Result, Unstructured};
use libfuzzer_sys::fuzz_target;
use lrmesh::lr::LrOptions;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::Mesh;

fn soup(u: &mut Unstructured) -> Result<(Mesh, EncodeOptions)> {
    let vertices = u.int_in_range(1..=40u32)?;
    let triangles = u.int_in_range(0..=80u32)?;
    let coordinate = |u: &mut Unstructured| -> Result<f32> { Ok(u.int_in_range(-1000..=1000i16)? as f32 / 7.0) };
    let mut mesh = Mesh::default();
    for _ in 0..vertices {
        mesh.positions.push([coordinate(u)?, coordinate(u)?, coordinate(u)?]);
    }
    for _ in 0..triangles {
        let mut t = [0u32; 3];
        for x in &mut t {
            *x = u.int_in_range(0..=vertices - 1)?;
        }
        mesh.triangles.push(t);
    }
    if u.arbitrary()? {
        mesh.normals = Some((0..vertices).map(|v| [v as f32, 0.5, -1.0]).collect());
    }
    if u.arbitrary()? {
        mesh.texcoords = Some((0..vertices).map(|v| [v as f32 / 3.0, 0.25]).collect());
    }
    if u.arbitrary()? {
        mesh.colors = Some((0..vertices).map(|v| [v as u8, 7, 9, 255]).collect());
    }
    let options = EncodeOptions {
        connectivity: if u.arbitrary()? { Connectivity::Edgebreaker } else { Connectivity::Lr },
        lr: LrOptions {
            tries: u.int_in_range(1..=4)?,
            seed: u.arbitrary()?,
        },
        keep_order: true,
        ..EncodeOptions::default()
    };
    Ok((mesh, options))
}

fuzz_target!(|data: &[u8]| {
    let Ok((mesh, options)) = soup(&mut Unstructured::new(data)) else {
        return;
    };
    let bytes = encode(&mesh, &options).expect("a valid mesh encodes");
    let back = open(&bytes, &Limits::default()).expect("what we write opens").to_mesh();
    assert_eq!(back.positions, mesh.positions);
    assert_eq!(back.normals, mesh.normals);
    assert_eq!(back.texcoords, mesh.texcoords);
    assert_eq!(back.colors, mesh.colors);
    assert_eq!(back.triangles.len(), mesh.triangles.len());
    for (got, want) in back.triangles.iter().zip(&mesh.triangles) {
        let rotations = [*want, [want[1], want[2], want[0]], [want[2], want[0], want[1]]];
        assert!(rotations.contains(got), "{got:?} is not a rotation of {want:?}");
    }
});
