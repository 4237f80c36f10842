//! The `lrmesh` command end to end: info, stats, convert, encode, verify, decode.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn lrmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lrmesh"))
        .args(args)
        .output()
        .expect("run lrmesh")
}

fn corpus(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus/meshes")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn info_json_has_the_manifest_figures() {
    let report = json(&lrmesh(&[
        "info",
        &corpus("elephant-with-holes.off"),
        "--json",
    ]));
    assert_eq!(report["vertices"], 2798);
    assert_eq!(report["boundary_loops"], 106);
    assert_eq!(report["genus"], 3);
}

#[test]
fn stats_json_has_lr_keys() {
    let stats = json(&lrmesh(&["stats", &corpus("knot1.off"), "--json"]));
    for key in [
        "triangles",
        "vertices",
        "isolated_vertices",
        "t0_pct",
        "t0w_pct",
        "ti_pct",
        "rpt",
    ] {
        assert!(stats["lr"].get(key).is_some(), "missing lr.{key}");
    }
    assert_eq!(stats["lr"]["triangles"], 6400);
    for key in [
        "bpt",
        "clers_bpt",
        "topology_bytes",
        "c",
        "l",
        "e",
        "r",
        "s",
    ] {
        assert!(
            stats["edgebreaker"].get(key).is_some(),
            "missing edgebreaker.{key}"
        );
    }
    for key in [
        "indices_per_triangle",
        "strips",
        "fans",
        "isolated_triangles",
        "cts_bits_per_triangle",
        "lr_index_rpt",
    ] {
        assert!(stats["strips"].get(key).is_some(), "missing strips.{key}");
    }
}

#[test]
fn encode_verify_decode_round_trip() {
    let lrm = scratch("cheese.lrm");
    let lrm = lrm.to_str().unwrap();
    let out = lrmesh(&["encode", &corpus("cheese.off"), "-o", lrm, "--keep-order"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("corner table"));
    assert!(lrmesh(&["verify", lrm]).status.success());
    let summary = json(&lrmesh(&["info", lrm, "--json"]));
    assert_eq!(summary["triangles"], 17786);
    assert_eq!(summary["keeps_order"], true);
    let off = scratch("cheese-back.off");
    let off = off.to_str().unwrap();
    assert!(lrmesh(&["decode", lrm, "-o", off]).status.success());
    let original = std::fs::read_to_string(corpus("cheese.off")).unwrap();
    let back = json(&lrmesh(&["info", off, "--json"]));
    let want = json(&lrmesh(&["info", &corpus("cheese.off"), "--json"]));
    assert_eq!(back, want);
    assert!(!original.is_empty());
}

#[test]
fn verify_rejects_a_damaged_file_in_one_line() {
    let lrm = scratch("knot.lrm");
    assert!(
        lrmesh(&["encode", &corpus("knot1.off"), "-o", lrm.to_str().unwrap()])
            .status
            .success()
    );
    let mut bytes = std::fs::read(&lrm).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x40;
    let bad = scratch("knot-bad.lrm");
    std::fs::write(&bad, &bytes).unwrap();
    let out = lrmesh(&["verify", bad.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("byte offset"), "{stderr}");
}

#[test]
fn bad_mesh_file_is_a_clean_error() {
    let bad = scratch("bad.off");
    std::fs::write(&bad, "OFF\n4000000000 1 0\n0 0 0\n").unwrap();
    let out = lrmesh(&["info", bad.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: ") && stderr.contains("bad.off"),
        "{stderr}"
    );
}
