//! The view of [`render`](super::render): the [`Camera`] that projects world positions to
//! pixels, and the small vector arithmetic it and the shading share.

use super::{Axis, RenderOptions};

/// The projection of [`render`](super::render): world positions to pixel coordinates and depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub(super) right: [f32; 3],
    pub(super) up: [f32; 3],
    pub(super) back: [f32; 3],
    pub(super) center: [f32; 3],
    /// Distance of the eye from `center` (perspective only).
    pub(super) eye: Option<f32>,
    /// Projected point that lands in the middle of the image.
    pub(super) mid: [f32; 2],
    /// Pixels per projected unit.
    pub(super) scale: f32,
    pub(super) width: f32,
    pub(super) height: f32,
}

impl Camera {
    /// The camera of `options`, fitted so that the given points fill the image with a margin.
    /// Points that are not finite are ignored.
    pub fn fit(points: &[[f32; 3]], options: &RenderOptions) -> Self {
        let (lo, hi) = points
            .iter()
            .filter(|p| p.iter().all(|x| x.is_finite()))
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), &p| {
                (
                    [0, 1, 2].map(|k| lo[k].min(p[k])),
                    [0, 1, 2].map(|k| hi[k].max(p[k])),
                )
            });
        let (center, radius) = if lo[0] <= hi[0] {
            let c = [0, 1, 2].map(|k| 0.5 * lo[k] + 0.5 * hi[k]);
            let r = 0.5 * norm([0, 1, 2].map(|k| hi[k] - lo[k]));
            (c, if r.is_finite() && r > 0.0 { r } else { 1.0 })
        } else {
            ([0.0; 3], 1.0)
        };
        let (h1, up_axis, h2) = match options.up {
            Axis::X => ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            Axis::Y => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            Axis::Z => ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]),
        };
        let (az, el) = (
            finite_or(options.azimuth, 0.0).to_radians(),
            finite_or(options.elevation, 0.0).to_radians(),
        );
        let back = normalize(add3(
            add3(
                scale3(h2, az.cos() * el.cos()),
                scale3(h1, az.sin() * el.cos()),
            ),
            scale3(up_axis, el.sin()),
        ));
        let right = {
            let r = cross(up_axis, back);
            if norm(r) < 1e-4 {
                // Looking straight down or up: keep the first horizontal axis to the right.
                h1
            } else {
                normalize(r)
            }
        };
        let up = cross(back, right);
        let mut camera = Camera {
            right,
            up,
            back,
            center,
            // A 30 degree field of view around the bounding sphere.
            eye: options
                .perspective
                .then(|| radius / (15f32.to_radians()).sin()),
            mid: [0.0; 2],
            scale: 1.0,
            width: options.width.max(1) as f32,
            height: options.height.max(1) as f32,
        };
        let (plo, phi) = points.iter().filter_map(|&p| camera.view(p)).fold(
            ([f32::MAX; 2], [f32::MIN; 2]),
            |(lo, hi), q| {
                (
                    [lo[0].min(q[0]), lo[1].min(q[1])],
                    [hi[0].max(q[0]), hi[1].max(q[1])],
                )
            },
        );
        if plo[0] <= phi[0] {
            camera.mid = [0.5 * plo[0] + 0.5 * phi[0], 0.5 * plo[1] + 0.5 * phi[1]];
            let margin = 0.92;
            let sx = margin * camera.width / (phi[0] - plo[0]);
            let sy = margin * camera.height / (phi[1] - plo[1]);
            let s = sx.min(sy);
            camera.scale = if s.is_finite() && s > 0.0 {
                s
            } else {
                margin * camera.width.min(camera.height) / (2.0 * radius)
            };
        }
        camera
    }

    /// View coordinates `(x right, y up, depth towards the eye)` of a finite point, after the
    /// perspective division; `None` for a point that is not finite or behind the eye.
    fn view(&self, p: [f32; 3]) -> Option<[f32; 3]> {
        if !p.iter().all(|x| x.is_finite()) {
            return None;
        }
        let d = sub3(p, self.center);
        let (x, y, z) = (dot(d, self.right), dot(d, self.up), dot(d, self.back));
        let q = match self.eye {
            None => [x, y, z],
            Some(eye) => {
                let w = eye - z;
                if w <= 1e-6 * eye {
                    return None;
                }
                [x * eye / w, y * eye / w, z]
            }
        };
        q.iter().all(|x| x.is_finite()).then_some(q)
    }

    /// Pixel coordinates `(column, row, depth)` of `p` (column and row in pixel units from the
    /// top-left corner; a pixel's centre is at `+0.5`), larger depth nearer the eye. `None`
    /// for a point that is not finite or behind the eye.
    pub fn project(&self, p: [f32; 3]) -> Option<[f32; 3]> {
        let [x, y, z] = self.view(p)?;
        Some([
            0.5 * self.width + (x - self.mid[0]) * self.scale,
            0.5 * self.height - (y - self.mid[1]) * self.scale,
            z,
        ])
    }

    /// The unit vector from the scene towards the eye.
    pub fn towards_eye(&self) -> [f32; 3] {
        self.back
    }
}

fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        default
    }
}

pub(super) fn add3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(super) fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn scale3(a: [f32; 3], s: f32) -> [f32; 3] {
    a.map(|x| x * s)
}

pub(super) fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn norm(a: [f32; 3]) -> f32 {
    dot(a, a).sqrt()
}

pub(super) fn normalize(a: [f32; 3]) -> [f32; 3] {
    let n = norm(a);
    if n > 0.0 && n.is_finite() {
        scale3(a, 1.0 / n)
    } else {
        a
    }
}
