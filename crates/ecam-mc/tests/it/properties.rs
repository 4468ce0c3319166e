//! Invariants of the Repeat type over random tables.
#![allow(clippy::unwrap_used, missing_docs)]

use ecam_core::PointTable;
use ecam_mc::{CamType, ECamData, MotionController};
use proptest::prelude::*;

fn table() -> impl Strategy<Value = PointTable> {
    prop::collection::vec((1i64..5000, -5000i64..5000), 1..6).prop_map(|steps| {
        let mut master = 0;
        let mut points = vec![(0, 0)];
        for (dm, slave) in steps {
            master += dm;
            points.push((master, slave));
        }
        PointTable::from_pairs(&points).unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    /// One table span further along the master, a Repeat cam's slave is
    /// exactly one stroke further, in either direction.
    #[test]
    fn repeat_adds_one_stroke_per_span(table in table(), m in -50_000i64..50_000, back in any::<bool>()) {
        use ecam_core::CamCurve;
        let (span, stroke) = (table.master_span(), table.stroke());
        let mut mc = MotionController::new(2);
        mc.start_ecam(ECamData { master_axis: 0, slave_axis: 1, cam_type: CamType::Repeat, table }).unwrap();
        let s1 = mc.drive(0, m, 1).unwrap();
        let (m2, sign) = if back { (m - span, -1) } else { (m + span, 1) };
        let s2 = mc.drive(0, m2, 1).unwrap();
        prop_assert_eq!(s2 - s1, sign * stroke);
    }
}
