//! Node transforms: 4×4 matrices, column-major as glTF stores them, in f64.

/// A column-major 4×4 matrix: element (row r, column c) is `m[4c + r]`.
pub(super) type Matrix = [f64; 16];

pub(super) const IDENTITY: Matrix = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// `a × b`.
pub(super) fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| {
        let (c, r) = (i / 4, i % 4);
        (0..4).map(|k| a[4 * k + r] * b[4 * c + k]).sum()
    })
}

/// `translation × rotation × scale`, the rotation a quaternion `[x, y, z, w]` (normalized
/// here); `None` for a zero quaternion.
pub(super) fn trs(t: [f64; 3], q: [f64; 4], s: [f64; 3]) -> Option<Matrix> {
    let len = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len <= 0.0 || !len.is_finite() {
        return None;
    }
    let [x, y, z, w] = q.map(|v| v / len);
    let rotation = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * w),
            2.0 * (x * z - y * w),
        ],
        [
            2.0 * (x * y - z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + x * w),
        ],
        [
            2.0 * (x * z + y * w),
            2.0 * (y * z - x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]; // rotation[c][r]: column c
    let mut m = IDENTITY;
    for c in 0..3 {
        for r in 0..3 {
            m[4 * c + r] = rotation[c][r] * s[c];
        }
    }
    m[12..15].copy_from_slice(&t);
    Some(m)
}

/// What a world matrix does to positions and normals.
pub(super) struct Placement {
    matrix: Matrix,
    /// Cofactors of the 3×3 part times the sign of its determinant: the inverse transpose up
    /// to a positive factor, defined even for a singular matrix.
    normal_matrix: [[f64; 3]; 3],
    identity: bool,
    mirrors: bool,
}

impl Placement {
    pub fn new(matrix: Matrix) -> Placement {
        let a = |r: usize, c: usize| matrix[4 * c + r];
        let cof = |r: usize, c: usize| {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1)
        };
        let det = (0..3).map(|c| a(0, c) * cof(0, c)).sum::<f64>();
        let sign = if det < 0.0 { -1.0 } else { 1.0 };
        Placement {
            matrix,
            normal_matrix: std::array::from_fn(|r| std::array::from_fn(|c| sign * cof(r, c))),
            identity: matrix == IDENTITY,
            mirrors: det < 0.0,
        }
    }

    /// Whether nothing changes.
    pub fn is_identity(&self) -> bool {
        self.identity
    }

    /// Whether the matrix mirrors (negative determinant): triangles turn clockwise.
    pub fn mirrors(&self) -> bool {
        self.mirrors
    }

    /// The placed position (may be non-finite for huge inputs; the caller checks).
    pub fn position(&self, p: [f32; 3]) -> [f32; 3] {
        if self.identity {
            return p;
        }
        let m = &self.matrix;
        std::array::from_fn(|r| {
            let v = (0..3).map(|c| m[4 * c + r] * f64::from(p[c])).sum::<f64>() + m[12 + r];
            v as f32
        })
    }

    /// The placed normal, of unit length (zero stays zero).
    pub fn normal(&self, n: [f32; 3]) -> [f32; 3] {
        if self.identity {
            return n;
        }
        let t: [f64; 3] = std::array::from_fn(|r| {
            (0..3)
                .map(|c| self.normal_matrix[r][c] * f64::from(n[c]))
                .sum()
        });
        let len = t.iter().map(|x| x * x).sum::<f64>().sqrt();
        if len > 0.0 && len.is_finite() {
            t.map(|x| (x / len) as f32)
        } else {
            [0.0; 3]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_about_z_turns_x_into_y() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let m = trs([1.0, 2.0, 3.0], [0.0, 0.0, h, h], [2.0, 2.0, 2.0]).unwrap();
        let p = Placement::new(m);
        let q = p.position([1.0, 0.0, 0.0]);
        assert!(
            (q[0] - 1.0).abs() < 1e-6 && (q[1] - 4.0).abs() < 1e-6 && (q[2] - 3.0).abs() < 1e-6
        );
        let n = p.normal([1.0, 0.0, 0.0]);
        assert!(n[0].abs() < 1e-6 && (n[1] - 1.0).abs() < 1e-6);
        assert!(!p.mirrors());
    }

    #[test]
    fn non_uniform_scale_uses_the_inverse_transpose() {
        let m = trs([0.0; 3], [0.0, 0.0, 0.0, 1.0], [2.0, 1.0, 1.0]).unwrap();
        let p = Placement::new(m);
        // The plane x + y = 0 scaled by 2 in x becomes x/2 + y = 0: normal (1/2, 1) normalized.
        let n = p.normal([
            std::f32::consts::FRAC_1_SQRT_2,
            std::f32::consts::FRAC_1_SQRT_2,
            0.0,
        ]);
        let want = [0.5f32, 1.0, 0.0].map(|x| x / 1.25f32.sqrt());
        assert!((0..3).all(|i| (n[i] - want[i]).abs() < 1e-6), "{n:?}");
    }

    #[test]
    fn mirror_keeps_normals_outward() {
        let m = trs([0.0; 3], [0.0, 0.0, 0.0, 1.0], [-1.0, 1.0, 1.0]).unwrap();
        let p = Placement::new(m);
        assert!(p.mirrors());
        assert_eq!(p.normal([1.0, 0.0, 0.0]), [-1.0, 0.0, 0.0]);
        assert_eq!(trs([0.0; 3], [0.0; 4], [1.0; 3]), None);
        let i = Placement::new(IDENTITY);
        assert_eq!(
            i.position([-0.0, 1.0, 2.0])[0].to_bits(),
            (-0.0f32).to_bits()
        );
        assert_eq!(multiply(&IDENTITY, &m), m);
    }
}
