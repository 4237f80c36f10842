//! `lrmesh convert`, `encode --weld` and `decode` with glTF and STL on both sides: the welded
//! box keeps every corner through the container, and writing STL says what it drops.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use lrmesh::fuzz_checks::assert_same_up_to_order;
use lrmesh::io::{read_mesh, ReadOptions};

fn lrmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lrmesh"))
        .args(args)
        .output()
        .expect("run lrmesh")
}

fn ok(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{stderr}");
    stderr
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_gltf");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn asset() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus/assets/gltf/BoxTextured-Binary/BoxTextured.glb")
        .to_string_lossy()
        .into_owned()
}

#[test]
fn welded_gltf_through_the_container_and_back_to_glb() {
    let lrm = scratch("box.lrm");
    let glb = scratch("box.glb");
    let (lrm_s, glb_s) = (lrm.to_str().unwrap(), glb.to_str().unwrap());
    ok(&lrmesh(&["encode", &asset(), "-o", lrm_s, "--weld"]));
    let stderr = ok(&lrmesh(&["decode", lrm_s, "-o", glb_s]));
    assert!(!stderr.contains("warning"), "{stderr}");
    let welded = read_mesh(Path::new(&asset()), &ReadOptions { weld: true })
        .unwrap()
        .mesh;
    assert_eq!(welded.vertex_count(), 8);
    let back = read_mesh(&glb, &ReadOptions::default()).unwrap().mesh;
    // The .glb holds the welded box split at its seams again.
    assert_same_up_to_order(&back, &welded.split_seams());
}

#[test]
fn stl_output_warns_about_what_it_drops() {
    let stl = scratch("box.stl");
    let stderr = ok(&lrmesh(&["convert", &asset(), stl.to_str().unwrap()]));
    assert!(
        stderr.contains("STL keeps positions only") && stderr.contains("texcoord0"),
        "{stderr}"
    );
    assert!(stderr.contains("1 part is dropped"), "{stderr}");
    assert_eq!(std::fs::metadata(&stl).unwrap().len(), 84 + 50 * 12);
    let ascii = scratch("box-ascii.stl");
    ok(&lrmesh(&[
        "convert",
        &asset(),
        ascii.to_str().unwrap(),
        "--ascii",
    ]));
    assert!(std::fs::read(&ascii).unwrap().starts_with(b"solid"));
    let back = read_mesh(&ascii, &ReadOptions { weld: true }).unwrap().mesh;
    assert_eq!((back.vertex_count(), back.triangle_count()), (8, 12));
    // --ascii means STL only.
    let out = lrmesh(&[
        "convert",
        &asset(),
        scratch("box.ply").to_str().unwrap(),
        "--ascii",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--ascii applies to STL output only"));
}

#[test]
fn gltf_converts_to_gltf_and_the_weld_option_applies() {
    let gltf = scratch("box.gltf");
    ok(&lrmesh(&[
        "convert",
        &asset(),
        gltf.to_str().unwrap(),
        "--weld",
    ]));
    let text = std::fs::read_to_string(&gltf).unwrap();
    assert!(text.contains("data:application/octet-stream;base64,"));
    let back = read_mesh(&gltf, &ReadOptions::default()).unwrap().mesh;
    assert_eq!((back.vertex_count(), back.triangle_count()), (24, 12));
    let out = lrmesh(&["info", gltf.to_str().unwrap(), "--weld", "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["vertices"], 8);
    assert_eq!(report["boundary_edges"], 0);
}
