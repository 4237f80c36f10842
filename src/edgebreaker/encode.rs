//! Compression: the Edgebreaker traversal of every component (paper, Appendix B, with the
//! boundary and handle `S` of sections 5 and 6), then the topology stream and the CLERS stream.

use super::coder::Encoder;
use super::rebuild::{rebuild, Known};
use super::topology::code_topology;
use super::{next, prev, sym, Comp, Decoded, EdgebreakerStats, Encoded, Topology, MAGIC, VERSION};
use crate::corner_table::NONE;
use crate::error::{Error, Result};
use crate::ops::CornerOps;
use crate::CornerTable;

/// The traversal's output, before entropy coding.
pub(crate) struct Plan {
    /// Symbol of each decode triangle (`P` for the implicit first triangles).
    pub symbols: Vec<u8>,
    /// Boundary `S`: (decode triangle, length of the hole it reaches), increasing.
    pub holes: Vec<(u32, u32)>,
    pub topology: Topology,
    pub vertex_order: Vec<u32>,
    pub triangle_order: Vec<u32>,
    /// Tip corner (table) of each decode triangle.
    pub entry: Vec<u32>,
    /// Vertices used by triangles (they come first in `vertex_order`).
    pub referenced: u32,
}

struct Walker<'a> {
    v: &'a [u32],
    o: &'a [u32],
    visited_t: Vec<bool>,
    visited_v: Vec<bool>,
    loop_of: Vec<u32>,
    loop_touched: Vec<bool>,
    /// Decode position of each table triangle.
    pos_of: Vec<u32>,
    /// Tip corner (table) of each decode triangle.
    entry: Vec<u32>,
    symbols: Vec<u8>,
    holes: Vec<(u32, u32)>,
    handles: Vec<(u32, u32)>,
    vertex_order: Vec<u32>,
    stack: Vec<(u32, u32, bool)>,
}

impl Walker<'_> {
    /// Calls `f` on each vertex of the boundary curve through corner `a`, starting with `a`'s
    /// vertex and going along the boundary half-edges; `a` must be at the outgoing end of its
    /// fan (the edge facing `a.p` is a boundary edge).
    fn for_loop(&self, mut a: u32, mut f: impl FnMut(u32)) {
        let start = self.v[a as usize];
        loop {
            f(self.v[a as usize]);
            let mut b = next(a);
            while self.o[prev(b) as usize] != NONE {
                b = prev(self.o[prev(b) as usize]);
            }
            a = b;
            if self.v[a as usize] == start {
                return;
            }
        }
    }

    /// Moves `a` around its vertex (direction D2) to the outgoing end of its fan.
    fn outgoing_end(&self, mut a: u32) -> u32 {
        while self.o[prev(a) as usize] != NONE {
            a = prev(self.o[prev(a) as usize]);
        }
        a
    }

    fn visit(&mut self, c: u32, s: u8) -> u32 {
        let t = self.symbols.len() as u32;
        crate::progress::tick(t as usize);
        self.visited_t[(c / 3) as usize] = true;
        self.pos_of[(c / 3) as usize] = t;
        self.entry.push(c);
        self.symbols.push(s);
        t
    }

    fn mark_vertex(&mut self, x: u32) {
        self.visited_v[x as usize] = true;
        self.vertex_order.push(x);
    }

    /// Numbers the boundary curve through `a` (at the outgoing end of its fan) and marks it
    /// touched; returns its length.
    fn number_loop(&mut self, a: u32) -> u32 {
        let id = self.loop_of[self.v[a as usize] as usize];
        self.loop_touched[id as usize] = true;
        let mut order = std::mem::take(&mut self.vertex_order);
        let before = order.len();
        self.for_loop(a, |x| order.push(x));
        let len = (order.len() - before) as u32;
        self.vertex_order = order;
        len
    }

    /// The decode corner of table corner `k` (whose triangle has been visited).
    fn decode_corner(&self, k: u32) -> u32 {
        let t = self.pos_of[(k / 3) as usize];
        let e = self.entry[t as usize];
        3 * t + (k % 3 + 3 - e % 3) % 3
    }

    /// The traversal of one component from corner `c` (the paper's `CompressComponent`).
    fn traverse(&mut self, mut c: u32) -> Result<()> {
        loop {
            let tip = self.v[c as usize];
            let r = self.o[next(c) as usize];
            let l = self.o[prev(c) as usize];
            let r_done = r == NONE || self.visited_t[(r / 3) as usize];
            let l_done = l == NONE || self.visited_t[(l / 3) as usize];
            if !self.visited_v[tip as usize] {
                self.visit(c, sym::C);
                self.mark_vertex(tip);
                c = r;
                continue;
            }
            if !r_done && !l_done {
                let t = self.visit(c, sym::S);
                let lp = self.loop_of[tip as usize];
                let hole = lp != NONE && !self.loop_touched[lp as usize];
                if hole {
                    let a = self.outgoing_end(c);
                    let len = self.number_loop(a);
                    self.holes.push((t, len));
                }
                self.stack.push((l, t, hole));
                c = r;
                continue;
            }
            if !r_done {
                self.visit(c, sym::L);
                c = r;
                continue;
            }
            if !l_done {
                self.visit(c, sym::R);
                c = l;
                continue;
            }
            self.visit(c, sym::E);
            loop {
                let Some((lc, t, hole)) = self.stack.pop() else {
                    return Ok(());
                };
                if !self.visited_t[(lc / 3) as usize] {
                    if hole {
                        return Err(Error::Internal(
                            "Edgebreaker: boundary S whose left triangle was not reached".into(),
                        ));
                    }
                    c = lc;
                    break;
                }
                if !hole {
                    let partner = self.decode_corner(lc);
                    self.handles.push((t, partner));
                }
            }
        }
    }
}

/// Runs the traversal over the whole table.
pub(crate) fn plan(table: &CornerTable) -> Result<Plan> {
    let v = table.v_table();
    let o = table.o_table();
    let nt = v.len() / 3;
    let nv = table.vertex_id_bound() as usize;
    crate::progress::phase("edgebreaker", nt as u64);
    let mut w = Walker {
        v,
        o,
        visited_t: vec![false; nt],
        visited_v: vec![false; nv],
        loop_of: vec![NONE; nv],
        loop_touched: Vec::new(),
        pos_of: vec![NONE; nt],
        entry: Vec::with_capacity(nt),
        symbols: Vec::with_capacity(nt),
        holes: Vec::new(),
        handles: Vec::new(),
        vertex_order: Vec::with_capacity(nv),
        stack: Vec::new(),
    };
    // Boundary curves: number them, mark their vertices visited.
    for k in 0..3 * nt as u32 {
        if o[k as usize] == NONE {
            let a = next(k);
            if w.loop_of[v[a as usize] as usize] == NONE {
                let id = w.loop_touched.len() as u32;
                w.loop_touched.push(false);
                let mut members = Vec::new();
                w.for_loop(a, |x| members.push(x));
                for x in members {
                    w.loop_of[x as usize] = id;
                    w.visited_v[x as usize] = true;
                }
            }
        }
    }
    let mut comps = Vec::new();
    // Components with boundary, each from the first free boundary edge found.
    for k in 0..3 * nt as u32 {
        if o[k as usize] == NONE && !w.visited_t[(k / 3) as usize] {
            let start = w.symbols.len() as u32;
            w.number_loop(next(k));
            w.traverse(k)?;
            comps.push(Comp {
                start,
                size: w.symbols.len() as u32 - start,
                closed: false,
            });
        }
    }
    // Closed components.
    for t in 0..nt as u32 {
        if !w.visited_t[t as usize] {
            let start = w.symbols.len() as u32;
            let c0 = 3 * t;
            w.visit(c0, sym::P);
            for c in [c0, next(c0), prev(c0)] {
                w.mark_vertex(v[c as usize]);
            }
            w.traverse(o[c0 as usize])?;
            comps.push(Comp {
                start,
                size: w.symbols.len() as u32 - start,
                closed: true,
            });
        }
    }
    let referenced = w.vertex_order.len() as u32;
    let c_table = table.c_table();
    w.vertex_order
        .extend((0..nv as u32).filter(|&x| c_table[x as usize] == NONE));
    if w.vertex_order.len() != nv {
        return Err(Error::Internal(
            "Edgebreaker: a vertex was numbered twice or never".into(),
        ));
    }
    w.handles.sort_unstable();
    let triangle_order = w.entry.iter().map(|&c| c / 3).collect();
    Ok(Plan {
        symbols: w.symbols,
        holes: w.holes,
        topology: Topology {
            comps,
            handles: w.handles,
        },
        vertex_order: w.vertex_order,
        triangle_order,
        entry: w.entry,
        referenced,
    })
}

struct PlanKnown<'a> {
    symbols: &'a [u8],
    holes: &'a [(u32, u32)],
    hi: usize,
}

impl Known for PlanKnown<'_> {
    fn symbol(&mut self, t: u32) -> u8 {
        self.symbols[t as usize]
    }
    fn hole(&mut self, t: u32) -> u32 {
        if self.hi > 0 && self.holes[self.hi - 1].0 == t {
            self.hi -= 1;
            self.holes[self.hi].1
        } else {
            0
        }
    }
}

fn leb128(out: &mut Vec<u8>, mut x: u64) {
    loop {
        let byte = (x & 0x7F) as u8;
        x >>= 7;
        if x == 0 {
            out.push(byte);
            return;
        }
        out.push(byte | 0x80);
    }
}

/// Encodes the connectivity of `table`.
///
/// # Errors
/// [`Error::Internal`] if the table's invariants do not hold (they always do for a table
/// built by [`CornerTable::build`]), or if the stream fails to rebuild the table (a bug).
pub fn encode(table: &CornerTable) -> Result<Encoded> {
    encode_glued(table, false).map(|(encoded, _)| encoded)
}

/// The decoded stream and the opposite of every corner, as [`super::decode_glued`] gives them.
pub(crate) type Glued = (Decoded, Vec<u32>);

/// [`encode`], and with `glued` what [`super::decode_glued`] gives back for the stream (the
/// pass that writes it rebuilds the same triangles and glues the same edges), without
/// decoding it.
pub(crate) fn encode_glued(table: &CornerTable, glued: bool) -> Result<(Encoded, Option<Glued>)> {
    let plan = plan(table)?;
    let nt = plan.symbols.len() as u32;
    let nv = plan.vertex_order.len() as u64;

    let mut topo = Encoder::new();
    code_topology(&mut topo, Some(&plan.topology), nt)?;
    let topo = topo.finish();

    let mut clers = Encoder::new();
    let mut known = PlanKnown {
        symbols: &plan.symbols,
        holes: &plan.holes,
        hi: plan.holes.len(),
    };
    let super::rebuild::Rebuilt {
        triangles: rebuilt,
        opposites,
        tally,
    } = rebuild(
        &mut clers,
        &mut known,
        &plan.topology,
        (nt, plan.referenced),
        glued,
    )
    .map_err(|e| Error::Internal(format!("Edgebreaker encoder could not rebuild: {e}")))?;
    let clers = clers.finish();
    // The stream must give back the table: check every corner (linear, and cheap next to
    // the traversal).
    let v = table.v_table();
    for (t, tri) in rebuilt.iter().enumerate() {
        let e = plan.entry[t];
        for (i, c) in [e, next(e), prev(e)].into_iter().enumerate() {
            if plan.vertex_order[tri[i] as usize] != v[c as usize] {
                return Err(Error::Internal(format!(
                    "Edgebreaker encoder: decode triangle {t} does not match the table"
                )));
            }
        }
    }

    let mut bytes = vec![MAGIC, VERSION];
    leb128(&mut bytes, nv);
    leb128(&mut bytes, nv - plan.referenced as u64);
    leb128(&mut bytes, nt as u64);
    leb128(&mut bytes, topo.len() as u64);
    let topology_bytes = (bytes.len() + topo.len()) as u64;
    bytes.extend_from_slice(&topo);
    bytes.extend_from_slice(&clers);

    let count = |s: u8| plan.symbols.iter().filter(|&&x| x == s).count() as u64;
    let per_triangle = |n: usize| {
        if nt == 0 {
            0.0
        } else {
            8.0 * n as f64 / nt as f64
        }
    };
    let stats = EdgebreakerStats {
        triangles: nt as u64,
        vertices: nv,
        bytes: bytes.len() as u64,
        bpt: per_triangle(bytes.len()),
        clers_bpt: per_triangle(clers.len()),
        topology_bytes,
        c: count(sym::C),
        l: count(sym::L),
        e: count(sym::E),
        r: count(sym::R),
        s: count(sym::S),
        handle_s: plan.topology.handles.len() as u64,
        boundary_s: tally.holes,
        p: count(sym::P),
        components: plan.topology.comps.len() as u64,
        boundary_components: plan.topology.comps.iter().filter(|c| !c.closed).count() as u64,
    };
    let glued = glued.then(|| {
        let decoded = Decoded {
            vertex_count: nv as u32,
            triangles: rebuilt,
        };
        (decoded, opposites)
    });
    let encoded = Encoded {
        bytes,
        vertex_order: plan.vertex_order,
        triangle_order: plan.triangle_order,
        stats,
    };
    Ok((encoded, glued))
}
