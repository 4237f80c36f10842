//! The adaptive model of the CLERS stream, shared by encoder and decoder so that both code
//! each decision with the same probabilities: binary decisions per context (the previous
//! symbol and the fan lengths around the gate), and whether a non-handle `S` is a boundary `S`
//! with the length of its hole. Kept apart from the rebuild so that the context layout is in
//! one place.

use crate::edgebreaker::coder::{code_uint, Bit, Bits, UintModel};

/// Symbols of context: the last `ORDER` symbols coded.
const ORDER: u32 = 1;
pub(super) const HIST: usize = 5usize.pow(ORDER);
/// Fan lengths are counted up to this.
pub(super) const FAN_CAP: u32 = 8;
const _: () = assert!(FAN_CAP < 16, "chain lengths are stored in 4 bits");
const CONTEXTS: usize = HIST * (FAN_CAP as usize + 1) * (FAN_CAP as usize + 1);

/// The adaptive model of the CLERS stream.
pub(super) struct Model {
    /// Binary decisions per context: C or not, R or not, S or not, L or E.
    pub(super) nodes: Box<[[Bit; 4]; CONTEXTS]>,
    pub(super) hist: usize,
    hole: [Bit; 1],
    hole_len: UintModel,
}

impl Model {
    pub(super) fn new() -> Model {
        Model {
            nodes: Box::new([[Bit::default(); 4]; CONTEXTS]),
            hist: 0,
            hole: [Bit::default()],
            hole_len: UintModel::default(),
        }
    }

    #[inline(always)]
    pub(super) fn push(&mut self, s: u8) {
        self.hist = if ORDER == 1 {
            s as usize // symbols are below 5
        } else {
            (self.hist * 5 + s as usize) % HIST
        };
    }

    /// Codes whether a non-handle `S` is a boundary `S`, and the length of its hole (at least 2).
    pub(super) fn code_hole<B: Bits>(&mut self, b: &mut B, len: u32) -> Option<u32> {
        if b.bit(&mut self.hole[0], (len != 0) as u32) == 0 {
            return Some(0);
        }
        let l = code_uint(b, &mut self.hole_len, len.wrapping_sub(2) as u64)?;
        u32::try_from(l).ok()?.checked_add(2)
    }
}
