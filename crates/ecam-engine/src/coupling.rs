//! The coupling law: commanded slave as a pure function of the master.
//!
//! Everything that decides *which* cycle the master is in, how many strokes
//! a repeat cam has accumulated and how a zoom scales them is exact integer
//! arithmetic in `i128`. Only the table value inside one cycle is a float.
//! So the commanded slave is `f(master, engagement)`: no state accumulates
//! from tick to tick, and a cam that runs for a year drifts by nothing.
//!
//! Units: a table input `t` is kept as `t_num = t × master_zoom.den`, so the
//! zoomed master `master × num / den` is the exact integer
//! `master × num` in those units.

use ecam_core::{CamCurve, Cursor};

use crate::rounding::{
    floor_div_rem, round_half_away, round_half_up, round_half_up_to_i64, round_to_i64,
    whole_to_i128,
};
use crate::start_rule;
use crate::steady::{Steady, Table};
use crate::{AxisConfig, Coupling, EngineError, MasterAlign, SlaveAlign};

/// How far the table extends along the master.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Extent {
    /// Repeats forever in both directions.
    Cyclic,
    /// A one-shot: this many cycles of master travel after engaging.
    Cycles(u32),
    /// No repetition: the slave holds the end values outside the table.
    Single,
}

/// A place on the master axis: cycle `k` and the offset `r_num` into it
/// (in table counts × master zoom denominator), `0 <= r_num <= period_num`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Place {
    pub(crate) k: i128,
    pub(crate) r_num: i128,
}

/// The integer geometry of the cycle, fixed while a cam is engaged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Geometry {
    origin: i64,
    origin_num: i128,
    period_num: i128,
    mnum: i128,
    mden: i128,
    snum: i128,
    sden: i128,
    /// Slave change added per cycle (0 for a periodic or normal cam).
    stroke: i128,
    /// The slave jumps at the seam: a repeating table whose first and last
    /// slave values differ and whose stroke is not accumulated.
    pub(crate) jumps_at_seam: bool,
    pub(crate) extent: Extent,
    /// Floats of the zooms, taken once here rather than at every sample
    /// (the same values: each is the one conversion the sample made).
    floats: ZoomFloats,
    /// The integers in 64 bits when they all fit (nearly always), for the
    /// 64-bit routes (`locate`, the steady constants).
    narrow: Option<NarrowGeometry>,
    /// What the start rule needs of the cycle (`start_rule.rs`), taken
    /// once here rather than at every engage.
    strokes: start_rule::StrokeGeometry,
}

/// A geometry's integers in 64 bits.
#[derive(Clone, Copy, Debug, PartialEq)]
struct NarrowGeometry {
    origin_num: i64,
    /// Positive.
    period_num: i64,
    mnum: i64,
    /// Positive.
    mden: i64,
    stroke: i64,
    /// `stroke × snum`.
    stroke_snum: i64,
    /// Positive.
    sden: i64,
    /// `stroke × snum / sden` where it is a whole number: the pulses one
    /// stroke adds to the zoomed value, exactly (see
    /// [`Engagement::slave_after_strokes`]).
    whole_stroke: Option<i64>,
}

impl NarrowGeometry {
    fn of(geo: &Geometry) -> Option<Self> {
        let narrow = |v: i128| i64::try_from(v).ok();
        let stroke = narrow(geo.stroke)?;
        let stroke_snum = stroke.checked_mul(narrow(geo.snum)?)?;
        let sden = narrow(geo.sden).filter(|&d| d > 0)?;
        Some(Self {
            origin_num: narrow(geo.origin_num)?,
            period_num: narrow(geo.period_num).filter(|&p| p > 0)?,
            mnum: narrow(geo.mnum)?,
            mden: narrow(geo.mden).filter(|&d| d > 0)?,
            stroke,
            stroke_snum,
            sden,
            whole_stroke: (stroke_snum % sden == 0).then_some(stroke_snum / sden),
        })
    }
}

/// The zoom factors as floats, and their product as the coupling law forms it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ZoomFloats {
    mden: f64,
    snum: f64,
    sden: f64,
    /// `(mnum / mden) × (snum / sden)`.
    factor: f64,
}

impl ZoomFloats {
    fn of(mnum: i128, mden: i128, snum: i128, sden: i128) -> Self {
        Self {
            mden: to_f64(mden),
            snum: to_f64(snum),
            sden: to_f64(sden),
            factor: (to_f64(mnum) / to_f64(mden)) * (to_f64(snum) / to_f64(sden)),
        }
    }
}

/// Largest single-turn range accepted (keeps every product far from overflow).
const MAX_TURN: u64 = 1 << 62;

impl Geometry {
    /// Checks `curve` against `config` and derives the cycle.
    pub(crate) fn new<C: CamCurve + ?Sized>(
        curve: &C,
        config: &AxisConfig,
    ) -> Result<Self, EngineError> {
        let first = curve.master_first();
        let last = curve.master_last();
        if last <= first {
            return Err(EngineError::EmptyCycle);
        }
        let (origin, span) = match config.single_turn {
            Some(turn) => {
                if turn.get() > MAX_TURN {
                    return Err(EngineError::BadTurn);
                }
                let turn = i128::from(turn.get());
                if first < 0 || i128::from(last) > turn {
                    return Err(EngineError::TableOutsideTurn);
                }
                (0, turn)
            }
            None => (first, i128::from(last) - i128::from(first)),
        };
        let raw_stroke = i128::from(curve.slave_last()) - i128::from(curve.slave_first());
        let (stroke, extent) = match config.coupling {
            Coupling::Periodic => (0, Extent::Cyclic),
            Coupling::Repeat { min_stroke } => {
                let joined = raw_stroke != 0 && raw_stroke.unsigned_abs() >= u128::from(min_stroke);
                (if joined { raw_stroke } else { 0 }, Extent::Cyclic)
            }
            Coupling::OneShot { repeats: u16::MAX } => (raw_stroke, Extent::Cyclic),
            Coupling::OneShot { repeats } => (raw_stroke, Extent::Cycles(u32::from(repeats) + 1)),
            // Document 001: on a single-turn master a normal cam repeats
            // with the turn (with a table covering the turn it behaves as
            // the periodic type); elsewhere it has no cycle.
            Coupling::Normal if config.single_turn.is_some() => (0, Extent::Cyclic),
            Coupling::Normal => (0, Extent::Single),
        };
        let (origin, span) = match extent {
            // A normal cam has no cycle: its "cycle" is the table itself.
            Extent::Single => (first, i128::from(last) - i128::from(first)),
            _ => (origin, span),
        };
        if config.master_zoom.is_negative() && matches!(extent, Extent::Cycles(_)) {
            return Err(EngineError::ReversedOneShot);
        }
        let mden = i128::from(config.master_zoom.den());
        let mnum = i128::from(config.master_zoom.signed_num());
        let snum = i128::from(config.slave_zoom.signed_num());
        let sden = i128::from(config.slave_zoom.den());
        let mut geometry = Self {
            origin,
            origin_num: i128::from(origin) * mden,
            period_num: span * mden,
            mnum,
            mden,
            snum,
            sden,
            stroke,
            jumps_at_seam: extent != Extent::Single && stroke == 0 && raw_stroke != 0,
            extent,
            floats: ZoomFloats::of(mnum, mden, snum, sden),
            narrow: None,
            strokes: start_rule::StrokeGeometry {
                per_stroke: 0.0,
                forward: 0,
                turns_back: curve.turns_back(),
            },
        };
        geometry.derive();
        Ok(geometry)
    }

    /// Takes what follows from the integers: their 64-bit copies and the
    /// start rule's figures.
    fn derive(&mut self) {
        self.narrow = NarrowGeometry::of(self);
        self.strokes = start_rule::StrokeGeometry {
            per_stroke: to_f64(self.stroke) * to_f64(self.snum) / to_f64(self.sden),
            forward: self.stroke.signum() * self.snum.signum() * self.mnum.signum(),
            turns_back: self.strokes.turns_back,
        };
    }

    /// One stroke in output pulses (0 for a cam that does not accumulate).
    pub(crate) fn stroke_pulses(&self) -> f64 {
        self.strokes.per_stroke
    }

    /// What the start rule needs of the cycle: a stroke in pulses, which
    /// way the slave goes while the master moves forward on a table that
    /// never turns back (the sign of stroke × both zooms, 0 without a
    /// stroke), and whether the table turns back.
    pub(crate) fn strokes(&self) -> start_rule::StrokeGeometry {
        self.strokes
    }

    /// The master zoom's denominator (the unit of table-input offsets).
    pub(crate) fn master_den(&self) -> i128 {
        self.mden
    }

    /// The same geometry with another slave zoom.
    pub(crate) fn with_slave_zoom(&self, zoom: crate::Zoom) -> Self {
        let snum = i128::from(zoom.signed_num());
        let sden = i128::from(zoom.den());
        let mut geometry = Self {
            snum,
            sden,
            floats: ZoomFloats::of(self.mnum, self.mden, snum, sden),
            ..*self
        };
        geometry.derive();
        geometry
    }

    /// The zoomed master in table-input units.
    pub(crate) fn zoomed_master(&self, master: i64) -> i128 {
        i128::from(master) * self.mnum
    }

    /// Where table input `t_num` lies.
    #[inline]
    pub(crate) fn locate(&self, t_num: i128) -> Place {
        // In 64 bits when the input and the offset from the origin fit
        // (the same place: nothing saturates there).
        if let Some(n) = &self.narrow
            && let Ok(t) = i64::try_from(t_num)
            && let Some(u) = t.checked_sub(n.origin_num)
        {
            return match self.extent {
                Extent::Single => Place {
                    k: 0,
                    r_num: i128::from(u.clamp(0, n.period_num)),
                },
                Extent::Cyclic | Extent::Cycles(_) => {
                    let (k, r_num) = floor_div_rem(u, n.period_num);
                    Place {
                        k: i128::from(k),
                        r_num: i128::from(r_num),
                    }
                }
            };
        }
        let u = t_num.saturating_sub(self.origin_num);
        match self.extent {
            Extent::Single => Place {
                k: 0,
                r_num: u.clamp(0, self.period_num),
            },
            Extent::Cyclic | Extent::Cycles(_) => {
                let (k, r_num) = div_floor(u, self.period_num);
                Place { k, r_num }
            }
        }
    }

    /// Table input of the start (`end = false`) or end of cycle `k`.
    pub(crate) fn boundary(&self, k: i128, end: bool) -> i128 {
        let k = if end { k.saturating_add(1) } else { k };
        self.origin_num
            .saturating_add(k.saturating_mul(self.period_num))
    }

    /// The place at the end of cycle `k` (seen from inside it: no seam jump).
    pub(crate) fn cycle_end(&self, k: i128) -> Place {
        Place {
            k,
            r_num: self.period_num,
        }
    }

    /// The place at the start of cycle `k`.
    pub(crate) fn cycle_start(k: i128) -> Place {
        Place { k, r_num: 0 }
    }

    /// Table input (after zoom, floor) of a place.
    #[inline(always)]
    pub(crate) fn input_in_cycle(&self, place: Place) -> i64 {
        // In 64 bits where the offset into the cycle fits (a place's is
        // never negative, so the floor is the quotient), as the steady
        // tick forms it; the same value (tested).
        if let Some(n) = &self.narrow
            && let Ok(r) = i64::try_from(place.r_num)
            && r >= 0
            && let Some(input) = self.origin.checked_add(r / n.mden)
        {
            return input;
        }
        let (whole, _) = div_floor(place.r_num, self.mden);
        clamp_i64(i128::from(self.origin).saturating_add(whole))
    }

    /// The same place in master counts before zoom (floor; a master zoom
    /// running the table backwards counts the travel the same way).
    #[inline(always)]
    pub(crate) fn raw_in_cycle(&self, place: Place) -> i64 {
        if let Some(n) = &self.narrow
            && let Ok(r) = i64::try_from(place.r_num)
            && r >= 0
            && let Some(mnum) = n.mnum.checked_abs()
        {
            return r / mnum.max(1);
        }
        clamp_i64(div_floor(place.r_num, self.mnum.abs().max(1)).0)
    }

    /// Table input as a float for the curve (the only float in the chain).
    pub(crate) fn table_x(&self, place: Place) -> f64 {
        self.origin as f64 + to_f64(place.r_num) / self.floats.mden
    }

    /// d(slave)/d(master) factor of the two zooms.
    fn zoom_factor(&self) -> f64 {
        self.floats.factor
    }

    /// Exact zoomed value of `table + strokes × stroke`, rounded once,
    /// halves up (the same pulse on either side of a seam, see
    /// [`crate::rounding::round_half_up_to_i64`]).
    ///
    /// Inlined where it is called (the engaging tick's), with the 128-bit
    /// route out of line.
    #[inline(always)]
    pub(crate) fn zoomed(&self, strokes: i128, table: f64) -> Result<i128, EngineError> {
        match i64::try_from(strokes)
            .ok()
            .and_then(|strokes| self.zoomed_narrow(strokes, table))
        {
            Some(value) => Ok(i128::from(value)),
            None => self.zoomed_wide(strokes, table),
        }
    }

    /// [`Geometry::zoomed`] in 128 bits (any value).
    #[inline(never)]
    fn zoomed_wide(&self, strokes: i128, table: f64) -> Result<i128, EngineError> {
        let accumulated = mul_exact(strokes, self.stroke)
            .and_then(|a| mul_exact(a, self.snum))
            .ok_or(EngineError::SlaveOverflow)?;
        let (whole, rem) = div_floor(accumulated, self.sden);
        let fraction = round_half_up((to_f64(rem) + table * self.floats.snum) / self.floats.sden);
        if !fraction.is_finite() || fraction.abs() > 1e36 {
            return Err(EngineError::SlaveOverflow);
        }
        whole
            .checked_add(whole_to_i128(fraction))
            .ok_or(EngineError::SlaveOverflow)
    }

    /// [`Geometry::zoomed`] in 64 bits, the same steps: `None` when a
    /// value leaves them (the 128-bit route then decides).
    #[inline]
    fn zoomed_narrow(&self, strokes: i64, table: f64) -> Option<i64> {
        // `strokes × (stroke × snum)`: where it fits it is the product
        // in either order (the 128-bit route decides where it does not).
        let n = self.narrow.as_ref()?;
        let accumulated = strokes.checked_mul(n.stroke_snum)?;
        let (whole, rem) = floor_div_rem(accumulated, n.sden);
        let fraction =
            round_half_up_to_i64((rem as f64 + table * self.floats.snum) / self.floats.sden)?;
        whole.checked_add(fraction)
    }
}

/// Floor division and its non-negative remainder for `b > 0`. Cycle
/// arithmetic is `i128` so nothing can overflow, but nearly every real value
/// fits 64 bits, where one hardware division is several times faster than
/// the 128-bit library routine.
#[inline]
fn div_floor(a: i128, b: i128) -> (i128, i128) {
    match (i64::try_from(a), i64::try_from(b)) {
        (Ok(a), Ok(b)) if b > 0 => {
            let (q, r) = floor_div_rem(a, b);
            (i128::from(q), i128::from(r))
        }
        _ => (a.div_euclid(b), a.rem_euclid(b)),
    }
}

/// `a × b`, `None` on overflow. Factors that fit 64 bits (nearly always)
/// take one widening multiply instead of the overflow-checked 128-bit routine.
#[inline]
fn mul_exact(a: i128, b: i128) -> Option<i128> {
    match (i64::try_from(a), i64::try_from(b)) {
        (Ok(a), Ok(b)) => Some(i128::from(a) * i128::from(b)),
        _ => a.checked_mul(b),
    }
}

/// `v` as a float. Values that fit 64 bits (nearly all) take the one
/// instruction conversion instead of the 128-bit library routine; larger
/// ones are built from their two halves (within a rounding of the nearest
/// float, which is all a float inside a cycle needs).
#[inline]
pub(crate) fn to_f64(v: i128) -> f64 {
    match i64::try_from(v) {
        Ok(small) => small as f64,
        Err(_) => ((v >> 64) as i64 as f64) * 18_446_744_073_709_551_616.0 + (v as u64) as f64,
    }
}

fn clamp_i64(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

/// The integers fixed at the engage instant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Engagement {
    /// Table input = master × num + `input_offset_num` (× den units).
    input_offset_num: i128,
    /// Whole strokes added to the master's cycle number: the cycle the
    /// cam engaged in counts as the strokes the start rule chose
    /// (`start_rule.rs`), not as its distance from the table's origin.
    shift: i128,
    /// Added to the zoomed table value.
    output_offset: i128,
    /// Cycle at the engage instant (cycles are reported from here).
    pub(crate) k_engage: i128,
    /// One-shot: the table-input range the cam covers.
    pub(crate) span: Option<(i128, i128)>,
}

/// The commanded slave at one place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sample {
    pub(crate) place: Place,
    pub(crate) slave: i64,
    pub(crate) unzoomed: i64,
    pub(crate) in_cycle_zoomed: i64,
    pub(crate) velocity_ratio: f64,
}

/// What placing an engagement found at its own place: the table's
/// value and slope there, and the table's value zoomed at the start
/// rule's strokes (what the output offset was fixed from), so that the
/// engaging tick's sample does not zoom the table a second time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AtEngage {
    pub(crate) table: Table,
    pub(crate) zoomed: i128,
}

fn table_value<C: CamCurve + ?Sized>(
    curve: &C,
    cursor: &mut Cursor,
    x: f64,
) -> Result<(f64, f64), EngineError> {
    let k = curve.eval(x, cursor);
    if k.s.is_finite() && k.v.is_finite() {
        Ok((k.s, k.v))
    } else {
        Err(EngineError::CurveNotFinite)
    }
}

impl Engagement {
    /// Fixes the coupling at master `master_at`, with the slave commanded at
    /// `slave_now`.
    pub(crate) fn new<C: CamCurve + ?Sized>(
        geo: &Geometry,
        config: &AxisConfig,
        curve: &C,
        cursor: &mut Cursor,
        master_at: i64,
        slave_now: i64,
    ) -> Result<Self, EngineError> {
        Self::placed(geo, config, curve, cursor, master_at, slave_now).map(|(e, _, _)| e)
    }

    /// [`Engagement::new`], with the place of `master_at` under it and
    /// the table's value and slope there and the slave the cam commands
    /// there (what the engaging tick follows:
    /// [`Engagement::sample_at_engage`] gives its sample without a second
    /// lookup).
    pub(crate) fn placed<C: CamCurve + ?Sized>(
        geo: &Geometry,
        config: &AxisConfig,
        curve: &C,
        cursor: &mut Cursor,
        master_at: i64,
        slave_now: i64,
    ) -> Result<(Self, Place, AtEngage), EngineError> {
        let zoomed = geo.zoomed_master(master_at);
        let t_engage = match config.master_align {
            MasterAlign::Absolute => zoomed,
            MasterAlign::Offset(o) => zoomed.saturating_add(i128::from(o) * geo.mden),
            MasterAlign::StartAt(v) => i128::from(v) * geo.mden,
            MasterAlign::StartAtUnzoomed(v) => i128::from(v) * geo.mnum,
        };
        let place = geo.locate(t_engage);
        let (table, slope) = table_value(curve, cursor, geo.table_x(place))?;
        let target = i128::from(slave_now);
        let (strokes, valued) =
            start_rule::strokes_at_start(geo.strokes(), config.slave_align, target, |n| {
                geo.zoomed(n, table)
            })?;
        // The stroke count of the cycle the master is in is `strokes`:
        // cycles count from there, not from the table's origin.
        let shift = strokes.saturating_sub(place.k);
        let on_table = match valued {
            Some(value) => value,
            None => geo.zoomed(strokes, table)?,
        };
        let output_offset = match config.slave_align {
            SlaveAlign::Absolute | SlaveAlign::NearestEquivalent => 0,
            SlaveAlign::Offset(o) => i128::from(o),
            SlaveAlign::Relative => target
                .checked_sub(on_table)
                .ok_or(EngineError::SlaveOverflow)?,
            SlaveAlign::At(v) => i128::from(v)
                .checked_sub(on_table)
                .ok_or(EngineError::SlaveOverflow)?,
            SlaveAlign::Modulo { axis, offset } => {
                axis.engage_offset(on_table, target, i128::from(offset))
            }
        };
        let span = match geo.extent {
            Extent::Cycles(n) => Some((
                t_engage,
                t_engage.saturating_add(i128::from(n).saturating_mul(geo.period_num)),
            )),
            Extent::Cyclic | Extent::Single => None,
        };
        Ok((
            Self {
                input_offset_num: t_engage.saturating_sub(zoomed),
                shift,
                output_offset,
                k_engage: place.k,
                span,
            },
            place,
            AtEngage {
                table: Table { s: table, v: slope },
                zoomed: on_table,
            },
        ))
    }

    /// Table input (× den units) for a master position.
    pub(crate) fn table_input(&self, geo: &Geometry, master: i64) -> i128 {
        geo.zoomed_master(master)
            .saturating_add(self.input_offset_num)
    }

    /// The engagement that carries a running cam onto a new table at the
    /// seam it just crossed: the boundary of old cycle `k` (its end when
    /// `forward`, else its start) becomes the start of the new table's
    /// cycle 0, and the output offset is chosen so that the new table gives
    /// `slave_at_seam` there: the slave is continuous across the switch.
    /// A one-shot's remaining travel is rescaled to the new cycle length.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn across_seam<C: CamCurve + ?Sized>(
        &self,
        old: &Geometry,
        new: &Geometry,
        curve: &C,
        cursor: &mut Cursor,
        k: i128,
        forward: bool,
        slave_at_seam: i64,
    ) -> Result<Self, EngineError> {
        let seam = old.boundary(k, forward);
        let input_offset_num = self
            .input_offset_num
            .checked_add(new.origin_num)
            .and_then(|v| v.checked_sub(seam))
            .ok_or(EngineError::SlaveOverflow)?;
        // Seen from the side the master came from: a periodic table's jump
        // belongs to the next cycle.
        let at_seam = if forward {
            Geometry::cycle_start(0)
        } else {
            new.cycle_end(-1)
        };
        let (table, _) = table_value(curve, cursor, new.table_x(at_seam))?;
        let on_table = new.zoomed(at_seam.k, table)?;
        let output_offset = i128::from(slave_at_seam)
            .checked_sub(on_table)
            .ok_or(EngineError::SlaveOverflow)?;
        let cycles_done =
            (if forward { k.saturating_add(1) } else { k }).saturating_sub(self.k_engage);
        let rescale = |t: i128| {
            let travel = t.saturating_sub(seam).saturating_mul(new.period_num);
            new.origin_num
                .saturating_add(div_floor(travel, old.period_num.max(1)).0)
        };
        Ok(Self {
            input_offset_num,
            shift: 0,
            output_offset,
            k_engage: cycles_done.saturating_neg(),
            span: self.span.map(|(begin, end)| (rescale(begin), rescale(end))),
        })
    }

    /// Limits the cam to the new table's first cycle after a seam switch:
    /// cycle 0 going forwards, cycle −1 going backwards.
    pub(crate) fn finish_after_first_pass(&mut self, geo: &Geometry, forward: bool) {
        let start = geo.origin_num;
        self.span = Some(if forward {
            (start, start.saturating_add(geo.period_num))
        } else {
            (start.saturating_sub(geo.period_num), start)
        });
    }

    /// The same engagement with `input_num` added to the table input
    /// (× master-zoom-denominator units) and `output` to the output.
    pub(crate) fn shifted(&self, input_num: i128, output: i128) -> Result<Self, EngineError> {
        Ok(Self {
            input_offset_num: self
                .input_offset_num
                .checked_add(input_num)
                .ok_or(EngineError::SlaveOverflow)?,
            output_offset: self
                .output_offset
                .checked_add(output)
                .ok_or(EngineError::SlaveOverflow)?,
            ..*self
        })
    }

    /// The same engagement on `new`, a geometry that differs from `old`
    /// only in its master zoom, with the table input at master `at` kept
    /// (to the nearest new table unit): the cam's phase is continuous.
    pub(crate) fn with_master_rescaled(
        &self,
        old: &Geometry,
        new: &Geometry,
        at: i64,
    ) -> Result<Self, EngineError> {
        let rescale = |t: i128| -> Result<i128, EngineError> {
            let scaled = mul_exact(t, new.mden)
                .and_then(|v| v.checked_mul(2))
                .and_then(|v| v.checked_add(old.mden))
                .ok_or(EngineError::SlaveOverflow)?;
            Ok(div_floor(scaled, 2 * old.mden).0)
        };
        let t_new = rescale(self.table_input(old, at))?;
        let span = match self.span {
            Some((begin, end)) => Some((rescale(begin)?, rescale(end)?)),
            None => None,
        };
        Ok(Self {
            input_offset_num: t_new
                .checked_sub(new.zoomed_master(at))
                .ok_or(EngineError::SlaveOverflow)?,
            span,
            ..*self
        })
    }

    /// Adds `n` whole strokes to the output (a direction-restricted
    /// ramp-in's target on a repeat cam).
    pub(crate) fn add_strokes(&mut self, n: i128) {
        self.shift = self.shift.saturating_add(n);
    }

    /// The whole master count at or before (`forward`) or at or after
    /// the boundary of cycle `k` (its end when `forward`, else its start).
    pub(crate) fn master_at_seam(&self, geo: &Geometry, k: i128, forward: bool) -> i64 {
        let t = geo
            .boundary(k, forward)
            .saturating_sub(self.input_offset_num);
        // master = t / mnum; the side of the old cycle is below the
        // boundary going forwards (above going backwards) in table input,
        // which a negative master zoom turns round in master counts.
        let (t, up) = if geo.mnum < 0 {
            (t.saturating_neg(), forward)
        } else {
            (t, !forward)
        };
        let (q, r) = div_floor(t, geo.mnum.abs().max(1));
        clamp_i64(if up && r != 0 { q.saturating_add(1) } else { q })
    }

    /// Moves the whole output by `delta` pulses (a blend that ended
    /// `delta` off the cam it blended onto).
    pub(crate) fn shift_output(&mut self, delta: i128) -> Result<(), EngineError> {
        self.output_offset = self
            .output_offset
            .checked_add(delta)
            .ok_or(EngineError::SlaveOverflow)?;
        Ok(())
    }

    /// Document 002 `CamInputOffset`, in table counts (floor).
    #[inline(always)]
    pub(crate) fn input_offset(&self, geo: &Geometry) -> i64 {
        match (
            i64::try_from(self.input_offset_num),
            i64::try_from(geo.mden),
        ) {
            // The common case in one division (the denominator is positive).
            (Ok(num), Ok(den)) if den > 0 => num.div_euclid(den),
            _ => clamp_i64(div_floor(self.input_offset_num, geo.mden).0),
        }
    }

    /// The 64-bit constants of this engagement on `geo` for the steady
    /// tick ([`crate::steady`]); `None` for a one-shot or a normal cam
    /// (their place is clamped) or when a constant leaves 64 bits.
    #[inline]
    pub(crate) fn steady(&self, geo: &Geometry) -> Option<Steady> {
        if geo.extent != Extent::Cyclic || self.span.is_some() || geo.mnum <= 0 {
            return None;
        }
        let narrow = |v: i128| i64::try_from(v).ok();
        let n = geo.narrow.as_ref()?;
        Some(Steady {
            mnum: n.mnum,
            offset_num: narrow(self.input_offset_num)?.checked_sub(n.origin_num)?,
            period_num: n.period_num,
            origin: geo.origin,
            origin_f: geo.origin as f64,
            mden: n.mden,
            mden_f: geo.floats.mden,
            shift: narrow(self.shift)?,
            stroke: n.stroke,
            stroke_snum: n.stroke_snum,
            snum_f: geo.floats.snum,
            sden: n.sden,
            sden_f: geo.floats.sden,
            zoom_factor: geo.zoom_factor(),
            output_offset: narrow(self.output_offset)?,
            k_engage: narrow(self.k_engage)?,
            input_offset: self.input_offset(geo),
        })
    }

    /// The commanded slave at `place`.
    pub(crate) fn sample<C: CamCurve + ?Sized>(
        &self,
        geo: &Geometry,
        curve: &C,
        cursor: &mut Cursor,
        place: Place,
    ) -> Result<Sample, EngineError> {
        let (s, v) = table_value(curve, cursor, geo.table_x(place))?;
        self.sample_of(geo, place, Table { s, v })
    }

    /// [`Engagement::sample`] for the table's value and slope at `place`
    /// known already (`table`, as [`Engagement::placed`] gives them).
    #[inline]
    pub(crate) fn sample_of(
        &self,
        geo: &Geometry,
        place: Place,
        table: Table,
    ) -> Result<Sample, EngineError> {
        match self.sample_narrow(geo, place, table.s, table.v) {
            Some(sample) => Ok(sample),
            None => self.sample_wide(geo, place, table.s, table.v),
        }
    }

    /// [`Engagement::sample_of`] at the engagement's own place, as
    /// [`Engagement::placed`] left it (`at`): the same sample, from the
    /// zoomed value it worked out there.
    #[inline]
    pub(crate) fn sample_at_engage(
        &self,
        geo: &Geometry,
        place: Place,
        at: AtEngage,
    ) -> Result<Sample, EngineError> {
        match self.slave_at_engage(at) {
            Some(slave) => self.sample_with_slave(geo, place, at.table, slave),
            None => self.sample_of(geo, place, at.table),
        }
    }

    /// The slave the cam commands at the engagement's own place, as
    /// [`Engagement::placed`] left it (`at`), from the zoomed value it
    /// worked out there: [`Engagement::sample_of`]'s slave. The strokes
    /// there are the start rule's, `place.k + shift`, unless the shift
    /// saturated (never for a place of a 64-bit master); `None` then, or
    /// where the slave leaves 64 bits: the full sample decides.
    #[inline]
    pub(crate) fn slave_at_engage(&self, at: AtEngage) -> Option<i64> {
        if self.shift == i128::MAX || self.shift == i128::MIN {
            return None;
        }
        at.zoomed
            .checked_add(self.output_offset)
            .and_then(|slave| i64::try_from(slave).ok())
    }

    /// [`Engagement::sample_of`]'s slave alone, for the table's value and
    /// slope at `place` (`table`): the zoomed value and the output offset,
    /// without the rest of the sample (what a restricted ramp-in
    /// direction checks after adding strokes).
    ///
    /// # Errors
    /// As [`Engagement::sample_of`].
    pub(crate) fn slave_of(
        &self,
        geo: &Geometry,
        place: Place,
        table: Table,
    ) -> Result<i64, EngineError> {
        match self.slave_narrow(geo, place, table.s) {
            Some(slave) => Ok(slave),
            None => self.sample_of(geo, place, table).map(|sample| sample.slave),
        }
    }

    /// [`Engagement::slave_of`] after `n` strokes were added, from the
    /// slave before (`before`): where one stroke zooms to a whole number
    /// of pulses (stroke × slave numerator a multiple of the denominator,
    /// as with a slave zoom of 1), each stroke adds exactly that many to
    /// the zoomed value (the cycle's remainder is 0 for every stroke
    /// count, so the rounded fraction is the same), and the slave moves
    /// by `n` of them. Used only where the 64-bit route would give a
    /// value for the new strokes; else zoomed again.
    ///
    /// # Errors
    /// As [`Engagement::sample_of`].
    #[inline]
    pub(crate) fn slave_after_strokes(
        &self,
        geo: &Geometry,
        place: Place,
        table: Table,
        before: i64,
        n: i128,
    ) -> Result<i64, EngineError> {
        let moved = geo.narrow.as_ref().and_then(|g| {
            let per_stroke = g.whole_stroke?;
            let strokes = i64::try_from(place.k.checked_add(self.shift)?).ok()?;
            strokes.checked_mul(g.stroke_snum)?;
            before.checked_add(i64::try_from(n).ok()?.checked_mul(per_stroke)?)
        });
        match moved {
            Some(slave) => Ok(slave),
            None => self.slave_of(geo, place, table),
        }
    }

    /// [`Engagement::sample_of`] where its slave is known already
    /// (`slave`, from [`Engagement::slave_of`] or
    /// [`Engagement::slave_at_engage`]): the rest of the sample around it.
    #[inline(always)]
    pub(crate) fn sample_with_slave(
        &self,
        geo: &Geometry,
        place: Place,
        table: Table,
        slave: i64,
    ) -> Result<Sample, EngineError> {
        match self.sample_around(geo, place, table.s, table.v, slave) {
            Some(sample) => Ok(sample),
            None => self.sample_of(geo, place, table),
        }
    }

    /// [`Engagement::sample`] in 64-bit integers, for the table value
    /// `table` and slope `slope` at `place`: the same steps in the same
    /// order as [`Engagement::sample_wide`] (as the steady tick takes them),
    /// so the same results; `None` as soon as a value would leave 64 bits,
    /// and the wide path decides (and reports any error).
    #[inline]
    fn sample_narrow(
        &self,
        geo: &Geometry,
        place: Place,
        table: f64,
        slope: f64,
    ) -> Option<Sample> {
        let slave = self.slave_narrow(geo, place, table)?;
        self.sample_around(geo, place, table, slope, slave)
    }

    /// The slave at `place` for the table value `table`, in 64 bits:
    /// the zoomed value at the engagement's strokes there plus the
    /// output offset; `None` as soon as a value would leave 64 bits.
    #[inline(always)]
    fn slave_narrow(&self, geo: &Geometry, place: Place, table: f64) -> Option<i64> {
        let narrow = |v: i128| i64::try_from(v).ok();
        let strokes = narrow(place.k)?.checked_add(narrow(self.shift)?)?;
        geo.zoomed_narrow(strokes, table)?
            .checked_add(narrow(self.output_offset)?)
    }

    /// The rest of [`Engagement::sample_narrow`] around the slave it
    /// commands (`slave`): the unzoomed value, the zoomed value in the
    /// cycle and the velocity ratio.
    #[inline]
    fn sample_around(
        &self,
        geo: &Geometry,
        place: Place,
        table: f64,
        slope: f64,
        slave: i64,
    ) -> Option<Sample> {
        let narrow = |v: i128| i64::try_from(v).ok();
        let strokes = narrow(place.k)?.checked_add(narrow(self.shift)?)?;
        let stroke = narrow(geo.stroke)?;
        let unzoomed = strokes
            .checked_mul(stroke)?
            .checked_add(round_to_i64(table)?)?;
        let in_cycle = table * geo.floats.snum / geo.floats.sden;
        Some(Sample {
            place,
            slave,
            unzoomed,
            // Saturating, as the wide path reports it.
            in_cycle_zoomed: round_to_i64(in_cycle)
                .unwrap_or_else(|| round_half_away(in_cycle) as i64),
            velocity_ratio: slope * geo.zoom_factor(),
        })
    }

    /// [`Engagement::sample`] in 128-bit integers (any value).
    fn sample_wide(
        &self,
        geo: &Geometry,
        place: Place,
        table: f64,
        slope: f64,
    ) -> Result<Sample, EngineError> {
        let strokes = place.k.saturating_add(self.shift);
        let zoomed = geo.zoomed(strokes, table)?;
        let slave = zoomed
            .checked_add(self.output_offset)
            .and_then(|s| i64::try_from(s).ok())
            .ok_or(EngineError::SlaveOverflow)?;
        let unzoomed = mul_exact(strokes, geo.stroke)
            .unwrap_or(i128::MAX)
            .saturating_add(whole_to_i128(round_half_away(table)));
        let in_cycle_zoomed = round_half_away(table * geo.floats.snum / geo.floats.sden) as i64;
        Ok(Sample {
            place,
            slave,
            unzoomed: clamp_i64(unzoomed),
            in_cycle_zoomed,
            velocity_ratio: slope * geo.zoom_factor(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rounding::xorshift;
    use crate::{AxisConfig, Coupling, Zoom};
    use core::num::NonZeroU64;
    use ecam_core::PointTable;

    fn doc001() -> PointTable {
        PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap()
    }

    /// The 64-bit sample is the 128-bit one wherever it gives a value, and
    /// gives one for every value of ordinary size.
    #[test]
    fn narrow_sample_equals_wide_sample() {
        let mut words = xorshift(0x5851_F42D_4C95_7F2D);
        let mut next = move || words.next().unwrap_or(1);
        let mut compared = 0;
        for _ in 0..20_000 {
            let pick = |w: u64, scale: u32| (w >> (64 - scale)) as i64 - (1i64 << (scale - 1));
            let config = AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                master_zoom: Zoom::new(1 + (next() % 9) as u16, 1 + (next() % 7) as u16).unwrap(),
                slave_zoom: Zoom::signed(
                    if next() % 2 == 0 { 1 } else { -1 } * (1 + (next() % 11) as i32),
                    1 + (next() % 13) as u16,
                )
                .unwrap(),
                ..AxisConfig::default()
            };
            let scale = [20, 40, 62][(next() % 3) as usize];
            let t =
                PointTable::from_pairs(&[(0, pick(next(), scale)), (1000, pick(next(), scale))])
                    .unwrap();
            let geo = Geometry::new(&t, &config).unwrap();
            let e = Engagement {
                input_offset_num: 0,
                shift: i128::from(pick(next(), scale)),
                output_offset: i128::from(pick(next(), scale)),
                k_engage: 0,
                span: None,
            };
            let place = Place {
                k: i128::from(pick(next(), scale)),
                r_num: i128::from((next() % 1000) as i64),
            };
            let table = (pick(next(), scale) as f64) * 0.37;
            let slope = 0.25;
            let wide = e.sample_wide(&geo, place, table, slope);
            match e.sample_narrow(&geo, place, table, slope) {
                Some(narrow) => {
                    assert_eq!(Ok(narrow), wide, "{e:?} {place:?} {table}");
                    compared += 1;
                }
                None => assert!(scale > 20, "small values stay narrow: {e:?} {place:?}"),
            }
        }
        assert!(compared > 5000, "{compared}");
    }

    /// A place's table input and raw master in the cycle are the same in
    /// 64 bits as by the 128-bit floor, for every master zoom (either
    /// sign) and every offset into the cycle, the table's origin included.
    #[test]
    fn narrow_places_in_the_cycle_equal_the_wide_ones() {
        let mut words = xorshift(0x2545_F491_4F6C_DD1D);
        let mut next = move || words.next().unwrap_or(1);
        for _ in 0..20_000 {
            let first = (next() % 2_000_001) as i64 - 1_000_000;
            let span = 1 + (next() % 100_000) as i64;
            let config = AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                master_zoom: Zoom::signed(
                    if next() % 2 == 0 { 1 } else { -1 } * (1 + (next() % 65_534) as i32),
                    1 + (next() % 65_534) as u16,
                )
                .unwrap(),
                ..AxisConfig::default()
            };
            let t = PointTable::from_pairs(&[(first, 0), (first + span, 700)]).unwrap();
            let geo = Geometry::new(&t, &config).unwrap();
            let place = Place {
                k: i128::from(next() as i64),
                r_num: i128::from(next()) % geo.period_num.max(1),
            };
            let (whole, _) = div_floor(place.r_num, geo.mden);
            let input = clamp_i64(i128::from(geo.origin).saturating_add(whole));
            let raw = clamp_i64(div_floor(place.r_num, geo.mnum.abs().max(1)).0);
            assert_eq!(geo.input_in_cycle(place), input, "{place:?}");
            assert_eq!(geo.raw_in_cycle(place), raw, "{place:?}");
        }
    }

    #[test]
    fn repeat_is_continuous_at_the_seam() {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let t = doc001();
        let geo = Geometry::new(&t, &config).unwrap();
        let mut c = Cursor::new();
        let e = Engagement::new(&geo, &config, &t, &mut c, 0, 0).unwrap();
        let at = |m: i64, c: &mut Cursor| {
            let p = geo.locate(e.table_input(&geo, m));
            e.sample(&geo, &t, c, p).unwrap().slave
        };
        assert_eq!(at(30000, &mut c), 2000);
        assert_eq!(at(40000, &mut c), 3000);
        assert_eq!(at(-10000, &mut c), 1000 - 1500);
        assert_eq!(at(-1, &mut c), 500);
        assert_eq!(at(90000, &mut c), 500 + 3 * 1500);
    }

    #[test]
    fn nearest_equivalent_matches_document_001() {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            slave_align: SlaveAlign::NearestEquivalent,
            single_turn: NonZeroU64::new(30000),
            ..AxisConfig::default()
        };
        let t = doc001();
        let geo = Geometry::new(&t, &config).unwrap();
        let mut c = Cursor::new();
        let e = Engagement::new(&geo, &config, &t, &mut c, 20000, -1500).unwrap();
        let p = geo.locate(e.table_input(&geo, 20000));
        assert_eq!(e.sample(&geo, &t, &mut c, p).unwrap().slave, -2000);
    }

    #[test]
    fn zoom_is_exact() {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_zoom: Zoom::new(7, 3).unwrap(),
            slave_zoom: Zoom::new(5, 3).unwrap(),
            ..AxisConfig::default()
        };
        let t = PointTable::from_pairs(&[(0, 0), (100, 1)]).unwrap();
        let geo = Geometry::new(&t, &config).unwrap();
        let mut c = Cursor::new();
        let e = Engagement::new(&geo, &config, &t, &mut c, 0, 0).unwrap();
        // master 3×10^12 → table input 7×10^12 = 7×10^10 cycles of stroke 1;
        // slave = 7×10^10 × 5/3, rounded.
        let m = 3_000_000_000_000;
        let p = geo.locate(e.table_input(&geo, m));
        let expected = (70_000_000_000i128 * 5 + 1) / 3;
        assert_eq!(
            i128::from(e.sample(&geo, &t, &mut c, p).unwrap().slave),
            expected
        );
    }
}
