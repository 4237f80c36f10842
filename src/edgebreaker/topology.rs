//! The topology stream: component counts and sizes, and the handle `S` triangles with the
//! corner glued to each one's left edge. Written once for encoder and decoder (see
//! [`super::coder::Bits`]); the decoder checks every value against the triangle count.

use super::coder::{uint_or, Bits, UintModel};
use super::{malformed, Comp, Topology};
use crate::error::Result;

#[derive(Default)]
struct Models {
    counts: UintModel,
    boundary_sizes: UintModel,
    closed_sizes: UintModel,
    gaps: UintModel,
    spans: UintModel,
}

/// Codes `known` (encoder) or decodes the topology of `nt` triangles (decoder, `known` is
/// `None`). The decoder returns components that exactly cover `0..nt` and handles that each
/// lie inside one component, away from its first and last triangle, with the glued corner in
/// a later triangle of the same component and not its tip.
pub(crate) fn code_topology<B: Bits>(
    b: &mut B,
    known: Option<&Topology>,
    nt: u32,
) -> Result<Topology> {
    let mut m = Models::default();
    let bad = |off: u64, what: &str| malformed(off, format!("topology stream: {what}"));
    let uint_err = |off| bad(off, "integer too long");

    let kn_boundary = known.map_or(0, |k| k.comps.iter().filter(|c| !c.closed).count());
    let kn_closed = known.map_or(0, |k| k.comps.len()) - kn_boundary;
    let n_boundary = uint_or(b, &mut m.counts, kn_boundary as u64, uint_err)?;
    let n_closed = uint_or(b, &mut m.counts, kn_closed as u64, uint_err)?;
    if n_boundary + n_closed > nt as u64 {
        return Err(bad(b.offset(), "more components than triangles"));
    }
    let mut comps = Vec::new();
    let mut start = 0u32;
    for i in 0..(n_boundary + n_closed) as usize {
        let closed = i as u64 >= n_boundary;
        let (model, min) = if closed {
            (&mut m.closed_sizes, 2)
        } else {
            (&mut m.boundary_sizes, 1)
        };
        let kn = known.map_or(0, |k| k.comps[i].size - min) as u64;
        let size = uint_or(b, model, kn, uint_err)? + min as u64;
        if size > (nt - start) as u64 {
            return Err(bad(b.offset(), "component sizes exceed the triangle count"));
        }
        comps.push(Comp {
            start,
            size: size as u32,
            closed,
        });
        start += size as u32;
    }
    if start != nt {
        return Err(bad(
            b.offset(),
            "component sizes do not add up to the triangle count",
        ));
    }

    let n_handles = uint_or(
        b,
        &mut m.counts,
        known.map_or(0, |k| k.handles.len()) as u64,
        uint_err,
    )?;
    if n_handles > nt as u64 {
        return Err(bad(b.offset(), "more handles than triangles"));
    }
    let mut handles = Vec::new();
    let mut next_free = 0u64; // handles are strictly increasing
    let mut ci = 0usize;
    for i in 0..n_handles as usize {
        let (kgap, kspan, krole) = known.map_or((0, 0, 0), |k| {
            let (t, c) = k.handles[i];
            (t as u64 - next_free, (c / 3 - t - 1) as u64, c % 3 - 1)
        });
        let gap = uint_or(b, &mut m.gaps, kgap, uint_err)?;
        let t = next_free + gap;
        if t >= nt as u64 {
            return Err(bad(b.offset(), "handle triangle out of range"));
        }
        let t = t as u32;
        while ci < comps.len() && comps[ci].start + comps[ci].size <= t {
            ci += 1;
        }
        let comp = comps[ci]; // exists: components cover 0..nt
        let last = comp.start + comp.size - 1;
        if t == last || (comp.closed && t == comp.start) {
            return Err(bad(
                b.offset(),
                "handle at the first or last triangle of a component",
            ));
        }
        let span = uint_or(b, &mut m.spans, kspan, uint_err)?;
        let role = b.raw(krole) + 1;
        if span >= (last - t) as u64 {
            return Err(bad(b.offset(), "handle corner outside its component"));
        }
        let other = t + 1 + span as u32;
        handles.push((t, 3 * other + role));
        next_free = t as u64 + 1;
    }
    Ok(Topology { comps, handles })
}
