//! How a total resolution is shared among segments (PC editor table dialog,
//! document 003 §6.2; ECAMTBX K2, document 000 appendix).

use alloc::vec::Vec;

use crate::TableError;

/// Fewest points a sampled table may have (document 003 §6.2: 10..512).
pub const MIN_TOTAL_RESOLUTION: u16 = 10;
/// Most points a sampled table may have: the register block's 512 sections.
pub const MAX_TOTAL_RESOLUTION: u16 = 512;

/// Points per segment for a table of `total` points, one of which is the
/// start point; `wanted[i]` is segment `i`'s own resolution, if set.
///
/// Why the start point counts: the documents call the total "the count of
/// points in the datasheet", each occupying one 4-word register entry, and
/// the register block holds at most 512 of them. The start point is the
/// dialog's section 0, which has no resolution of its own.
pub(crate) fn distribute(total: u16, wanted: &[Option<u16>]) -> Result<Vec<u16>, TableError> {
    if total < MIN_TOTAL_RESOLUTION {
        return Err(TableError::Parameter {
            name: "total resolution",
            reason: "must be between 10 and 512",
        });
    }
    if total > MAX_TOTAL_RESOLUTION {
        return Err(TableError::SectionCount {
            count: usize::from(total),
            min: usize::from(MIN_TOTAL_RESOLUTION),
            max: usize::from(MAX_TOTAL_RESOLUTION),
        });
    }
    let available = u32::from(total) - 1;
    let fixed: u32 = wanted.iter().flatten().map(|&r| u32::from(r)).sum();
    let unset = wanted.iter().filter(|r| r.is_none()).count() as u32;
    if fixed > available {
        return Err(TableError::Parameter {
            name: "segment resolution",
            reason: "adds up to more points than the total resolution leaves after the start point",
        });
    }
    let left = available - fixed;
    let (share, extra) = match unset {
        0 => (0, 0),
        n => (left / n, left % n),
    };
    if unset > 0 && share == 0 {
        return Err(TableError::Parameter {
            name: "total resolution",
            reason: "leaves no point for a segment without its own resolution",
        });
    }
    let mut handed_extra = 0;
    let per_segment = wanted
        .iter()
        .map(|r| match r {
            Some(r) => *r,
            None => {
                let one_more = u32::from(handed_extra < extra);
                handed_extra += 1;
                // share + 1 ≤ 511: fits u16.
                (share + one_more) as u16
            }
        })
        .collect();
    Ok(per_segment)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use alloc::vec;

    #[test]
    fn unset_segments_share_what_is_left() {
        assert_eq!(
            distribute(100, &[None; 5]).unwrap(),
            vec![20, 20, 20, 20, 19]
        );
        assert_eq!(
            distribute(100, &[Some(50), None, None]).unwrap(),
            vec![50, 25, 24]
        );
        assert_eq!(distribute(30, &[Some(5), Some(6)]).unwrap(), vec![5, 6]);
    }

    #[test]
    fn refuses_totals_and_sums_out_of_range() {
        assert_eq!(distribute(9, &[None]).unwrap_err().code(), 6781);
        assert_eq!(distribute(513, &[None]).unwrap_err().code(), 6783);
        assert_eq!(distribute(20, &[Some(20)]).unwrap_err().code(), 6781);
        assert_eq!(
            distribute(20, &[Some(17), None, None, None])
                .unwrap_err()
                .code(),
            6781
        );
    }
}
