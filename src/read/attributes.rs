//! The `ATTR` section and the version-1.0 per-vertex sections `NORM`, `TEXC` and `COLR`, as
//! one list of attribute views that answer "which value at this corner" in constant time on
//! the file's bytes. Their rules (V14, V40–V42, V46) are checked in `rules`.

mod coded;
mod predicted;
mod rules;

use crate::format::attributes::Seams;
use crate::format::quantized::{Quantizer, PREDICTED, QUANTIZED, RAW};
use crate::format::{le_f32, le_u32};
use crate::mesh::{ComponentType, Semantic};
use crate::ops::CornerOps;
use crate::words::Stored as Packed;
use crate::words::Words;
pub(super) use rules::{attributes, Context};

/// One attribute of a container, borrowed from its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct AttributeView<'a> {
    /// What it means.
    pub semantic: Semantic,
    /// Components per value.
    pub components: u8,
    /// Type of each component.
    pub component_type: ComponentType,
    /// Integers stand for fractions.
    pub normalized: bool,
    /// Given per corner (otherwise per vertex).
    pub per_corner: bool,
    /// Raw values (value encoding 0); empty when quantized.
    values: &'a [u8],
    /// Value encodings 1 and 2: how the integers map to values, and the packed words.
    quantized: Option<(Quantizer, Packed<'a>)>,
    value_count: u32,
    extra: u32,
    flagged: u32,
    seams: Option<Seams<Packed<'a>>>,
    /// The seam encoding (FORMAT.md §3.9): 0 tables, 1 coded.
    seam_encoding: u8,
    /// The normal predictor (FORMAT.md §3.9, byte 22): 0 surface, 1 neighbours.
    normal_predictor: u8,
    /// Bytes the attribute takes in the file: its record, or its 1.0 section.
    stored_bytes: u64,
}

impl<'a> AttributeView<'a> {
    /// Bytes the attribute takes in the file: its `ATTR` record (header, name, values and
    /// seam tables), or its version-1.0 section.
    pub fn stored_bytes(&self) -> u64 {
        self.stored_bytes
    }

    /// Values stored: one per container vertex, then the extra ones.
    pub fn value_count(&self) -> u32 {
        self.value_count
    }

    /// Values beyond the vertices' own: the cost of the seams.
    pub fn extra_values(&self) -> u32 {
        self.extra
    }

    /// Triangle slots with a corner on an extra value.
    pub fn flagged_triangles(&self) -> u32 {
        self.flagged
    }

    /// Bytes of one value as the component type stores it (what
    /// [`AttributeView::value_bytes`] gives for a raw record).
    pub fn value_len(&self) -> usize {
        usize::from(self.components) * self.component_type.size()
    }

    /// The value encoding of the record (FORMAT.md §3.9): 0 raw, 1 quantized, 2 predicted.
    pub fn value_encoding(&self) -> u8 {
        match &self.quantized {
            None => RAW,
            Some((_, Packed::File(_))) => QUANTIZED,
            Some((_, Packed::Decoded(_))) => PREDICTED,
        }
    }

    /// The seam encoding of the record (FORMAT.md §3.9): 0 the random-access tables, 1 coded
    /// (decoded when the container was opened).
    pub fn seam_encoding(&self) -> u8 {
        self.seam_encoding
    }

    /// The normal predictor of a record of predicted values (FORMAT.md §3.9, byte 22): 0
    /// from the surface, 1 from the neighbours only; 0 for any other record.
    pub fn normal_predictor(&self) -> u8 {
        self.normal_predictor
    }

    /// How the values are quantized, for a record of value encoding 1 or 2.
    pub fn quantizer(&self) -> Option<Quantizer> {
        self.quantized.as_ref().map(|(q, _)| *q)
    }

    /// The little-endian bytes of value `i` as the file stores them, for a raw record
    /// (value encoding 0); `None` for a quantized record, whose values are integers of a
    /// few bits: read them with [`AttributeView::value_f32`].
    ///
    /// # Panics
    /// When `i` is not below [`AttributeView::value_count`].
    pub fn value_bytes(&self, i: u32) -> Option<&'a [u8]> {
        assert!(i < self.value_count, "value {i} out of range");
        if self.quantized.is_some() {
            return None;
        }
        let n = self.value_len();
        Some(&self.values[n * i as usize..n * i as usize + n])
    }

    /// The integers of value `i` of a quantized record (`c'` of them: 2 for an octahedral
    /// normal, else `c`; the rest 0); `None` for a raw record.
    ///
    /// # Panics
    /// When `i` is not below [`AttributeView::value_count`].
    pub fn value_levels(&self, i: u32) -> Option<[u32; 4]> {
        assert!(i < self.value_count, "value {i} out of range");
        let (q, words) = self.quantized.as_ref()?;
        let mut out = [0; 4];
        q.levels_at(words, i, &mut out);
        Some(out)
    }

    /// Value `i` as f32 numbers (normalized integers mapped to fractions, quantized values
    /// decoded); the components beyond [`AttributeView::components`] are 0.
    ///
    /// # Panics
    /// When `i` is not below [`AttributeView::value_count`].
    pub fn value_f32(&self, i: u32) -> [f32; 4] {
        assert!(i < self.value_count, "value {i} out of range");
        if let Some((q, words)) = &self.quantized {
            return q.value_at(words, i);
        }
        let n = self.value_len();
        let b = &self.values[n * i as usize..n * i as usize + n];
        let size = self.component_type.size();
        let mut out = [0.0; 4];
        for (k, x) in out
            .iter_mut()
            .take(usize::from(self.components))
            .enumerate()
        {
            let c = &b[size * k..size * k + size];
            let raw = match self.component_type {
                ComponentType::I8 => f64::from(c[0] as i8),
                ComponentType::U8 => f64::from(c[0]),
                ComponentType::I16 => f64::from(i16::from_le_bytes([c[0], c[1]])),
                ComponentType::U16 => f64::from(u16::from_le_bytes([c[0], c[1]])),
                ComponentType::U32 => f64::from(le_u32(c, 0)),
                ComponentType::F32 => f64::from(le_f32(c, 0)),
            };
            *x = self.component_type.to_f32(raw, self.normalized);
        }
        out
    }

    /// The value index at corner `k` of triangle slot `t`, whose vertex is `v`.
    pub(super) fn value_index(&self, t: u32, k: usize, v: u32, vertices: u32) -> u32 {
        match &self.seams {
            Some(seams) => seams.value_index(t, k, v, vertices),
            None => v,
        }
    }
}

impl<'a> super::Container<'a> {
    /// Every attribute of the file.
    pub fn attributes(&self) -> &[AttributeView<'a>] {
        &self.attributes
    }

    /// The attribute of `semantic`, if the file has it.
    pub fn attribute(&self, semantic: &Semantic) -> Option<&AttributeView<'a>> {
        self.attributes.iter().find(|a| a.semantic == *semantic)
    }

    /// The triangle slot of corner `c` and its position `k` in its triangle (0 for `t.c`, 1
    /// for `t.c.n`, 2 for `t.c.p`).
    fn slot(&self, c: crate::Corner) -> (u32, usize) {
        let conn = &self.connectivity;
        let t = conn.triangle(c);
        let first = conn.triangle_corner(t);
        let k = if c == first {
            0
        } else if c == conn.next(first) {
            1
        } else {
            2
        };
        (t.0, k)
    }

    /// The index of `a`'s value at corner `c` (for [`AttributeView::value_bytes`] and
    /// [`AttributeView::value_f32`]), in constant time: the vertex's own value unless the
    /// corner's triangle is flagged with an extra value there.
    ///
    /// # Panics
    /// When `c` is not a corner of the connectivity, as the corner operators do.
    pub fn value_index(&self, a: &AttributeView, c: crate::Corner) -> u32 {
        let (t, k) = self.slot(c);
        let v = self.connectivity.vertex(c).0;
        a.value_index(t, k, v, self.vertices)
    }

    /// The index of `a`'s value at corner `k` of kept-aside triangle `j`.
    ///
    /// # Panics
    /// When `j` is not below [`Container::kept_triangle_count`](super::Container::kept_triangle_count) or `k > 2`.
    pub fn kept_value_index(&self, a: &AttributeView, j: u32, k: usize) -> u32 {
        assert!(
            k < 3 && (j as usize) < self.kept.count() / 3,
            "kept corner {j}:{k} out of range"
        );
        let v = self.kept.at(3 * j as usize + k);
        a.value_index(
            self.connectivity.triangle_id_bound() + j,
            k,
            v,
            self.vertices,
        )
    }

    /// The parts' labels, when the file has them.
    pub fn parts(&self) -> Option<&super::PartsView<'a>> {
        self.parts.as_ref()
    }

    /// The part index of triangle `t` of the connectivity, when the file has parts.
    pub fn part_index(&self, t: crate::Triangle) -> Option<u32> {
        self.parts.as_ref().map(|p| p.part_of_slot(t.0))
    }

    /// The part index of kept-aside triangle `j`, when the file has parts.
    pub fn kept_part_index(&self, j: u32) -> Option<u32> {
        let slot = self.connectivity.triangle_id_bound() + j;
        self.parts.as_ref().map(|p| p.part_of_slot(slot))
    }
}
