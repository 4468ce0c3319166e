//! Whatever a program (or a Modbus client) writes into the DECAM block and
//! however the master moves, the instruction never panics, and the error
//! register (offset 2) and the error flag bits 4/5 agree.
#![allow(clippy::unwrap_used)]

use crate::decam_support::Rig;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(256)))]
    #[test]
    fn any_block_and_master_motion_is_survived(
        words in prop::collection::vec((0u16..60, any::<i16>()), 0..40),
        steps in prop::collection::vec(-100_000i64..100_000, 1..60),
        start in prop::sample::select(vec![0i16, 1, 2, 3, -1]),
        edges in any::<u64>(),
    ) {
        let mut r = Rig::new(&[(0, 0), (500, 100), (1000, 0)]);
        r.set(5, start);
        for (offset, value) in &words {
            // Keep the version/flag words the instruction owns out of it;
            // everything else, including the table and its count, is fair game.
            if *offset > 2 {
                r.set(*offset, *value);
            }
        }
        for (i, step) in steps.iter().enumerate() {
            if i % 10 == 0 {
                r.scan();
            }
            r.set_bit(crate::decam_support::START, edges >> (i % 64) & 1 == 1);
            r.tick(*step);
            let flags = r.flags();
            let error = r.reg(2);
            // Bits 4/5 are set exactly when the error register holds a code.
            prop_assert_eq!(flags & (1 << 4) != 0, error == 6781, "flags {:#x} error {}", flags, error);
            if flags & (1 << 5) != 0 {
                prop_assert!(error != 0 && error != 6781);
            }
        }
    }
}
