mod common;
use lrmesh::format::Tag;
use lrmesh::read::{open, Limits, Sections};
use lrmesh::write::assemble;
use lrmesh::Error;

fn vector(name: &str) -> Vec<u8> {
    std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("spec/vectors")
            .join(name),
    )
    .unwrap()
}

fn scan(name: &str, bytes: &[u8], tag: Tag, width: usize, values: impl Fn(u32) -> Vec<u32>) {
    let sections = common::sections_of(bytes);
    let index = sections.iter().position(|s| s.0 == tag).unwrap();
    let base = Sections::parse(bytes, &Limits::default()).unwrap().sections[index].offset;
    for at in (0..sections[index].2.len() / width).map(|i| width * i) {
        let field = &sections[index].2[at..at + width];
        let original = field.iter().rev().fold(0u32, |x, &b| x << 8 | b as u32);
        for value in values(original) {
            if value == original {
                continue;
            }
            let mut forged = sections.clone();
            forged[index].2[at..at + width].copy_from_slice(&value.to_le_bytes()[..width]);
            match open(&assemble(&forged), &Limits::default()) {
                Err(Error::Format(e)) => println!(
                    "{name} {} at {at} {original:#x}->{value:#x}: V{} {} rel {} {}{}",
                    tag,
                    e.rule.0,
                    e.section,
                    e.offset as i64 - base as i64,
                    e.message,
                    if e.offset == base + at as u64 {
                        " HERE"
                    } else {
                        ""
                    }
                ),
                Err(e) => println!("{name} at {at} {original:#x}->{value:#x}: other {e}"),
                Ok(_) => println!("{name} at {at} {original:#x}->{value:#x}: OK"),
            }
        }
    }
}

#[test]
#[ignore]
fn explore() {
    let which = std::env::var("WHICH").unwrap();
    let bytes = vector(&which);
    let tag = Tag(std::env::var("TAG").unwrap().as_bytes().try_into().unwrap());
    let width: usize = std::env::var("WIDTH")
        .map(|w| w.parse().unwrap())
        .unwrap_or(4);
    let sections = common::sections_of(&bytes);
    let s = sections.iter().find(|s| s.0 == tag).unwrap();
    let words: Vec<u32> =
        s.2.chunks(width)
            .map(|c| c.iter().rev().fold(0u32, |x, &b| x << 8 | b as u32))
            .collect();
    println!("words: {words:?}");
    let small = |o: u32| {
        let mut v: Vec<u32> = (0..30).collect();
        v.extend([
            o ^ 0x8000_0000,
            o ^ 0x4000_0000,
            o.wrapping_add(1),
            o.wrapping_sub(1),
            u32::MAX,
            0x3FFF_FFFF,
            0x8000,
            0xC000,
            0x4000,
        ]);
        v
    };
    scan(&which, &bytes, tag, width, small);
}

#[test]
#[ignore]
fn explore_v38() {
    use lrmesh::{CornerOps, Vertex};
    use lrmesh::lr::LrLayout;
    use lrmesh::generate::{self, Rng};
    let mut meshes: Vec<(String, lrmesh::Mesh)> = vec![];
    for entry in std::fs::read_dir(common::corpus_dir()).unwrap() {
        let p = entry.unwrap().path();
        if let Ok(m) = lrmesh::load(&p) { meshes.push((p.display().to_string(), m)); }
    }
    for v in ["boundary_hedra_open", "defective_torus", "nonmanifold_vertex", "torus_with_t0"] {
        meshes.push((v.into(), lrmesh::load(format!("{}/spec/vectors/{v}.off", env!("CARGO_MANIFEST_DIR"))).unwrap()));
    }
    for seed in 0..20 {
        let mut m = generate::torus(5, 6);
        generate::punch_holes(&mut m, 2, &mut Rng::new(seed));
        generate::add_defects(&mut m, 3, &mut Rng::new(seed));
        meshes.push((format!("gen{seed}"), m));
    }
    for (name, mesh) in meshes {
        for conn in [lrmesh::write::Connectivity::Lr, lrmesh::write::Connectivity::LrCompact] {
        let bytes = lrmesh::write::encode(&mesh, &lrmesh::write::EncodeOptions { connectivity: conn, keep_order: true, ..Default::default() }).unwrap();
        let view = open(&bytes, &Limits::default()).unwrap();
        let c = view.connectivity();
        let m_r = view.lr().map(|l| l.ring_vertices()).or(view.lr_compact().map(|l| l.ring_vertices())).unwrap();
        for v in m_r..c.vertex_id_bound() {
            let corners: Vec<_> = c.corners().filter(|&x| c.vertex(x) == Vertex(v)).collect();
            let open = corners.iter().filter(|&&x| c.unswing(x).is_none()).count();
            if corners.len() >= 2 && open > 0 {
                println!("{name} {conn:?} len {} v {v} corners {corners:?} open {open}", bytes.len());
            }
        }
        }
    }
}
