//! Every fuzz target's seeds (`corpus/fuzz/<target>/`) and findings
//! (`corpus/fuzz/regressions/<target>/`) replayed through the target's own checks
//! (`lrmesh::fuzz_checks`, which the targets in `fuzz/` call): an input that once broke the
//! library must keep passing. A missing or empty directory fails the test, so that a replay
//! cannot silently check nothing.

use std::path::{Path, PathBuf};

use lrmesh::fuzz_checks::{run, TARGETS};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/fuzz")
}

/// The files of `dir`, which must exist and hold at least one.
fn inputs(dir: &Path) -> Vec<PathBuf> {
    let entries = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}: a replay directory is missing", dir.display()));
    let files: Vec<PathBuf> = entries
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .collect();
    assert!(!files.is_empty(), "{}: no input to replay", dir.display());
    files
}

fn replay(dir: &Path, target: &str) -> usize {
    let files = inputs(dir);
    for file in &files {
        let data = std::fs::read(file).unwrap();
        let outcome = std::panic::catch_unwind(|| run(target, &data));
        assert!(outcome.is_ok(), "{target}: {} fails", file.display());
    }
    files.len()
}

/// Every target has seeds, and each passes.
#[test]
fn seeds_of_every_target_pass() {
    for target in TARGETS {
        let n = replay(&root().join(target), target);
        eprintln!("{target}: {n} seeds");
    }
}

/// Every finding kept in `corpus/fuzz/regressions/<target>/` passes; every directory there
/// names a target and holds at least one input.
#[test]
fn regressions_pass() {
    let regressions = root().join("regressions");
    let dirs: Vec<PathBuf> = std::fs::read_dir(&regressions)
        .expect("corpus/fuzz/regressions is missing")
        .map(|e| e.unwrap().path())
        .collect();
    assert!(!dirs.is_empty(), "corpus/fuzz/regressions is empty");
    let mut replayed = 0;
    for dir in dirs {
        assert!(dir.is_dir(), "{}: outside a target folder", dir.display());
        let target = dir.file_name().unwrap().to_str().unwrap().to_string();
        assert!(
            TARGETS.contains(&target.as_str()),
            "{target} is not a fuzz target"
        );
        replayed += replay(&dir, &target);
    }
    assert!(replayed > 0);
}
