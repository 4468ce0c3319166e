//! The steady tick: a running cam with nothing changing, computed from
//! constants fixed once per engagement, in 64-bit integers.
//!
//! While a cam simply runs (no ramp-in, switch, blend, offset or scaling
//! change, no one-shot span, no end-of-cycle stop, whole master counts)
//! every integer the coupling law needs is fixed from the engage instant
//! on: zoom factors, the input offset, the stroke, the output offset. They
//! are taken once, into 64-bit fields, the moment the cam settles, and each
//! tick is then one cycle division, one lookup, one stroke division and one
//! rounding. The arithmetic is the coupling law's own, in the same order
//! (`coupling.rs`), so every result is the same; any product that would
//! leave 64 bits hands the tick back to the general 128-bit path, which
//! also reports every error. `axis.rs` tests both paths against each other.

use ecam_core::{CamCurve, Cursor};

use crate::rounding::{floor_div_rem, round_half_away, round_half_up_to_i64, round_to_i64};

/// The constants of one settled engagement (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Steady {
    /// Master zoom numerator (table input per master count, × `mden`).
    pub(crate) mnum: i64,
    /// Added to `master × mnum` to give the offset from the table origin.
    pub(crate) offset_num: i64,
    /// One cycle in table-input units.
    pub(crate) period_num: i64,
    /// The table's first master.
    pub(crate) origin: i64,
    pub(crate) origin_f: f64,
    /// Master zoom denominator.
    pub(crate) mden: i64,
    pub(crate) mden_f: f64,
    /// Whole strokes added to the cycle index (nearest-equivalent start).
    pub(crate) shift: i64,
    /// Slave change per cycle, before zoom.
    pub(crate) stroke: i64,
    /// `stroke × snum`.
    pub(crate) stroke_snum: i64,
    pub(crate) snum_f: f64,
    /// Slave zoom denominator.
    pub(crate) sden: i64,
    pub(crate) sden_f: f64,
    /// The two zooms' product, as the coupling law forms it.
    pub(crate) zoom_factor: f64,
    /// Added to the zoomed table value.
    pub(crate) output_offset: i64,
    /// The cycle at the engage instant (cycles are reported from it).
    pub(crate) k_engage: i64,
    /// Document 002 `CamInputOffset`, reported each tick.
    pub(crate) input_offset: i64,
}

/// The table's value and slope at one place (both finite).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Table {
    pub(crate) s: f64,
    pub(crate) v: f64,
}

/// What one steady tick computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SteadySample {
    /// Cycle index and offset into it (as `coupling::Place`).
    pub(crate) k: i64,
    pub(crate) r_num: i64,
    /// The commanded slave.
    pub(crate) slave: i64,
    /// Table value plus accumulated strokes, before slave zoom.
    pub(crate) unzoomed: i64,
    /// The table value in the cycle after slave zoom, rounded.
    pub(crate) in_cycle_zoomed: i64,
    pub(crate) velocity_ratio: f64,
    /// Table input in the cycle after master zoom (floor).
    pub(crate) master_in_cycle: i64,
    /// The same before master zoom (floor).
    pub(crate) master_in_cycle_raw: i64,
}

impl Steady {
    /// The same constants, bit for bit (floats by their bits), in one
    /// pass without branches: what a prepared switch checks that it was
    /// prepared from (`axis/plan.rs`).
    #[inline]
    pub(crate) fn same(&self, other: &Self) -> bool {
        let ints = [
            self.mnum ^ other.mnum,
            self.offset_num ^ other.offset_num,
            self.period_num ^ other.period_num,
            self.origin ^ other.origin,
            self.mden ^ other.mden,
            self.shift ^ other.shift,
            self.stroke ^ other.stroke,
            self.stroke_snum ^ other.stroke_snum,
            self.sden ^ other.sden,
            self.output_offset ^ other.output_offset,
            self.k_engage ^ other.k_engage,
            self.input_offset ^ other.input_offset,
        ];
        let floats = [
            self.origin_f.to_bits() ^ other.origin_f.to_bits(),
            self.mden_f.to_bits() ^ other.mden_f.to_bits(),
            self.snum_f.to_bits() ^ other.snum_f.to_bits(),
            self.sden_f.to_bits() ^ other.sden_f.to_bits(),
            self.zoom_factor.to_bits() ^ other.zoom_factor.to_bits(),
        ];
        ints.iter().fold(0, |a, v| a | v) == 0 && floats.iter().fold(0, |a, v| a | v) == 0
    }

    /// The same constants with `input` added to the table input (×
    /// master-zoom-denominator units) and `output` to the output, as
    /// `Engagement::shifted` moves an engagement; `None` when a value
    /// leaves 64 bits.
    #[inline]
    pub(crate) fn shifted(&self, input: i128, output: i128) -> Option<Self> {
        Some(Self {
            offset_num: self.offset_num.checked_add(i64::try_from(input).ok()?)?,
            output_offset: self
                .output_offset
                .checked_add(i64::try_from(output).ok()?)?,
            ..*self
        })
    }

    /// The cam at `master`, or `None` when a value leaves 64 bits or the
    /// curve gives no finite value (the general path then decides).
    #[inline(always)]
    pub(crate) fn sample<C: CamCurve + ?Sized>(
        &self,
        master: i64,
        curve: &C,
        cursor: &mut Cursor,
    ) -> Option<SteadySample> {
        let u = master
            .checked_mul(self.mnum)?
            .checked_add(self.offset_num)?;
        // `div_euclid` here rather than `place`'s `floor_div_rem`: the
        // same values, and the compiler makes the steady tick shorter so.
        let k = u.div_euclid(self.period_num);
        let r_num = u.rem_euclid(self.period_num);
        let kin = self.table(r_num, curve, cursor)?;
        self.zoom(k, r_num, kin)
    }

    /// The cycle `k` and the offset `r_num` into it of `master` (as
    /// `Geometry::locate` of the table input).
    #[inline(always)]
    pub(crate) fn place(&self, master: i64) -> Option<(i64, i64)> {
        let u = master
            .checked_mul(self.mnum)?
            .checked_add(self.offset_num)?;
        Some(floor_div_rem(u, self.period_num))
    }

    /// The table value and slope at offset `r_num` into a cycle (the
    /// curve's kinematics; `None` when not finite).
    #[inline(always)]
    pub(crate) fn table<C: CamCurve + ?Sized>(
        &self,
        r_num: i64,
        curve: &C,
        cursor: &mut Cursor,
    ) -> Option<Table> {
        let x = self.origin_f + r_num as f64 / self.mden_f;
        let kin = curve.eval(x, cursor);
        if !(kin.s.is_finite() && kin.v.is_finite()) {
            return None;
        }
        Some(Table { s: kin.s, v: kin.v })
    }

    /// The cam at place (`k`, `r_num`) for the table's kinematics `kin`
    /// there (two sets of constants that differ only in the slave zoom
    /// share one table lookup: a slave-scaling ramp).
    #[inline(always)]
    pub(crate) fn zoom(&self, k: i64, r_num: i64, kin: Table) -> Option<SteadySample> {
        let strokes = k.checked_add(self.shift)?;
        let accumulated = strokes.checked_mul(self.stroke_snum)?;
        let (whole, rem) = floor_div_rem(accumulated, self.sden);
        let fraction = round_half_up_to_i64((rem as f64 + kin.s * self.snum_f) / self.sden_f)?;
        let slave = whole
            .checked_add(fraction)?
            .checked_add(self.output_offset)?;
        let unzoomed = strokes
            .checked_mul(self.stroke)?
            .checked_add(round_to_i64(kin.s)?)?;
        let in_cycle = kin.s * self.snum_f / self.sden_f;
        Some(SteadySample {
            k,
            r_num,
            slave,
            unzoomed,
            // Saturating, as the general path reports it.
            in_cycle_zoomed: round_to_i64(in_cycle)
                .unwrap_or_else(|| round_half_away(in_cycle) as i64),
            velocity_ratio: kin.v * self.zoom_factor,
            master_in_cycle: self.origin.checked_add(r_num / self.mden)?,
            master_in_cycle_raw: r_num / self.mnum,
        })
    }
}
