//! Static prefix codes (GEOMETRY.md §9.3): canonical, length-limited Huffman codes described by
//! their code lengths, written and read least significant bit first as in Deflate, so that a
//! decoder takes a symbol in one table lookup. Used where decode speed matters more than the
//! last percent of size (`GEOM` encoding 6).

/// The longest code: a decoding table has `2^MAX_LEN` entries.
pub(crate) const MAX_LEN: u32 = 11;

/// Code lengths (0: the symbol has no code) of a length-limited Huffman code for `counts`, by
/// package-merge: the optimal code whose lengths are at most [`MAX_LEN`]. One used symbol gets
/// length 1; no used symbol, all zeros.
pub(crate) fn code_lengths(counts: &[u64]) -> Vec<u8> {
    let mut lengths = vec![0u8; counts.len()];
    let mut leaves: Vec<(u64, usize)> = (0..counts.len())
        .filter(|&s| counts[s] > 0)
        .map(|s| (counts[s], s))
        .collect();
    match leaves.len() {
        0 => return lengths,
        1 => {
            lengths[leaves[0].1] = 1;
            return lengths;
        }
        _ => {}
    }
    debug_assert!(leaves.len() <= 1 << MAX_LEN);
    leaves.sort_unstable();
    // An item is a weight and how many times each leaf is in it.
    let n = leaves.len();
    let leaf_items: Vec<(u64, Vec<u8>)> = leaves
        .iter()
        .enumerate()
        .map(|(i, &(w, _))| {
            let mut in_it = vec![0u8; n];
            in_it[i] = 1;
            (w, in_it)
        })
        .collect();
    let mut list = leaf_items.clone();
    for _ in 1..MAX_LEN {
        let packages = list.chunks_exact(2).map(|pair| {
            let counts = pair[0].1.iter().zip(&pair[1].1).map(|(a, b)| a + b);
            (pair[0].0 + pair[1].0, counts.collect::<Vec<u8>>())
        });
        let mut merged: Vec<(u64, Vec<u8>)> = leaf_items.iter().cloned().chain(packages).collect();
        // Stable: a leaf before a package of the same weight.
        merged.sort_by_key(|item| item.0);
        list = merged;
    }
    for item in &list[..2 * n - 2] {
        for (i, &k) in item.1.iter().enumerate() {
            lengths[leaves[i].1] += k;
        }
    }
    lengths
}

/// The canonical codes of `lengths` (Deflate's assignment: shorter codes first, then by
/// symbol), each bit-reversed so that it is written least significant bit first. `None` when
/// the lengths oversubscribe the code space or exceed [`MAX_LEN`].
pub(crate) fn canonical_codes(lengths: &[u8]) -> Option<Vec<u32>> {
    let mut per_length = [0u32; MAX_LEN as usize + 1];
    for &l in lengths {
        *per_length.get_mut(l as usize)? += 1;
    }
    per_length[0] = 0;
    // Kraft: the codes of each length must fit in what the shorter ones leave.
    let mut next = [0u32; MAX_LEN as usize + 2];
    let mut code = 0u32;
    for len in 1..=MAX_LEN as usize {
        code = (code + per_length[len - 1]) << 1;
        next[len] = code;
        if code + per_length[len] > 1 << len {
            return None;
        }
    }
    Some(
        lengths
            .iter()
            .map(|&l| {
                if l == 0 {
                    return 0;
                }
                let c = next[l as usize];
                next[l as usize] += 1;
                c.reverse_bits() >> (32 - l as u32)
            })
            .collect(),
    )
}

/// A decoding table: entry `i` for the next [`MAX_LEN`] bits `i` of the stream holds the
/// symbol (high byte) and its code length (low byte, 0 for bits that start no code).
pub(crate) struct DecodeTable(Box<[u16; 1 << MAX_LEN]>);

impl DecodeTable {
    /// The table of `lengths` (at most 256 symbols); `None` as for [`canonical_codes`].
    pub(crate) fn new(lengths: &[u8]) -> Option<DecodeTable> {
        debug_assert!(lengths.len() <= 256);
        let codes = canonical_codes(lengths)?;
        let mut table = Box::new([0u16; 1 << MAX_LEN]);
        for (s, (&l, &code)) in lengths.iter().zip(&codes).enumerate() {
            if l > 0 {
                let entry = ((s as u16) << 8) | l as u16;
                let mut i = code as usize;
                while i < 1 << MAX_LEN {
                    table[i] = entry;
                    i += 1 << l;
                }
            }
        }
        Some(DecodeTable(table))
    }

    /// The entry of the next bits `peek` (only the low [`MAX_LEN`] are looked at).
    #[inline(always)]
    pub(crate) fn entry(&self, peek: u64) -> u16 {
        self.0[(peek & ((1 << MAX_LEN) - 1)) as usize]
    }
}

/// Writes bits least significant first into bytes.
#[derive(Default)]
pub(crate) struct BitWriter {
    bytes: Vec<u8>,
    buffer: u64,
    filled: u32,
}

impl BitWriter {
    /// Appends the low `n` bits of `bits` (`n` at most 32).
    pub(crate) fn put(&mut self, bits: u32, n: u32) {
        debug_assert!(n <= 32 && (n == 32 || bits >> n == 0));
        self.buffer |= (bits as u64) << self.filled;
        self.filled += n;
        while self.filled >= 8 {
            self.bytes.push(self.buffer as u8);
            self.buffer >>= 8;
            self.filled -= 8;
        }
    }

    /// The bytes, the last one padded with zero bits.
    pub(crate) fn finish(mut self) -> Vec<u8> {
        if self.filled > 0 {
            self.bytes.push(self.buffer as u8);
        }
        self.bytes
    }
}

/// Bytes past the end of a stream that a [`BitReader`] may look at (zeros).
const PADDING: usize = 64;

/// Reads bits least significant first; looking past the end sees zero bits, and
/// [`BitReader::overrun`] says whether bits past the end were consumed.
pub(crate) struct BitReader {
    bytes: Vec<u8>,
    /// Bits consumed.
    at: usize,
    len_bits: usize,
}

impl BitReader {
    /// A reader over a copy of `stream` with zero padding (so that a peek is one load).
    pub(crate) fn new(stream: &[u8]) -> BitReader {
        let mut bytes = Vec::with_capacity(stream.len() + PADDING);
        bytes.extend_from_slice(stream);
        bytes.resize(stream.len() + PADDING, 0);
        BitReader {
            bytes,
            at: 0,
            len_bits: 8 * stream.len(),
        }
    }

    /// The next 57 bits or more, without consuming them. Call [`BitReader::overrun`] at
    /// least every 256 bits consumed: past the padding, a peek sees zeros only.
    #[inline(always)]
    pub(crate) fn peek(&self) -> u64 {
        let byte = (self.at >> 3).min(self.bytes.len() - 8);
        let word = u64::from_le_bytes(self.bytes[byte..byte + 8].try_into().unwrap());
        word >> (self.at & 7)
    }

    /// Consumes `n` bits.
    #[inline(always)]
    pub(crate) fn consume(&mut self, n: u32) {
        self.at += n as usize;
    }

    /// Whether more bits were consumed than the stream holds.
    pub(crate) fn overrun(&self) -> bool {
        self.at > self.len_bits
    }

    /// Bits consumed so far.
    pub(crate) fn position(&self) -> usize {
        self.at
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lengths of `counts` form a complete code, never longer than the limit, and cost
    /// no more than a plain Huffman code when that fits.
    #[test]
    fn lengths_are_complete_and_limited() {
        let mut rng = crate::rng::Rng::new(5);
        for case in 0..300 {
            let n = 2 + rng.below(60) as usize;
            let counts: Vec<u64> = (0..n)
                .map(|i| match case % 3 {
                    0 => rng.below(1000) as u64,
                    1 => 1u64 << (i % 40),
                    _ => (rng.below(3) as u64) * (1 + rng.below(100000) as u64),
                })
                .collect();
            let lengths = code_lengths(&counts);
            let used = counts.iter().filter(|&&c| c > 0).count();
            for (&c, &l) in counts.iter().zip(&lengths) {
                assert_eq!(c > 0, l > 0);
                assert!(l as u32 <= MAX_LEN);
            }
            if used >= 2 {
                let kraft: f64 = lengths
                    .iter()
                    .filter(|&&l| l > 0)
                    .map(|&l| 0.5f64.powi(l as i32))
                    .sum();
                assert!((kraft - 1.0).abs() < 1e-12, "kraft {kraft}");
            }
            assert!(canonical_codes(&lengths).is_some());
        }
    }

    #[test]
    fn symbols_round_trip_through_the_table() {
        let counts: Vec<u64> = (0..40).map(|i| 1 + (i * 37 % 11) as u64 * 100).collect();
        let lengths = code_lengths(&counts);
        let codes = canonical_codes(&lengths).unwrap();
        let table = DecodeTable::new(&lengths).unwrap();
        let mut w = BitWriter::default();
        let symbols: Vec<usize> = (0..500).map(|i| (i * 7919) % 40).collect();
        for &s in &symbols {
            w.put(codes[s], lengths[s] as u32);
            w.put(s as u32 & 1, 1);
        }
        let bytes = w.finish();
        let mut r = BitReader::new(&bytes);
        for &s in &symbols {
            let e = table.entry(r.peek());
            assert_eq!((e >> 8) as usize, s);
            r.consume(e as u32 & 0xFF);
            assert_eq!(r.peek() & 1, s as u64 & 1);
            r.consume(1);
        }
        assert!(!r.overrun());
        r.consume(8);
        assert!(r.overrun());
    }

    #[test]
    fn oversubscribed_lengths_are_refused() {
        assert!(canonical_codes(&[1, 1, 1]).is_none());
        assert!(canonical_codes(&[1, 2, 2, 3]).is_none());
        assert!(canonical_codes(&[12]).is_none());
        // Incomplete codes are allowed: their missing patterns start no code.
        let table = DecodeTable::new(&[0, 1]).unwrap();
        assert_eq!(table.entry(0), (1 << 8) | 1);
        assert_eq!(table.entry(1), 0);
    }
}
