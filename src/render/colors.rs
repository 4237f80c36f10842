//! The colours of [`ColorMode`](super::ColorMode): ring order from blue to red, and the
//! triangle-class palette of the LR paper's Fig. 1.

use crate::ids::{Triangle, Vertex};
use crate::lr::{LrInspect, LrLayout, TriangleClass};

/// Ring position of each ring vertex in `0..=1` (start to end of its ring).
pub(super) fn ring_parameters<L: LrLayout>(lr: &L) -> Vec<f32> {
    let mut param = vec![0.0; lr.ring_vertices() as usize];
    for r in 0..lr.ring_count() {
        let Some(range) = lr.ring_range(r) else {
            continue;
        };
        let span = (range.len().max(2) - 1) as f32;
        for v in range.clone() {
            if let Some(p) = param.get_mut(v as usize) {
                *p = (v - range.start) as f32 / span;
            }
        }
    }
    param
}

/// Ring-order colour of triangle `t`: a ring-edge triangle takes its ring edge's place, a T0
/// the mean place of its ring vertices; grey when none of its vertices is on a ring.
pub(super) fn ring_color<L: LrLayout>(
    lr: &L,
    ring: &[f32],
    t: Triangle,
    vs: [Vertex; 3],
) -> Option<[f32; 3]> {
    let slot = t.0 / 2;
    if t.0 < 2 * lr.ring_vertices() {
        return ring.get(slot as usize).map(|&x| blue_to_red(x));
    }
    let on_ring: Vec<f32> = vs
        .iter()
        .filter_map(|v| ring.get(v.idx()).copied())
        .collect();
    if on_ring.is_empty() {
        return Some([0.6, 0.6, 0.6]);
    }
    Some(blue_to_red(
        on_ring.iter().sum::<f32>() / on_ring.len() as f32,
    ))
}

/// Hue from blue (`x = 0`) through cyan, green and yellow to red (`x = 1`).
pub(super) fn blue_to_red(x: f32) -> [f32; 3] {
    let h = 4.0 * (1.0 - x.clamp(0.0, 1.0)); // 4 = blue, 0 = red, in sixths of the hue circle
    let f = h - h.floor();
    let rgb = match h as u32 {
        0 => [1.0, f, 0.0],
        1 => [1.0 - f, 1.0, 0.0],
        2 => [0.0, 1.0, f],
        3 => [0.0, 1.0 - f, 1.0],
        _ => [0.0, 0.0, 1.0],
    };
    // Slightly desaturated so that the shading reads on every hue.
    rgb.map(|c| 0.12 + 0.88 * c)
}

/// The palette of Fig. 1: neutral T1, highlighted T0, T2 and warts.
pub(super) fn class_color(class: TriangleClass) -> [f32; 3] {
    match class {
        TriangleClass::T1Left => [1.0, 0.82, 0.6],
        TriangleClass::T1Right => [0.98, 0.95, 0.84],
        TriangleClass::T2 => [0.2, 0.45, 1.0],
        TriangleClass::T2Wart => [0.55, 0.25, 0.95],
        TriangleClass::T0 => [0.15, 0.75, 0.25],
        TriangleClass::T0Wart => [0.95, 0.15, 0.15],
    }
}
