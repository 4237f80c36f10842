//! Tables as arrays of fixed-size integers, owned (`Vec`) or read in place from
//! little-endian bytes: the storage that every representation's tables are generic over, so
//! that the same operator code runs on a built structure and on a loaded file.

/// An array of 32-bit words: a vector, or little-endian bytes read in place.
pub trait Words {
    /// Word `i`. Panics when `i` is out of range; validation guarantees it never is.
    fn at(&self, i: usize) -> u32;
    /// Number of words.
    fn count(&self) -> usize;
    /// Words `i .. i + N`, with one bounds check where the storage allows it.
    #[inline(always)]
    fn array<const N: usize>(&self, i: usize) -> [u32; N] {
        std::array::from_fn(|k| self.at(i + k))
    }
    /// [`array`](Self::array), or `None` when the words run past the end (one bounds check
    /// where the storage allows it, instead of a test of the count and the array's own).
    #[inline(always)]
    fn try_array<const N: usize>(&self, i: usize) -> Option<[u32; N]> {
        (i + N <= self.count()).then(|| self.array(i))
    }
    /// Words `k` and `k + 1` as the low and high halves of a `u64`, the high half 0 when `k`
    /// is the last word: a bit field that may run into the next word, read with one bounds
    /// check where the storage allows it.
    #[inline(always)]
    fn pair(&self, k: usize) -> u64 {
        let next = if k + 1 < self.count() {
            self.at(k + 1)
        } else {
            0
        };
        u64::from(self.at(k)) | u64::from(next) << 32
    }
}

impl Words for Vec<u32> {
    #[inline(always)]
    fn at(&self, i: usize) -> u32 {
        self[i]
    }
    #[inline(always)]
    fn array<const N: usize>(&self, i: usize) -> [u32; N] {
        let words: &[u32; N] = self[i..i + N].try_into().expect("N words");
        *words
    }
    fn count(&self) -> usize {
        self.len()
    }
}

/// Little-endian 32-bit words in a byte slice, read without assuming alignment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LeWords<'a>(pub(crate) &'a [u8]);

impl Words for LeWords<'_> {
    #[inline(always)]
    fn at(&self, i: usize) -> u32 {
        // One bounds check and one (unaligned) load: indexing the four bytes one by one
        // made the compiler assemble the word from bytes.
        let b: [u8; 4] = self.0[4 * i..4 * i + 4].try_into().expect("four bytes");
        u32::from_le_bytes(b)
    }
    #[inline(always)]
    fn array<const N: usize>(&self, i: usize) -> [u32; N] {
        words_of(&self.0[4 * i..4 * (i + N)])
    }
    #[inline(always)]
    fn try_array<const N: usize>(&self, i: usize) -> Option<[u32; N]> {
        self.0.get(4 * i..4 * (i + N)).map(words_of)
    }
    #[inline(always)]
    fn pair(&self, k: usize) -> u64 {
        match self.0.get(4 * k..4 * k + 8) {
            Some(b) => u64::from_le_bytes(b.try_into().expect("eight bytes")),
            None => u64::from(self.at(k)),
        }
    }
    fn count(&self) -> usize {
        self.0.len() / 4
    }
}

/// The little-endian words of `bytes` (`4N` of them).
#[inline(always)]
fn words_of<const N: usize>(bytes: &[u8]) -> [u32; N] {
    std::array::from_fn(|k| {
        u32::from_le_bytes([
            bytes[4 * k],
            bytes[4 * k + 1],
            bytes[4 * k + 2],
            bytes[4 * k + 3],
        ])
    })
}

/// Words read in place from the file, or decoded when the container was opened (a coded
/// section or field: the readers keep both behind [`Words`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Stored<'a> {
    /// Little-endian words of the file.
    File(LeWords<'a>),
    /// Words decoded from a coded part of the file.
    Decoded(Vec<u32>),
}

impl Default for Stored<'_> {
    fn default() -> Self {
        Stored::File(LeWords::default())
    }
}

impl Words for Stored<'_> {
    #[inline]
    fn at(&self, i: usize) -> u32 {
        match self {
            Stored::File(w) => w.at(i),
            Stored::Decoded(w) => w[i],
        }
    }
    fn count(&self) -> usize {
        match self {
            Stored::File(w) => w.count(),
            Stored::Decoded(w) => w.len(),
        }
    }
}

/// An array of 16-bit units: a vector, or little-endian bytes read in place.
pub trait Units {
    /// Unit `i`. Panics when `i` is out of range; validation guarantees it never is.
    fn at(&self, i: usize) -> u16;
    /// Number of units.
    fn count(&self) -> usize;
}

impl Units for Vec<u16> {
    #[inline(always)]
    fn at(&self, i: usize) -> u16 {
        self[i]
    }
    fn count(&self) -> usize {
        self.len()
    }
}

/// Little-endian 16-bit units in a byte slice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LeUnits<'a>(pub(crate) &'a [u8]);

impl Units for LeUnits<'_> {
    #[inline(always)]
    fn at(&self, i: usize) -> u16 {
        let b: [u8; 2] = self.0[2 * i..2 * i + 2].try_into().expect("two bytes");
        u16::from_le_bytes(b)
    }
    fn count(&self) -> usize {
        self.0.len() / 2
    }
}

/// Words that count their reads: the tests that every operator reads a bounded number of
/// words whatever the mesh.
#[cfg(test)]
pub(crate) struct Counting<'a> {
    pub(crate) words: &'a [u32],
    pub(crate) reads: &'a std::cell::Cell<usize>,
}

#[cfg(test)]
impl Words for Counting<'_> {
    fn at(&self, i: usize) -> u32 {
        self.reads.set(self.reads.get() + 1);
        self.words[i]
    }
    fn count(&self) -> usize {
        self.words.len()
    }
}

/// The set bits of a `u128`, lowest first.
pub(crate) struct Bits128(pub(crate) u128);

impl Iterator for Bits128 {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        (self.0 != 0).then(|| {
            let bit = self.0.trailing_zeros() as usize;
            self.0 &= self.0 - 1;
            bit
        })
    }
}

/// The set bits of a mask, lowest first.
pub(crate) struct BitsSet(pub(crate) u64);

impl Iterator for BitsSet {
    type Item = u32;
    #[inline]
    fn next(&mut self) -> Option<u32> {
        let i = self.0.trailing_zeros();
        (self.0 != 0).then(|| {
            self.0 &= self.0 - 1;
            i
        })
    }
}
