//! The PLC's E-cam register block image of a point table (document 003 §5
//! and §6.1): word 38 holds the number of sections, word 39 the offset of the
//! table (always 40), and from word 40 on each section takes four words:
//! master then slave, each a 32-bit integer stored low word first.
//!
//! A "section" here is one table entry (a master/slave point), as the
//! register list names them ("section 0 of master axis" …): a table of `N`
//! points writes `N` at word 38 and fills words 40 to 40 + 4·N − 1. The
//! block holds at most 512.
//!
//! ```
//! use ecam_core::{PointTable, register_image};
//!
//! let table = PointTable::from_pairs(&[(0, 0), (100_000, -70_000)])?;
//! let words = register_image::to_words(&table)?;
//! assert_eq!(words.len(), 48);
//! assert_eq!(words[38], 2);
//! assert_eq!(words[39], 40);
//! assert_eq!((words[44], words[45]), (-31072, 1)); // 100000 = 0x0001_86A0
//! assert_eq!(register_image::from_words(&words)?, table);
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use alloc::vec;
use alloc::vec::Vec;

use crate::{CamPoint, PointTable, TableError};

/// Word offset of the section count.
pub const SECTION_COUNT_OFFSET: usize = 38;
/// Word offset of the table-offset word, which always holds 40.
pub const TABLE_OFFSET_OFFSET: usize = 39;
/// Word offset of section 0.
pub const TABLE_OFFSET: usize = 40;
/// Words per section: master (2) and slave (2).
pub const WORDS_PER_SECTION: usize = 4;
/// Most sections the register block holds.
pub const MAX_SECTIONS: usize = 512;

/// Splits a 32-bit value into (low, high) words.
pub const fn split(value: i32) -> [i16; 2] {
    let bits = value as u32;
    [bits as u16 as i16, (bits >> 16) as u16 as i16]
}

/// Joins (low, high) words into a 32-bit value.
pub const fn join(low: i16, high: i16) -> i32 {
    ((high as u16 as u32) << 16 | (low as u16 as u32)) as i32
}

/// Number of words a block with `sections` sections occupies (offsets 0..len).
pub const fn block_len(sections: usize) -> usize {
    TABLE_OFFSET + WORDS_PER_SECTION * sections
}

/// The table's words from offset 38 on: section count, 40, then the sections.
/// This is what the PLC's ECAMTBX writes at `D1 + 38`.
///
/// # Errors
/// [`TableError::SectionCount`] (6783) for more than 512 points;
/// [`TableError::ValueOutOfRange`] (6782) naming the first point whose master
/// or slave is not a signed 32-bit value.
pub fn table_words(table: &PointTable) -> Result<Vec<i16>, TableError> {
    let points = table.points();
    if points.len() > MAX_SECTIONS {
        return Err(TableError::SectionCount {
            count: points.len(),
            min: 2,
            max: MAX_SECTIONS,
        });
    }
    let mut words = Vec::with_capacity(2 + WORDS_PER_SECTION * points.len());
    // ≤ 512: fits.
    words.push(points.len() as i16);
    words.push(TABLE_OFFSET as i16);
    for (section, p) in points.iter().enumerate() {
        let master =
            i32::try_from(p.master).map_err(|_| TableError::ValueOutOfRange { section })?;
        let slave = i32::try_from(p.slave).map_err(|_| TableError::ValueOutOfRange { section })?;
        words.extend_from_slice(&split(master));
        words.extend_from_slice(&split(slave));
    }
    Ok(words)
}

/// A whole register block image (offsets 0 to 40 + 4·N − 1) holding `table`;
/// the words before 38 are zero.
///
/// # Errors
/// As [`table_words`].
pub fn to_words(table: &PointTable) -> Result<Vec<i16>, TableError> {
    let tail = table_words(table)?;
    let mut words = vec![0; SECTION_COUNT_OFFSET];
    words.extend_from_slice(&tail);
    Ok(words)
}

/// Reads the table out of a register block image that starts at offset 0.
///
/// # Errors
/// [`TableError::SectionCount`] (6783) when word 38 is below 2 or above 512;
/// [`TableError::Parameter`] (6781) when the image is shorter than its
/// section count needs or word 39 is not 40;
/// [`TableError::MasterNotIncreasing`] (6782) naming the first section whose
/// master is not greater than the one before.
pub fn from_words(words: &[i16]) -> Result<PointTable, TableError> {
    let count_word = words
        .get(SECTION_COUNT_OFFSET)
        .copied()
        .ok_or(TableError::Parameter {
            name: "register block",
            reason: "is shorter than 40 words",
        })?;
    let count = usize::try_from(count_word).unwrap_or(usize::MAX);
    if !(2..=MAX_SECTIONS).contains(&count) {
        return Err(TableError::SectionCount {
            count: if count_word < 0 { 0 } else { count },
            min: 2,
            max: MAX_SECTIONS,
        });
    }
    if words.get(TABLE_OFFSET_OFFSET).copied() != Some(TABLE_OFFSET as i16) {
        return Err(TableError::Parameter {
            name: "table offset (word 39)",
            reason: "must be 40",
        });
    }
    let data = words
        .get(TABLE_OFFSET..block_len(count))
        .ok_or(TableError::Parameter {
            name: "register block",
            reason: "is shorter than its section count needs (40 + 4 words per section)",
        })?;
    table_from_sections(data)
}

/// The table held by section words (from offset 40 on, four words per
/// point), however many points they make.
///
/// # Errors
/// [`TableError::MasterNotIncreasing`] (6782) naming the first section whose
/// master is not greater than the one before; [`TableError::SectionCount`]
/// for fewer than two points.
pub fn table_from_sections(words: &[i16]) -> Result<PointTable, TableError> {
    let points = words
        .chunks_exact(WORDS_PER_SECTION)
        .map(|w| CamPoint::new(i64::from(join(w[0], w[1])), i64::from(join(w[2], w[3]))))
        .collect();
    PointTable::new(points)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn words_round_trip_signed_values() {
        for v in [
            0,
            1,
            -1,
            65535,
            65536,
            -65536,
            i32::MAX,
            i32::MIN,
            100_000,
            -70_000,
        ] {
            let [lo, hi] = split(v);
            assert_eq!(join(lo, hi), v);
        }
    }

    #[test]
    fn refuses_values_beyond_32_bits_with_section() {
        let t = PointTable::from_pairs(&[(0, 0), (1, 1 << 31)]).unwrap();
        assert_eq!(
            to_words(&t).unwrap_err(),
            TableError::ValueOutOfRange { section: 1 }
        );
    }

    #[test]
    fn refuses_more_than_512_sections() {
        let pairs: Vec<(i64, i64)> = (0..513).map(|i| (i, 0)).collect();
        let t = PointTable::from_pairs(&pairs).unwrap();
        assert_eq!(to_words(&t).unwrap_err().code(), 6783);
        let pairs: Vec<(i64, i64)> = (0..512).map(|i| (i, 0)).collect();
        let t = PointTable::from_pairs(&pairs).unwrap();
        assert_eq!(to_words(&t).unwrap().len(), block_len(512));
    }

    #[test]
    fn reading_checks_count_length_and_order() {
        let t = PointTable::from_pairs(&[(0, 0), (10, 5), (20, 0)]).unwrap();
        let mut w = to_words(&t).unwrap();
        assert_eq!(from_words(&w[..w.len() - 1]).unwrap_err().code(), 6781);
        assert_eq!(from_words(&w[..10]).unwrap_err().code(), 6781);
        w[38] = 513;
        assert_eq!(from_words(&w).unwrap_err().code(), 6783);
        w[38] = -1;
        assert_eq!(from_words(&w).unwrap_err().code(), 6783);
        w[38] = 3;
        w[48] = 0; // section 2's master low word: 20 -> 0
        assert_eq!(
            from_words(&w).unwrap_err(),
            TableError::MasterNotIncreasing { section: 2 }
        );
    }
}
