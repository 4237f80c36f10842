//! The colours of [`ColorMode`](super::ColorMode): ring order from blue to red (grey off
//! the rings), and the triangle-class palette of the LR paper's Fig. 1.

use crate::lr::TriangleClass;

/// The colour of a triangle with no vertex on a ring.
pub(super) const OFF_RING: [f32; 3] = [0.6, 0.6, 0.6];

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
