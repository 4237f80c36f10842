//! The rasterizer: supersampled colour and depth buffers, filled triangle by triangle with
//! a z-test, ring lines drawn over them, and the samples averaged into an [`Image`].

use super::camera::Camera;
use super::Image;
use crate::lr::LrLayout;
use crate::ops::CornerOps;

/// How far in front of the surface a ring line may be and still be drawn: a small fraction
/// of the depth range of the mesh.
pub(super) fn depth_bias<L: LrLayout>(camera: &Camera, positions: &[[f32; 3]], lr: &L) -> f32 {
    let (lo, hi) = lr
        .vertices()
        .filter_map(|v| camera.project(positions[v.idx()]))
        .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
            (lo.min(p[2]), hi.max(p[2]))
        });
    if lo <= hi {
        0.01 * (hi - lo)
    } else {
        0.0
    }
}

/// The supersampled colour and depth buffers.
pub(super) struct Target {
    width: u32,
    height: u32,
    rgb: Vec<[u8; 3]>,
    depth: Vec<f32>,
}

impl Target {
    pub(super) fn new(width: u32, height: u32, background: [u8; 3]) -> Target {
        let n = width as usize * height as usize;
        Target {
            width,
            height,
            rgb: vec![background; n],
            depth: vec![f32::NEG_INFINITY; n],
        }
    }

    /// Fills the samples whose centres lie inside (or on an edge of) triangle `p`, nearer
    /// than what is there. Scanline spans come from the edge functions, so the work is the
    /// rows of the triangle's bounding box plus the samples it covers.
    pub(super) fn triangle(&mut self, p: [[f32; 3]; 3], color: [u8; 3]) {
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        // Edge i from p[i] to p[i+1]: E(x, y) = a x + b y + c, positive inside.
        let sign = area.signum();
        let edges = [0, 1, 2].map(|i| {
            let (u, w) = (p[i], p[(i + 1) % 3]);
            let a = sign * (u[1] - w[1]);
            let b = sign * (w[0] - u[0]);
            let c = -(a * u[0] + b * u[1]);
            (a, b, c)
        });
        // Depth plane z = z0 + dzdx (x - x0) + dzdy (y - y0).
        let dzdx = ((p[1][2] - p[0][2]) * (p[2][1] - p[0][1])
            - (p[2][2] - p[0][2]) * (p[1][1] - p[0][1]))
            / area;
        let dzdy = ((p[2][2] - p[0][2]) * (p[1][0] - p[0][0])
            - (p[1][2] - p[0][2]) * (p[2][0] - p[0][0]))
            / area;
        let ymin = p.iter().map(|q| q[1]).fold(f32::MAX, f32::min);
        let ymax = p.iter().map(|q| q[1]).fold(f32::MIN, f32::max);
        let row0 = (ymin - 0.5).ceil().max(0.0);
        let row1 = (ymax - 0.5).floor().min(self.height as f32 - 1.0);
        if row0 > row1 {
            return;
        }
        for row in row0 as u32..=row1 as u32 {
            let y = row as f32 + 0.5;
            let (mut lo, mut hi) = (0.0f32, self.width as f32);
            for &(a, b, c) in &edges {
                let rhs = -(b * y + c);
                if a > 0.0 {
                    lo = lo.max(rhs / a);
                } else if a < 0.0 {
                    hi = hi.min(rhs / a);
                } else if rhs > 0.0 {
                    lo = f32::MAX;
                }
            }
            let col0 = (lo - 0.5).ceil().max(0.0);
            let col1 = (hi - 0.5).floor().min(self.width as f32 - 1.0);
            if col0.is_nan() || col1.is_nan() || col0 > col1 {
                continue;
            }
            let base = row as usize * self.width as usize;
            for col in col0 as u32..=col1 as u32 {
                let x = col as f32 + 0.5;
                let z = p[0][2] + dzdx * (x - p[0][0]) + dzdy * (y - p[0][1]);
                let i = base + col as usize;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.rgb[i] = color;
                }
            }
        }
    }

    /// A line `width` samples wide from `a` to `b`, drawn where it is no more than `bias`
    /// behind the surface.
    pub(super) fn line(&mut self, a: [f32; 3], b: [f32; 3], width: f32, bias: f32, color: [u8; 3]) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let steps = dx.abs().max(dy.abs()).ceil();
        // The fitted camera keeps every vertex in the image, so no line is longer than its
        // diagonal; anything longer (never drawn) is skipped to keep the steps bounded.
        let limit = 4.0 * (self.width + self.height) as f32;
        if !steps.is_finite() || steps > limit {
            return;
        }
        let steps = steps.max(1.0) as u32;
        let half = (width * 0.5).max(0.5);
        for k in 0..=steps {
            let f = k as f32 / steps as f32;
            let (x, y, z) = (a[0] + f * dx, a[1] + f * dy, a[2] + f * (b[2] - a[2]));
            let (x0, x1) = ((x - half).round() as i64, (x + half).round() as i64);
            let (y0, y1) = ((y - half).round() as i64, (y + half).round() as i64);
            for row in y0.max(0)..y1.min(self.height as i64) {
                for col in x0.max(0)..x1.min(self.width as i64) {
                    let i = row as usize * self.width as usize + col as usize;
                    if z + bias >= self.depth[i] {
                        self.rgb[i] = color;
                    }
                }
            }
        }
    }

    /// Averages `s` x `s` blocks of samples into pixels.
    pub(super) fn downsample(self, s: u32) -> Image {
        let (width, height) = (self.width / s, self.height / s);
        let mut rgb = Vec::with_capacity(3 * width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                let mut sum = [0u32; 3];
                for j in 0..s {
                    let row = (y * s + j) as usize * self.width as usize;
                    for i in 0..s {
                        let c = self.rgb[row + (x * s + i) as usize];
                        for k in 0..3 {
                            sum[k] += c[k] as u32;
                        }
                    }
                }
                let n = s * s;
                rgb.extend(sum.map(|v| ((v + n / 2) / n) as u8));
            }
        }
        Image { width, height, rgb }
    }
}
