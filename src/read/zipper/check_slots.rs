//! [V58] slot by slot (`spec/FORMAT.md` §3.5e): the check that names the first fault, run
//! when the open's fast pass (`zipper_scan`) has found one.

use super::{EXCEPTIONS, HEADS, PAIRS, PLANES, RECORDS};
use crate::error::{Result, Rule};
use crate::lr::zipper::{
    implied_wart, BLOCK_SHIFT, DELTAS, EXCEPTION, FOUR, HEAD_WORDS, IRREGULAR_SLOT,
    NEXT_NEXT_OR_NULL, PLANE_WORDS, PREVIOUS, RECORD_WORDS, SHORT_HEAD_WORDS, STATE_SHIFT,
    STORES_BOTH, STORES_FIRST, STORES_NONE, STORES_SECOND,
};
use crate::lr::{LrLayout, ZipperTables, NULL, VALUE, WART};
use crate::read::lr_rules::ring_slot_flags;
use crate::read::zipper_scan::{block_symbols, tip_word_holds};
use crate::words::{LeWords, Words};

/// [V58]: each block's head counts the exceptions and records before it; symbols of slots
/// past the last ring vertex are 0; exception and record words have bit 31 clear and a tip
/// below `m`; record word 1 says what it stores as FORMAT.md §3.5e allows, the pairs used
/// once each in order; every slot's tip is below `m` (`NULL` only in a right slot of symbol
/// 5); every exception word, record and pair is used. Returns the flags of every slot for
/// [`SlotMap`], found in the same pass. Slot by slot, so that the first fault is named: the
/// reader runs it when the fast pass (`scan_slots`) has found one.
pub(super) fn check_slots(
    t: &ZipperTables<LeWords>,
    word_err: &impl Fn(usize, usize, Rule, String) -> crate::Error,
) -> Result<Vec<u8>> {
    let (m, m_r) = (t.m, t.m_r);
    let mut flags = Vec::with_capacity(2 * m_r as usize);
    let (mut exceptions, mut records, mut pairs) = (0usize, 0usize, 0usize);
    let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);
    let n0 = t.t0_count() as u64;
    for block in 0..blocks {
        let before = [0, 1].map(|k| t.before_block(block, k));
        if before != [exceptions, records] {
            // The head's count word, or in the compact form its exception count's field.
            let index = match (t.compact, t.short_heads) {
                (true, _) => 2 * block,
                (false, true) => SHORT_HEAD_WORDS * block + 1,
                (false, false) => HEAD_WORDS * block + 2,
            };
            return Err(word_err(
                HEADS,
                index,
                Rule(58),
                format!(
                    "block {block} counts {} exceptions and {} records before it, not {exceptions} and {records}",
                    before[0], before[1]
                ),
            ));
        }
        let first = (block << BLOCK_SHIFT) as u32;
        let slot = t.block_planes(block);
        let used = 2 * (m_r - first).min(1 << BLOCK_SHIFT);
        let beyond = if used == 128 { 0 } else { u128::MAX << used };
        if slot.p.iter().any(|p| p & beyond != 0) {
            return Err(word_err(
                PLANES,
                PLANE_WORDS * block,
                Rule(58),
                format!("block {block} has symbols past the last ring vertex"),
            ));
        }
        let symbols = block_symbols(&slot);
        let fours = t.block_fours(&slot);
        let mut chain = [0, 1].map(|side| t.chain_head(block, side));
        for bit in 0..used {
            let (v, side) = (first + bit / 2, (bit % 2) as usize);
            let s = symbols[bit as usize] as u32;
            let mut wart = 0;
            let next = t.ring_next(v);
            // With WART_DELTAS, whether the side's next slot is a canonical T2: in this
            // block unless v ends its ring or the block.
            let next_symbol = if next == v + 1 && bit + 2 < used {
                symbols[bit as usize + 2] as u32
            } else {
                t.symbol(next, side)
            };
            let before_t2 = t.wart_deltas & (next_symbol == PREVIOUS);
            let four = fours >> bit & 1 != 0;
            let tip = match s {
                s if s < DELTAS || four => {
                    wart = before_t2 as u32;
                    chain[side] = chain[side].wrapping_sub(if four { FOUR } else { s });
                    chain[side]
                }
                NEXT_NEXT_OR_NULL if side == 1 && !before_t2 && !t.fours()[1] => NULL,
                EXCEPTION | IRREGULAR_SLOT => {
                    let (array, at, count) = if s == EXCEPTION {
                        exceptions += 1;
                        (EXCEPTIONS, exceptions - 1, t.exceptions.count())
                    } else {
                        records += 1;
                        (RECORDS, RECORD_WORDS * (records - 1), t.records.count())
                    };
                    let words = if s == EXCEPTION {
                        &t.exceptions
                    } else {
                        &t.records
                    };
                    if at >= count {
                        return Err(word_err(
                            PLANES,
                            PLANE_WORDS * block,
                            Rule(58),
                            format!(
                                "slot ({v}, {side}) has no {} word left",
                                if s == EXCEPTION {
                                    "exception"
                                } else {
                                    "record"
                                }
                            ),
                        ));
                    }
                    let word = words.at(at);
                    if !tip_word_holds(word, m) {
                        return Err(word_err(
                            array,
                            at,
                            Rule(58),
                            format!("slot ({v}, {side}): word {word:#x} is not a WART flag and a vertex"),
                        ));
                    }
                    if s == IRREGULAR_SLOT {
                        let second = t.records.at(at + 1);
                        let value = second & ((1 << STATE_SHIFT) - 1);
                        let ok = match second >> STATE_SHIFT {
                            // ROW_RECORDS: a T0 row or a pair.
                            STORES_FIRST if t.row_records => (value as u64) < n0,
                            STORES_NONE | STORES_SECOND if t.row_records => false,
                            STORES_NONE => value == 0,
                            STORES_FIRST | STORES_SECOND => {
                                (value as u64) < 4 * n0 && value % 4 != 3
                            }
                            STORES_BOTH => {
                                pairs += 1;
                                value as usize == pairs - 1 && pairs <= t.pairs.count() / 2
                            }
                            _ => false,
                        };
                        if !ok {
                            return Err(word_err(
                                RECORDS,
                                at + 1,
                                Rule(58),
                                format!(
                                    "record {}: word 1 {second:#x} stores no valid opposite",
                                    records - 1
                                ),
                            ));
                        }
                    }
                    // With IMPLIED_WARTS: before a canonical T2, and not its redundant copy.
                    wart = match t.implied_warts {
                        true => {
                            implied_wart(next_symbol == PREVIOUS, word & VALUE, t.ring_next(next))
                        }
                        false => word & WART != 0,
                    } as u32;
                    chain[side] = word & VALUE;
                    chain[side]
                }
                // The ring rules' own tips: v.p, v.n.n.
                PREVIOUS => t.ring_prev(v),
                _ => t.ring_next(next),
            };
            if tip >= m && !(tip == NULL && s == NEXT_NEXT_OR_NULL && !four) {
                return Err(word_err(
                    PLANES,
                    PLANE_WORDS * block,
                    Rule(58),
                    format!("slot ({v}, {side}) has tip {tip:#x} ({m} vertices)"),
                ));
            }
            let nn = t.ring_next(next);
            flags.push(ring_slot_flags(tip, wart, (s == IRREGULAR_SLOT) as u32, nn));
        }
    }
    let left = [
        (EXCEPTIONS, exceptions, t.exceptions.count()),
        (RECORDS, RECORD_WORDS * records, t.records.count()),
        (PAIRS, 2 * pairs, t.pairs.count()),
    ];
    for (array, used, count) in left {
        if used != count {
            return Err(word_err(
                array,
                used,
                Rule(58),
                format!("{} words not used by any slot", count - used),
            ));
        }
    }
    Ok(flags)
}
