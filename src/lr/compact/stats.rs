//! The statistics of a bit-efficient LR ([`CompactStats`], shown by `lrmesh stats` and
//! serialised as its JSON object `lr_compact`): triangle classes, records, overflow rows and
//! bytes, computed from a built [`CompactLr`]. Reporting only, apart from construction and
//! decoding.

use super::CompactLr;
use crate::ids::Triangle;
use crate::lr::tables::{LrLayout, LEFT, RIGHT};
use crate::lr::{LrInspect, TriangleClass};

/// The bit-efficient LR's statistics (`lrmesh stats`, JSON object `lr_compact`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CompactStats {
    /// The HYBRID-RING-EXPANDER period chosen (0: depth first).
    pub k: u32,
    /// Triangles `n` (degenerate ones, kept aside, not counted).
    pub triangles: u32,
    /// Isolated vertices `m_i`.
    pub isolated_vertices: u32,
    /// Percentage of T0 triangles after wart skipping.
    pub t0_pct: f64,
    /// Percentage of T0 triangles in a wart's slot.
    pub t0w_pct: f64,
    /// Percentage of irregular T1 triangles (T0^w included, stored as T1).
    pub t1i_pct: f64,
    /// Percentage of irregular T2 triangles.
    pub t2i_pct: f64,
    /// Percentage of pairs with a record (long references or irregular slots), of triangles.
    pub tl_pct: f64,
    /// Percentage of T0 rows whose fields overflow to 32 bits, of triangles.
    pub t0_overflow_pct: f64,
    /// Bytes of the `LRBE` section.
    pub bytes: u64,
    /// Connectivity bits per triangle: every byte of the `LRBE` section.
    pub bpt: f64,
}

impl CompactStats {
    pub(super) fn new(lr: &CompactLr) -> CompactStats {
        let t = &lr.tables;
        let counts = lr.counts();
        let n = counts.triangles.max(1) as f64;
        let pct = |x: usize| 100.0 * x as f64 / n;
        let (mut t1i, mut t2i) = (0, 0);
        for v in 0..t.m_r {
            for side in [LEFT, RIGHT] {
                if t.irregular(v, side) {
                    // T0^w slots are stored as T1s, so they count there.
                    match t.triangle_class(Triangle(2 * v + side as u32)) {
                        Some(TriangleClass::T2 | TriangleClass::T2Wart) => t2i += 1,
                        _ => t1i += 1,
                    }
                }
            }
        }
        let extended = (0..t.m_r).filter(|&v| t.is_extended(v)).count();
        let bytes = lr.stored_bytes();
        CompactStats {
            k: lr.period,
            triangles: counts.triangles,
            isolated_vertices: counts.isolated_vertices(),
            t0_pct: pct(counts.t0 as usize),
            t0w_pct: pct(counts.t0_wart as usize),
            t1i_pct: pct(t1i),
            t2i_pct: pct(t2i),
            tl_pct: pct(extended),
            t0_overflow_pct: pct(t.overflow_rows() as usize),
            bytes,
            bpt: 8.0 * bytes as f64 / n,
        }
    }
}

impl std::fmt::Display for CompactStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "bit-efficient LR")?;
        writeln!(f, "  period k                 {}", self.k)?;
        writeln!(f, "  isolated vertices m_i    {}", self.isolated_vertices)?;
        writeln!(f, "  T0 (after wart skipping) {:.2}%", self.t0_pct)?;
        writeln!(f, "  T0^w                     {:.2}%", self.t0w_pct)?;
        writeln!(f, "  T1^i                     {:.2}%", self.t1i_pct)?;
        writeln!(f, "  T2^i                     {:.2}%", self.t2i_pct)?;
        writeln!(f, "  pairs with a record      {:.2}%", self.tl_pct)?;
        writeln!(f, "  bytes                    {}", self.bytes)?;
        writeln!(f, "  bits per triangle        {:.2}", self.bpt)
    }
}
