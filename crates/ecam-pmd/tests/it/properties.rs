//! Invariants of the cam face over random tables and master paths.
#![allow(clippy::unwrap_used, missing_docs)]

use ecam_pmd::{CamParam, MotionProcessor};
use proptest::prelude::*;

fn cam_processor(values: &[i64], counts: i64) -> MotionProcessor {
    let mut p = MotionProcessor::default();
    p.set_buffer_length(3, values.len() as i64).unwrap();
    for &v in values {
        p.write_buffer(3, v).unwrap();
    }
    p.set_profile_mode(0, 8).unwrap();
    p.update(0).unwrap();
    p.set_cam(0, CamParam::CamBufferId, 3).unwrap();
    p.set_cam(0, CamParam::CamCounts, counts).unwrap();
    p.set_cam(0, CamParam::CamSource, 0x0001).unwrap();
    p
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    /// Started at input 0 from commanded 0, the output at input k·CamCounts
    /// is exactly k·(last − first), whatever path the input took there.
    #[test]
    fn whole_tables_add_whole_strokes(
        values in prop::collection::vec(-10_000i64..10_000, 2..12),
        counts in 2i64..400,
        path in prop::collection::vec(-300i64..300, 0..8),
        k in -3i64..4,
    ) {
        let mut p = cam_processor(&values, counts);
        p.set_event_action(0, 0, 9).unwrap();
        prop_assert!(p.cam_active(0).unwrap());
        prop_assert_eq!(p.commanded_position(0).unwrap(), 0);
        for target in path.iter().copied().chain([k * counts]) {
            let from = p.actual_position(1).unwrap();
            let ticks = (target - from).unsigned_abs().max(1);
            p.move_to(1, target, ticks as i64).unwrap();
            p.run(ticks);
        }
        let stroke = values[values.len() - 1] - values[0];
        prop_assert_eq!(p.commanded_position(0).unwrap(), k * stroke);
    }

    /// A refused SetCam leaves every parameter as it was.
    #[test]
    fn refused_set_cam_changes_nothing(
        requests in prop::collection::vec((0usize..6, -5i64..1_000_000_000), 1..20),
    ) {
        let mut p = cam_processor(&[0, 1, 2], 10);
        for (param, value) in requests {
            let param = CamParam::ALL[param];
            let before: Vec<i64> = CamParam::ALL.iter().map(|&q| p.get_cam(0, q).unwrap()).collect();
            if p.set_cam(0, param, value).is_err() {
                let after: Vec<i64> = CamParam::ALL.iter().map(|&q| p.get_cam(0, q).unwrap()).collect();
                prop_assert_eq!(before, after);
            } else {
                prop_assert_eq!(p.get_cam(0, param).unwrap(), value);
            }
        }
    }
}
