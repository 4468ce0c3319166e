//! The start rule of a repeating cam: where the slave engages when a cam
//! starts (or restarts) with the master anywhere on its axis.
//!
//! One rule for every face (docs/engine.md, "The start rule"):
//!
//! - the cycle count starts in the cycle the master is in at the start:
//!   the strokes a repeat cam accumulates are counted from there, never
//!   from the table's origin (a start at master 10000 on a 3183-count
//!   knife table does not owe three revolutions);
//! - a table with a stroke engages at the equivalent position (table value
//!   plus whole strokes) nearest the slave: for a table that never turns
//!   back the first one at or ahead of it in the direction the cam moves
//!   the slave, so the start travels less than one stroke and sends no
//!   reverse pulse; for a table that turns back (document 001's Repeat
//!   example) the nearest either way;
//! - a table without a stroke (periodic, out-and-back, normal) starts at
//!   the table value itself, absolute, as the documents say.
//!
//! With the slave at 0 and the master on the table's origin this is the
//! table's first value, whenever that lies within one stroke ahead of 0:
//! the documents' own examples start exactly as before.

use crate::rounding::{ceil_to_i128, exact_f64};
use crate::{EngineError, SlaveAlign};

/// What the start rule needs to know of a cam's cycle (the coupling works
/// it out; kept to plain numbers so the rule depends on nothing else).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StrokeGeometry {
    /// One stroke in output pulses after the slave zoom (signed; 0 for a
    /// cam that does not accumulate one).
    pub(crate) per_stroke: f64,
    /// The sign of the slave's motion while the master moves forward on a
    /// table that never turns back: stroke × slave zoom × master zoom.
    pub(crate) forward: i128,
    /// The table moves the slave both ways inside a cycle.
    pub(crate) turns_back: bool,
}

/// The strokes to add to the table value at the start: the stroke count
/// the cycle the master is in takes, and `value` of it when the rule
/// worked it out already (so the caller need not again). `value(n)` is
/// the zoomed table value at the engage place plus `n` strokes (exact,
/// rounded once), `slave` where the slave stands. Only an absolute slave
/// ([`SlaveAlign::Absolute`], [`SlaveAlign::NearestEquivalent`]) on a cam
/// with a stroke looks for the equivalent position; every other start
/// counts the engage cycle as cycle 0.
///
/// Inlined where it is called, with the search out of line: every other
/// start (a relative slave, the default) is then a test of the rule, not
/// a call (the engaging tick, docs/engine.md "Benchmarks").
#[inline(always)]
pub(crate) fn strokes_at_start(
    geo: StrokeGeometry,
    align: SlaveAlign,
    slave: i128,
    value: impl Fn(i128) -> Result<i128, EngineError>,
) -> Result<(i128, Option<i128>), EngineError> {
    match align {
        SlaveAlign::Absolute | SlaveAlign::NearestEquivalent
            if geo.forward != 0 && geo.per_stroke != 0.0 =>
        {
            equivalent(geo, slave, value).map(|(n, v)| (n, Some(v)))
        }
        _ => Ok((0, None)),
    }
}

/// The strokes that put `value(n)` first at or ahead of `slave` in the
/// cam's forward direction, or nearest either way on a table that turns
/// back, and `value` there. Each place is valued once (the engage tick
/// pays for every one).
#[inline(never)]
fn equivalent(
    geo: StrokeGeometry,
    slave: i128,
    value: impl Fn(i128) -> Result<i128, EngineError>,
) -> Result<(i128, i128), EngineError> {
    let direction = geo.forward;
    // Travel to the position of `m` steps, each step one stroke in
    // `direction`: it grows with `m`. With the value there.
    let step = direction * geo.per_stroke.signum() as i128;
    let travel = |m: i128| -> Result<(i128, i128), EngineError> {
        let v = value(m.checked_mul(step).ok_or(EngineError::SlaveOverflow)?)?;
        v.checked_sub(slave)
            .map(|t| (t * direction, v))
            .ok_or(EngineError::SlaveOverflow)
    };
    let origin = travel(0)?;
    let estimate = -exact_f64(origin.0) / geo.per_stroke.abs();
    if !estimate.is_finite() || estimate.abs() > 1e30 {
        return Err(EngineError::SlaveOverflow);
    }
    let guess = ceil_to_i128(estimate);
    let at_guess = if guess == 0 { origin } else { travel(guess)? };
    // Bracket the first `m` with travel >= 0 around the guess (a rounding
    // away, or a stroke below one pulse), then halve: bounded work.
    // `below` has travel < 0, `ahead` travel >= 0.
    let (mut below, mut ahead) = ((guess, at_guess), (guess, at_guess));
    let mut reach = 1i128;
    while below.1.0 >= 0 {
        let m = below
            .0
            .checked_sub(reach)
            .ok_or(EngineError::SlaveOverflow)?;
        below = (m, travel(m)?);
        reach = reach.saturating_mul(2);
    }
    reach = 1;
    while ahead.1.0 < 0 {
        let m = ahead
            .0
            .checked_add(reach)
            .ok_or(EngineError::SlaveOverflow)?;
        ahead = (m, travel(m)?);
        reach = reach.saturating_mul(2);
    }
    while ahead.0 - below.0 > 1 {
        let m = below.0 + (ahead.0 - below.0) / 2;
        let mid = (m, travel(m)?);
        if mid.1.0 >= 0 {
            ahead = mid;
        } else {
            below = mid;
        }
    }
    let (m, (_, v)) = if geo.turns_back && -below.1.0 < ahead.1.0 {
        below
    } else {
        ahead
    };
    Ok((m * step, v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coupling::Geometry;
    use crate::{AxisConfig, Coupling, Zoom};
    use ecam_core::{CamCurve, Cursor, PointTable};

    fn geometry(table: &PointTable, slave_zoom: Zoom, master_zoom: Zoom) -> Geometry {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            slave_zoom,
            master_zoom,
            ..AxisConfig::default()
        };
        Geometry::new(table, &config).unwrap()
    }

    fn start(table: &PointTable, at: f64, slave: i128, zoom: Zoom) -> i128 {
        let geo = geometry(table, zoom, Zoom::ONE);
        let value = table.position(at, &mut Cursor::new());
        let (n, at) = strokes_at_start(geo.strokes(), SlaveAlign::Absolute, slave, |n| {
            geo.zoomed(n, value)
        })
        .unwrap();
        // The value handed back is the value of the strokes handed back.
        assert_eq!(at, Some(geo.zoomed(n, value).unwrap()));
        geo.zoomed(n, value).unwrap()
    }

    #[test]
    fn a_rising_table_engages_ahead_of_the_slave_within_one_stroke() {
        let knife = PointTable::from_pairs(&[(0, 0), (1000, 100)]).unwrap();
        // The case: master at 2500 is 500 into the cycle: 50.
        assert_eq!(start(&knife, 500.0, 0, Zoom::ONE), 50);
        assert_eq!(start(&knife, 500.0, 51, Zoom::ONE), 150);
        assert_eq!(start(&knife, 500.0, 50, Zoom::ONE), 50);
        assert_eq!(start(&knife, 500.0, -1000, Zoom::ONE), -950);
        assert_eq!(start(&knife, 0.0, 0, Zoom::ONE), 0);
    }

    #[test]
    fn a_falling_table_engages_below_the_slave() {
        let down = PointTable::from_pairs(&[(0, 0), (1000, -100)]).unwrap();
        assert_eq!(start(&down, 500.0, 0, Zoom::ONE), -50);
        assert_eq!(start(&down, 500.0, -51, Zoom::ONE), -150);
        // A negative slave zoom turns a rising table into a falling output.
        let up = PointTable::from_pairs(&[(0, 0), (1000, 100)]).unwrap();
        assert_eq!(start(&up, 500.0, 0, Zoom::signed(-1, 1).unwrap()), -50);
    }

    #[test]
    fn a_table_that_turns_back_takes_the_nearest_either_way() {
        // Document 001: master 20000 (table value 1000), slave -1500: -2000.
        let doc001 =
            PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)])
                .unwrap();
        assert_eq!(start(&doc001, 20000.0, -1500, Zoom::ONE), -2000);
        assert_eq!(start(&doc001, 20000.0, -900, Zoom::ONE), -500);
    }

    #[test]
    fn a_stroke_below_one_pulse_still_lands_within_one_pulse() {
        let fine = PointTable::from_pairs(&[(0, 0), (1000, 1)]).unwrap();
        let zoom = Zoom::new(1, 7).unwrap();
        for slave in [-5, 0, 3, 1000] {
            let at = start(&fine, 500.0, slave, zoom);
            assert!((0..=1).contains(&(at - slave)), "{slave} -> {at}");
        }
    }
}
