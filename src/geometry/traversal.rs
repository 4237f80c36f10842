//! The order in which predicted positions are coded (GEOMETRY.md §3.2): a traversal of the
//! decoded triangles that enters a triangle whose far vertex is already known before one
//! that brings a new vertex, and a new vertex reached by two triangles before one reached by
//! one, so that most vertices come when several parallelograms predict them (the
//! prediction-degree traversal of Draco's encoder, reimplemented from its description).

use crate::ids::NONE;

/// Priorities: 0 for a triangle whose far vertex is known, 1 for a far vertex reached twice
/// or more, 2 for one reached once.
const PRIORITIES: usize = 3;

/// The vertices of a corner table (`v`, `o` its V and O tables, `vertices` of them) in coding
/// order: every vertex once, those of no triangle last, in increasing id.
pub(crate) fn coding_order(v: &[u32], o: &[u32], vertices: usize) -> Vec<u32> {
    let triangles = v.len() / 3;
    let next = |c: usize| c - c % 3 + (c % 3 + 1) % 3;
    let prev = |c: usize| c - c % 3 + (c % 3 + 2) % 3;
    let mut seen_vertex = vec![false; vertices];
    let mut seen_triangle = vec![false; triangles];
    let mut degree = vec![0u8; vertices];
    let mut order = Vec::with_capacity(vertices);
    let mut stacks: [Vec<u32>; PRIORITIES] = Default::default();
    let visit = |x: u32, order: &mut Vec<u32>, seen: &mut [bool]| {
        if !seen[x as usize] {
            seen[x as usize] = true;
            order.push(x);
        }
    };
    for start in 0..triangles {
        if seen_triangle[start] {
            continue;
        }
        let c0 = 3 * start;
        visit(v[next(c0)], &mut order, &mut seen_vertex);
        visit(v[prev(c0)], &mut order, &mut seen_vertex);
        stacks[0].push(c0 as u32);
        let mut best = 0;
        while let Some(popped) = (best..PRIORITIES).find_map(|i| stacks[i].pop().map(|c| (i, c))) {
            best = popped.0;
            let mut c = popped.1 as usize;
            if seen_triangle[c / 3] {
                continue;
            }
            loop {
                seen_triangle[c / 3] = true;
                visit(v[c], &mut order, &mut seen_vertex);
                let open = |d: u32| d != NONE && !seen_triangle[d as usize / 3];
                let (right, left) = (o[next(c)], o[prev(c)]);
                let mut priority = |d: u32| {
                    let tip = v[d as usize] as usize;
                    if seen_vertex[tip] {
                        0
                    } else {
                        degree[tip] = degree[tip].saturating_add(1);
                        if degree[tip] > 1 {
                            1
                        } else {
                            2
                        }
                    }
                };
                if open(left) {
                    let p = priority(left);
                    if !open(right) && p <= best {
                        c = left as usize;
                        continue;
                    }
                    stacks[p].push(left);
                    best = best.min(p);
                }
                if open(right) {
                    let p = priority(right);
                    if p <= best {
                        c = right as usize;
                        continue;
                    }
                    stacks[p].push(right);
                    best = best.min(p);
                }
                break;
            }
        }
    }
    for x in 0..vertices as u32 {
        visit(x, &mut order, &mut seen_vertex);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corner_table::CornerTable;

    #[test]
    fn every_vertex_once() {
        for mesh in [
            crate::Mesh::new(
                vec![[0.0; 3]; 6],
                vec![
                    [0, 1, 2],
                    [0, 2, 3],
                    [0, 3, 4],
                    [0, 4, 1],
                    [5, 2, 1],
                    [5, 3, 2],
                    [5, 4, 3],
                    [5, 1, 4],
                ],
            ),
            crate::Mesh::new(vec![[0.0; 3]; 5], vec![[0, 1, 2], [2, 1, 3]]),
            crate::Mesh::new(vec![[0.0; 3]; 2], vec![]),
        ] {
            let t = CornerTable::from_mesh(&mesh).unwrap();
            let n = t.c_table().len();
            let mut order = coding_order(t.v_table(), t.o_table(), n);
            order.sort_unstable();
            assert_eq!(order, (0..n as u32).collect::<Vec<_>>());
        }
    }
}
