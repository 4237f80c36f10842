use lrmesh::ops::{self, CornerOps};
use std::time::Instant;
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let reps: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(50);
    let bytes = std::fs::read(&path).unwrap();
    let c = lrmesh::read::open(&bytes, &lrmesh::read::Limits::default()).unwrap();
    let mut best = f64::MAX;
    let mut s = 0;
    fn run<M: CornerOps>(mesh: &M, reps: usize, best: &mut f64, s: &mut u32) {
        for _ in 0..reps {
            let t = Instant::now();
            *s = mesh.vertices().map(|v| ops::valence(mesh, v)).sum::<u32>();
            *best = best.min(t.elapsed().as_secs_f64());
        }
    }
    if let Some(t) = c.lr() {
        run(t, reps, &mut best, &mut s);
    }
    if let Some(t) = c.lr_compact() {
        run(t, reps, &mut best, &mut s);
    }
    if let Some(t) = c.zipper() {
        run(t, reps, &mut best, &mut s);
    }
    let mesh2 = lrmesh::io::read_mesh(
        std::path::Path::new("../shared/meshes/bunny00.off"),
        &Default::default(),
    )
    .unwrap()
    .mesh;
    let ct = lrmesh::CornerTable::from_mesh(&mesh2).unwrap();
    let mut bestc = f64::MAX;
    let mut s2 = 0;
    if std::env::var("NOCT").is_err() {
        for _ in 0..reps {
            let t = Instant::now();
            s2 = ct.vertices().map(|v| ops::valence(&ct, v)).sum::<u32>();
            bestc = bestc.min(t.elapsed().as_secs_f64());
        }
    }
    println!(
        "view {:.2} ms  ct {:.2} ms  ratio {:.3}  ({s} {s2})",
        best * 1e3,
        bestc * 1e3,
        best / bestc
    );
}
