//! Writing a whole point table into a DECAM block's registers: the image
//! of `ecam_core::register_image` at `S2 + 38` (count, 40, the points),
//! with document 003's checks. ECAMTBX writes its tables this way, and so
//! does `ecam plc run --load D2000=table.csv`.

use ecam_core::{CODE_SECTION_COUNT, CODE_TABLE, PointTable, TableError, register_image};

use super::offsets;
use crate::device::D_COUNT;
use crate::devices::Devices;
use crate::operation_error::OperationError;

/// Writes `table` into the block at `D{block}`: `D{block+38}` the point
/// count, `D{block+39}` 40, the points from `D{block+40}`. Nothing is
/// written when a check fails. Gives the number of points.
///
/// # Errors
/// 6783 for fewer than 2 or more than 512 points, or a table that does not
/// fit below D8512; 6782 naming the first point whose master or slave does
/// not fit 32 bits.
///
/// ```
/// use ecam_core::PointTable;
/// use ecam_plc::Devices;
///
/// let mut dev = Devices::new();
/// let table = PointTable::from_pairs(&[(0, 0), (100_000, -70_000)])?;
/// assert_eq!(ecam_plc::decam::load_table(&mut dev, 2000, &table)?, 2);
/// assert_eq!(dev.word(2038)?, 2);
/// assert_eq!(dev.dword(2044)?, 100_000);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load_table(
    devices: &mut Devices,
    block: u16,
    table: &PointTable,
) -> Result<usize, OperationError> {
    let points = table.points().len();
    if !(2..=usize::from(offsets::MAX_SECTIONS)).contains(&points) {
        return Err(OperationError::new(
            CODE_SECTION_COUNT,
            format!("{points} table points; a DECAM table holds 2-512"),
        ));
    }
    // 2..=512 points: the count fits u16.
    let end = u32::from(block) + offsets::block_words(points as u16);
    if end > u32::from(D_COUNT) {
        return Err(OperationError::new(
            CODE_SECTION_COUNT,
            format!("a table of {points} points at D{block} does not fit below D8512"),
        ));
    }
    let words = register_image::table_words(table).map_err(|e| match e {
        TableError::ValueOutOfRange { section } => OperationError::new(
            CODE_TABLE,
            format!("table point {section} does not fit 32-bit registers"),
        ),
        other => OperationError::new(other.code(), other.to_string()),
    })?;
    let first = block.saturating_add(offsets::SECTIONS);
    for (i, word) in words.into_iter().enumerate() {
        let _ = devices.set_word(first.saturating_add(i as u16), word);
    }
    Ok(points)
}
