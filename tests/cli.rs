//! The `lrmesh` command end to end: info, stats, convert, encode, verify, decode, render, bench.

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
    for key in [
        "k",
        "isolated_vertices",
        "t0_pct",
        "t0w_pct",
        "t1i_pct",
        "t2i_pct",
        "bpt",
    ] {
        assert!(
            stats["lr_compact"].get(key).is_some(),
            "missing lr_compact.{key}"
        );
    }
    // knot1 is regular: the bit-efficient LR stays close to 16 bits per triangle.
    let bpt = stats["lr_compact"]["bpt"].as_f64().unwrap();
    assert!(bpt > 15.0 && bpt < 18.0, "lr_compact.bpt {bpt}");
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

/// Width, height and colour type of a PNG file.
fn png_info(path: &Path) -> (u32, u32, png::ColorType) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let info = decoder.read_info().unwrap().info().clone();
    (info.width, info.height, info.color_type)
}

#[test]
fn render_writes_a_png_and_nothing_else_to_stderr() {
    let png = scratch("elephant.png");
    let out = lrmesh(&[
        "render",
        &corpus("elephant-with-holes.off"),
        "-o",
        png.to_str().unwrap(),
        "--mode",
        "classes",
        "--size",
        "160x120",
        "--view",
        "-45,10",
        "--perspective",
        "--ring-lines",
    ]);
    assert!(out.status.success());
    // No progress bar when stderr is not a terminal: one line, no escape codes.
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!("wrote {}: 160x120 pixels\n", png.display())
    );
    assert!(out.stdout.is_empty());
    assert_eq!(png_info(&png), (160, 120, png::ColorType::Rgb));
}

#[test]
fn render_reads_an_lr_container_and_refuses_edgebreaker() {
    let lrm = scratch("bunny-render.lrm");
    let lrm = lrm.to_str().unwrap();
    assert!(lrmesh(&["encode", &corpus("bunny_small.obj"), "-o", lrm])
        .status
        .success());
    let png = scratch("bunny-from-lrm.png");
    let out = lrmesh(&[
        "render",
        lrm,
        "-o",
        png.to_str().unwrap(),
        "--size",
        "64x64",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(png_info(&png).0, 64);

    let eb = scratch("bunny-render-eb.lrm");
    let eb = eb.to_str().unwrap();
    let encode = &["encode", &corpus("bunny_small.obj"), "-o", eb];
    assert!(
        lrmesh(&[&encode[..], &["--connectivity", "edgebreaker"]].concat())
            .status
            .success()
    );
    let out = lrmesh(&["render", eb, "-o", png.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("render needs LR connectivity"), "{stderr}");

    // A bit-efficient LR container renders as the standard one would.
    let compact = scratch("bunny-render-compact.lrm");
    let compact = compact.to_str().unwrap();
    let encode = &["encode", &corpus("bunny_small.obj"), "-o", compact];
    assert!(
        lrmesh(&[&encode[..], &["--connectivity", "lr-compact"]].concat())
            .status
            .success()
    );
    let out = lrmesh(&[
        "render",
        compact,
        "-o",
        png.to_str().unwrap(),
        "--size",
        "48x40",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(png_info(&png).0, 48);
}

#[test]
fn render_rejects_bad_sizes_and_views() {
    let png = scratch("never.png");
    for args in [
        ["--size", "0x10"],
        ["--size", "100"],
        ["--size", "20000x10"],
        ["--view", "10"],
        ["--view", "nan,3"],
    ] {
        let out = lrmesh(
            &[
                &[
                    "render",
                    &corpus("tetrahedron.off"),
                    "-o",
                    png.to_str().unwrap(),
                ],
                &args[..],
            ]
            .concat(),
        );
        assert!(!out.status.success(), "{args:?}");
    }
    assert!(!png.exists());
}

#[test]
fn bench_json_has_one_row_per_representation() {
    let out = lrmesh(&["bench", &corpus("knot1.off"), "--json", "--runs", "1"]);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = json(&out);
    assert_eq!(report["triangles"], 6400);
    let rows = report["rows"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["name"].as_str().unwrap()).collect();
    for name in [
        "corner table",
        "LR (owned)",
        "LR (view)",
        "compact LR (owned)",
        "compact LR (view)",
        "Edgebreaker",
        "strips (CTS)",
    ] {
        assert!(names.contains(&name), "no row {name} in {names:?}");
    }
    assert_eq!(names[0], "corner table");
    for key in ["c_v", "c_o", "valence", "normals", "contour"] {
        assert_eq!(rows[0]["loops"][key], 1.0, "corner table {key}");
        assert!(report["baseline_ns"][key].as_f64().unwrap() > 0.0);
    }
    for row in rows {
        let bytes = row["bytes"].as_f64().unwrap();
        let bpt = row["bits_per_triangle"].as_f64().unwrap();
        assert!(
            bytes > 0.0 && (bpt - 8.0 * bytes / 6400.0).abs() < 1e-9,
            "{row}"
        );
        assert!(row["build_ms"].as_f64().unwrap() >= 0.0);
    }
    // Edgebreaker has no random access; the LR view opens from bytes.
    let row = |name: &str| rows.iter().find(|r| r["name"] == name).unwrap();
    assert!(row("Edgebreaker")["loops"].is_null());
    // Every other row's loops were timed (interleaved, each recorded under its row's name).
    let timings = report["timings"].as_array().unwrap();
    for r in rows.iter().filter(|r| r["name"] != "Edgebreaker") {
        let name = r["name"].as_str().unwrap();
        assert!(r["loops"]["valence"].as_f64().is_some(), "{name}");
        for key in ["c.v", "c.o", "valence", "normals", "contour"] {
            let step = format!("{name}: {key}");
            assert!(timings.iter().any(|t| t["step"] == step.as_str()), "{step}");
        }
    }
    assert!(row("LR (view)")["open_ms"].as_f64().is_some());
    for name in ["LR (view)", "compact LR (view)", "Edgebreaker"] {
        assert!(
            row(name)["memcpy_ms"].as_f64().is_some_and(|t| t > 0.0),
            "{name}"
        );
    }
    assert!(row("LR (owned)")["memcpy_ms"].is_null());
    // Verifying checks the semantic rules on top of the well-formed check.
    for name in ["LR (view)", "compact LR (view)"] {
        let (open, verify) = (
            row(name)["open_ms"].as_f64(),
            row(name)["verify_ms"].as_f64(),
        );
        assert!(verify.is_some_and(|v| v > 0.0) && open.is_some(), "{name}");
    }
    assert!(row("Edgebreaker")["verify_ms"].is_null());
    assert!(row("LR (owned)")["bytes"].as_f64() < row("corner table")["bytes"].as_f64());
    assert!(row("compact LR (owned)")["bytes"].as_f64() < row("LR (owned)")["bytes"].as_f64());
    assert!(row("compact LR (view)")["open_ms"].as_f64().is_some());

    let text = lrmesh(&["bench", &corpus("tetrahedron.off"), "--runs", "1"]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("representation") && text.contains("Edgebreaker"),
        "{text}"
    );
}

/// `--quantize-position` (and its alias `--quantize`) and `-l` choose the position encoding
/// that `info --json` reports under `positions`; out-of-range values are refused.
#[test]
fn encode_position_options_and_info_positions() {
    let input = corpus("fandisk.off");
    let cases: [(&[&str], &str, Option<u64>); 6] = [
        (&["--connectivity", "edgebreaker"], "predicted-f32", None),
        (
            &["--connectivity", "edgebreaker", "--quantize-position", "11"],
            "predicted-grid",
            Some(11),
        ),
        (
            &[
                "--connectivity",
                "edgebreaker",
                "--quantize",
                "16",
                "-l",
                "0",
            ],
            "grid16",
            Some(16),
        ),
        (&["-l", "0"], "f32", None),
        (&["--quantize-position", "14"], "blocked-grid", Some(14)),
        (
            &[
                "--connectivity",
                "strips",
                "--quantize-position",
                "14",
                "--level",
                "0",
            ],
            "blocked-grid",
            Some(14),
        ),
    ];
    for (i, (options, encoding, bits)) in cases.iter().enumerate() {
        let out = scratch(&format!("positions{i}.lrm"));
        let mut args = vec!["encode", &input, "-o", out.to_str().unwrap()];
        args.extend_from_slice(options);
        let status = lrmesh(&args);
        assert!(
            status.status.success(),
            "{options:?}: {}",
            String::from_utf8_lossy(&status.stderr)
        );
        let info = json(&lrmesh(&["info", out.to_str().unwrap(), "--json"]));
        let p = &info["positions"];
        assert_eq!(p["encoding"], *encoding, "{options:?}");
        assert_eq!(p["bits"].as_u64(), *bits, "{options:?}");
        assert!(p["bits_per_vertex"].as_f64().unwrap() > 0.0);
        assert_eq!(info["quantized"], bits.is_some());
    }
    for bad in [
        ["--quantize-position", "0"],
        ["--quantize-position", "31"],
        ["-l", "10"],
    ] {
        let out = scratch("refused.lrm");
        let mut args = vec!["encode", &input, "-o", out.to_str().unwrap()];
        args.extend_from_slice(&bad);
        let status = lrmesh(&args);
        assert!(!status.status.success(), "{bad:?} accepted");
    }
}

/// `--quantize-normal` and `--quantize-texcoord` make the attribute records smaller and the
/// file version 1.2; bits out of range are refused.
#[test]
fn encode_attribute_quantization_options() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus/assets/obj/spider/spider.obj")
        .to_string_lossy()
        .into_owned();
    let attribute_bytes = |options: &[&str]| {
        let out = scratch(&format!("attributes{}.lrm", options.len()));
        // As given: the spider has triangles written the other way round, whose repair
        // (section FLIP, version 1.5) would decide the version; as strips, since the LR of
        // a mesh with holes lists its open fans (`LRTB` flag `OPEN_FANS`, version 1.17).
        let mut args = vec![
            "encode",
            &input,
            "-o",
            out.to_str().unwrap(),
            "--no-orient",
            "--connectivity",
            "strips",
        ];
        args.extend_from_slice(options);
        let status = lrmesh(&args);
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        let info = json(&lrmesh(&["info", out.to_str().unwrap(), "--json"]));
        let bytes: u64 = info["attribute_details"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a["bytes"].as_u64().unwrap())
            .sum();
        (info["version"].as_str().unwrap().to_string(), bytes)
    };
    // Level 0 keeps the positions raw, so that only the attributes decide the version.
    let (raw_version, raw) = attribute_bytes(&["-l", "0"]);
    let (version, quantized) = attribute_bytes(&[
        "-l",
        "0",
        "--quantize-normal",
        "10",
        "--quantize-texcoord",
        "12",
    ]);
    assert_eq!((raw_version.as_str(), version.as_str()), ("1.1", "1.2"));
    assert!(quantized * 2 < raw, "{quantized} of {raw}");
    for bad in [["--quantize-normal", "25"], ["--quantize-texcoord", "0"]] {
        let out = scratch("refused-attributes.lrm");
        let mut args = vec!["encode", &input, "-o", out.to_str().unwrap()];
        args.extend_from_slice(&bad);
        assert!(!lrmesh(&args).status.success(), "{bad:?} accepted");
    }
}
