//! Generated meshes of known topology, for tests and benchmarks: tori, handles, holes,
//! several components, irregular valences, and soups with every defect a real mesh can have.
//!
//! Everything is deterministic for a given seed.

use crate::corner_table::CornerTable;
use crate::ops::CornerOps;
use crate::{Corner, Mesh};

pub use crate::rng::Rng;

/// A closed torus of `2 * around * along` triangles on a regular grid (every valence 6).
/// `around` and `along` must be at least 3.
pub fn torus(around: u32, along: u32) -> Mesh {
    assert!(
        around >= 3 && along >= 3,
        "a torus grid needs at least 3x3 cells"
    );
    let (big, small) = (1.0f32, 0.35f32);
    let mut positions = Vec::with_capacity((around * along) as usize);
    for i in 0..along {
        let u = i as f32 / along as f32 * std::f32::consts::TAU;
        for j in 0..around {
            let w = j as f32 / around as f32 * std::f32::consts::TAU;
            let r = big + small * w.cos();
            positions.push([r * u.cos(), r * u.sin(), small * w.sin()]);
        }
    }
    let id = |i: u32, j: u32| (i % along) * around + (j % around);
    let mut triangles = Vec::with_capacity(2 * (around * along) as usize);
    for i in 0..along {
        for j in 0..around {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles)
}

/// Moves every vertex by up to `amount` along each axis.
pub fn jitter(mesh: &mut Mesh, amount: f32, rng: &mut Rng) {
    for p in &mut mesh.positions {
        for x in p.iter_mut() {
            *x += (rng.unit() * 2.0 - 1.0) * amount;
        }
    }
}

/// Flips about `count` random interior edges of a manifold mesh, skipping flips that would
/// create an existing edge or leave a vertex with valence below 3. This makes valences
/// irregular without changing the topology.
pub fn flip_edges(mesh: &mut Mesh, count: usize, rng: &mut Rng) {
    let Ok(table) = CornerTable::from_mesh(mesh) else {
        return;
    };
    let corners = mesh.triangles.len() as u32 * 3;
    if corners == 0 {
        return;
    }
    let mut valence = vec![0u32; mesh.positions.len()];
    for tri in &mesh.triangles {
        for &v in tri {
            valence[v as usize] += 1;
        }
    }
    // The table is not updated as we flip, so each triangle is flipped at most once.
    let mut touched = vec![false; mesh.triangles.len()];
    for _ in 0..count {
        let c = Corner(rng.below(corners));
        let Some(d) = table.opposite(c) else { continue };
        let (t, u) = (c.idx() / 3, d.idx() / 3);
        if touched[t] || touched[u] {
            continue;
        }
        // Triangles (x, a, b) and (y, b, a) become (x, y, b) and (y, x, a).
        let x = mesh.triangles[t][c.idx() % 3];
        let y = mesh.triangles[u][d.idx() % 3];
        let a = mesh.triangles[t][(c.idx() + 1) % 3];
        let b = mesh.triangles[t][(c.idx() + 2) % 3];
        if x == y
            || valence[a as usize] <= 3
            || valence[b as usize] <= 3
            || joined(mesh, &table, c, [x, y])
        {
            continue;
        }
        mesh.triangles[t] = [x, y, b];
        mesh.triangles[u] = [y, x, a];
        valence[a as usize] -= 1;
        valence[b as usize] -= 1;
        valence[x as usize] += 1;
        valence[y as usize] += 1;
        touched[t] = true;
        touched[u] = true;
    }
}

/// Whether some triangle of `mesh` holds both `x` and `y` now, `at_x` being a corner at `x`
/// of a triangle not flipped yet. Such a triangle is one around `x` in `table` (the mesh
/// before any flip) or a neighbour of one: a flip gives a vertex only to the neighbour across
/// the flipped edge of a triangle that holds it, and flips each triangle once at most. A
/// walk of a few dozen triangles, where a set of every edge would take some 40 bytes per
/// triangle.
fn joined(mesh: &Mesh, table: &CornerTable, at_x: Corner, [x, y]: [u32; 2]) -> bool {
    let holds = |t: usize| {
        let tri = mesh.triangles[t];
        tri.contains(&x) && tri.contains(&y)
    };
    let near = |k: Corner| {
        let t = k.idx() / 3;
        holds(t)
            || (0..3).any(|i| {
                table
                    .opposite(Corner((3 * t + i) as u32))
                    .is_some_and(|d| holds(d.idx() / 3))
            })
    };
    // Around x one way, then (on a boundary) the other way.
    let mut k = at_x;
    loop {
        if near(k) {
            return true;
        }
        match table.swing(k) {
            Some(n) if n == at_x => return false,
            Some(n) => k = n,
            None => break,
        }
    }
    let mut k = at_x;
    while let Some(p) = table.unswing(k) {
        if p == at_x || near(p) {
            return p != at_x;
        }
        k = p;
    }
    false
}

/// An irregular closed genus-1 mesh of at least `min_triangles` triangles: a torus grid with a
/// third of its edges flipped at random and its vertices jittered.
pub fn irregular_torus(min_triangles: u32, seed: u64) -> Mesh {
    let cells = min_triangles.div_ceil(2).max(9);
    let along = ((cells as f64).sqrt().ceil() as u32).max(3);
    let around = cells.div_ceil(along).max(3);
    let mut mesh = torus(around, along);
    let mut rng = Rng::new(seed);
    let flips = mesh.triangles.len() / 2;
    flip_edges(&mut mesh, flips, &mut rng);
    jitter(&mut mesh, 0.2 / along as f32, &mut rng);
    mesh
}

/// A closed sphere (genus 0) of `2 * around * (along - 1)` triangles: `along - 1` rings of
/// `around` vertices between two poles. `around` must be at least 3, `along` at least 2.
pub fn sphere(around: u32, along: u32) -> Mesh {
    assert!(around >= 3 && along >= 2, "a sphere grid needs 3 x 2 cells");
    let rings = along - 1;
    let mut positions = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for i in 1..along {
        let polar = i as f32 / along as f32 * std::f32::consts::PI;
        for j in 0..around {
            let w = j as f32 / around as f32 * std::f32::consts::TAU;
            positions.push([polar.sin() * w.cos(), polar.sin() * w.sin(), polar.cos()]);
        }
    }
    let id = |i: u32, j: u32| 2 + i * around + j % around;
    let mut triangles = Vec::with_capacity(2 * (around * rings) as usize);
    for j in 0..around {
        triangles.push([0, id(0, j), id(0, j + 1)]);
        triangles.push([1, id(rings - 1, j + 1), id(rings - 1, j)]);
    }
    for i in 0..rings - 1 {
        for j in 0..around {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles)
}

/// What [`surface`] makes (`lrmesh generate`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceOptions {
    /// About this many triangles in all (at least 16 per component).
    pub triangles: u64,
    /// The genus of each component: 0 a sphere, 1 a torus, more a torus with handles.
    pub genus: u32,
    /// Triangles removed at random in all, each opening a hole (two side by side open one).
    pub holes: u32,
    /// Components, side by side along x.
    pub components: u32,
    /// Irregular valences: half as many edge flips as triangles, and jittered vertices.
    pub irregular: bool,
    /// The same seed gives the same mesh.
    pub seed: u64,
}

/// A mesh of about `options.triangles` triangles with the topology `options` ask for.
pub fn surface(options: &SurfaceOptions) -> Mesh {
    let mut rng = Rng::new(options.seed);
    let components = options.components.max(1);
    let each = (options.triangles / components as u64).max(16);
    let mut mesh = Mesh::default();
    for k in 0..components {
        let mut part = match options.genus {
            0 => {
                // 2 * around * (along - 1) triangles, around = 2 * along.
                let along = (((each / 4) as f64).sqrt().round() as u32).max(2);
                let around = (each / (2 * (along as u64 - 1))).max(3) as u32;
                sphere(around, along)
            }
            _ => {
                let cells = each.div_ceil(2);
                let along = ((cells as f64).sqrt().ceil() as u32).max(3);
                let around = (cells.div_ceil(along as u64) as u32).max(3);
                torus(around, along)
            }
        };
        if options.irregular {
            let flips = part.triangles.len() / 2;
            flip_edges(&mut part, flips, &mut rng);
            let step = 0.2 / (part.triangles.len() as f32).sqrt();
            jitter(&mut part, step, &mut rng);
        }
        add_random_handles(
            &mut part,
            options.genus.saturating_sub(1) as usize,
            &mut rng,
        );
        for p in &mut part.positions {
            p[0] += 3.0 * k as f32;
        }
        append(&mut mesh, &part);
    }
    punch_holes(&mut mesh, options.holes as usize, &mut rng);
    mesh
}

/// Appends `other` to `mesh` as a separate component.
pub fn append(mesh: &mut Mesh, other: &Mesh) {
    let base = mesh.positions.len() as u32;
    mesh.positions.extend_from_slice(&other.positions);
    mesh.triangles
        .extend(other.triangles.iter().map(|t| t.map(|v| v + base)));
}

/// Removes triangles `t1` and `t2` (which must share no vertex and sit in a closed oriented
/// mesh) and joins their holes with a tube of six triangles: a handle when both are in one
/// component (genus + 1), a connected sum when they are in two (the genera add up).
pub fn add_handle(mesh: &mut Mesh, t1: usize, t2: usize) {
    let [a, b, c] = mesh.triangles[t1];
    let [d, e, f] = mesh.triangles[t2];
    // Ring P = (a, b, c) is used as a->b->c; ring Q = (e, d, f) as d->e, e->f, f->d, matching
    // the reversed edges left around the two holes.
    let p = [a, b, c];
    let q = [e, d, f];
    let (hi, lo) = (t1.max(t2), t1.min(t2));
    mesh.triangles.swap_remove(hi);
    mesh.triangles.swap_remove(lo);
    for i in 0..3 {
        let j = (i + 1) % 3;
        mesh.triangles.push([p[i], p[j], q[j]]);
        mesh.triangles.push([p[i], q[j], q[i]]);
    }
}

/// Up to `count` handles (see [`add_handle`]), each between a random triangle and a random
/// triangle far from it; a draw with no far triangle adds nothing.
pub fn add_random_handles(mesh: &mut Mesh, count: usize, rng: &mut Rng) {
    for _ in 0..count {
        let t = rng.below(mesh.triangles.len() as u32) as usize;
        if let Some(u) = far_triangle(mesh, t, rng) {
            add_handle(mesh, t, u);
        }
    }
}

/// A triangle of `mesh` none of whose vertices is `t`'s vertex or neighbour, so that a tube
/// between the two (see [`add_handle`]) creates no existing edge. `None` if there is none.
pub fn far_triangle(mesh: &Mesh, t: usize, rng: &mut Rng) -> Option<usize> {
    let tri = mesh.triangles[t];
    let mut near = vec![false; mesh.positions.len()];
    for u in &mesh.triangles {
        if u.iter().any(|v| tri.contains(v)) {
            for &v in u {
                near[v as usize] = true;
            }
        }
    }
    let n = mesh.triangles.len();
    let start = rng.below(n as u32) as usize;
    (0..n)
        .map(|k| (start + k) % n)
        .find(|&u| mesh.triangles[u].iter().all(|&v| !near[v as usize]))
}

/// Removes `count` random triangles, opening holes (which may touch at vertices and so make
/// non-manifold vertices).
pub fn punch_holes(mesh: &mut Mesh, count: usize, rng: &mut Rng) {
    for _ in 0..count.min(mesh.triangles.len().saturating_sub(1)) {
        let t = rng.below(mesh.triangles.len() as u32) as usize;
        mesh.triangles.swap_remove(t);
    }
}

/// Adds the defects real meshes have, each about `count` times: flipped triangles, duplicate
/// triangles (same and flipped orientation), degenerate triangles, a third triangle on an
/// existing edge (non-manifold edge), a triangle touching the mesh at a single vertex
/// (non-manifold vertex), and unreferenced vertices.
pub fn add_defects(mesh: &mut Mesh, count: usize, rng: &mut Rng) {
    if mesh.triangles.is_empty() || mesh.positions.is_empty() {
        return;
    }
    for _ in 0..count {
        let nt = mesh.triangles.len() as u32;
        let t = rng.below(nt) as usize;
        let [a, b, c] = mesh.triangles[t];
        match rng.below(7) {
            0 => mesh.triangles[t] = [a, c, b],
            1 => mesh.triangles.push([b, c, a]),
            2 => mesh.triangles.push([a, c, b]),
            3 => mesh.triangles.push([a, a, b]),
            4 => {
                let x = mesh.positions.len() as u32;
                mesh.positions
                    .push(jittered(mesh.positions[a as usize], rng));
                mesh.triangles.push([a, b, x]);
            }
            5 => {
                let x = mesh.positions.len() as u32;
                mesh.positions
                    .push(jittered(mesh.positions[a as usize], rng));
                mesh.positions
                    .push(jittered(mesh.positions[b as usize], rng));
                mesh.triangles.push([a, x, x + 1]);
            }
            _ => mesh
                .positions
                .push(jittered(mesh.positions[c as usize], rng)),
        }
    }
}

fn jittered(p: [f32; 3], rng: &mut Rng) -> [f32; 3] {
    p.map(|x| x + rng.unit() * 0.1)
}

/// `triangles` random triangles over `vertices` vertices: a soup with every kind of defect.
pub fn soup(vertices: u32, triangles: u32, rng: &mut Rng) -> Mesh {
    let vertices = vertices.max(1);
    let positions = (0..vertices)
        .map(|_| [rng.unit(), rng.unit(), rng.unit()])
        .collect();
    let tris = (0..triangles)
        .map(|_| [0; 3].map(|_: u32| rng.below(vertices)))
        .collect();
    Mesh::new(positions, tris)
}
