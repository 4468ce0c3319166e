//! The minimal loop: one axis-tick written by hand with nothing but the
//! work a repeat cam needs each cycle, as the honest limit the engine's
//! tick is measured against (`axis_tick` bench, `side_by_side` example).
//!
//! Same work as the engine for a running repeat cam: the exact cycle
//! division, the cursor lookup and interpolation (the same `PointTable`),
//! exact zoom and accumulated stroke rounded once, the pulse frequency
//! limiter with its credit, four sync windows, and the full output record
//! (`TickOutput`) written. What it leaves out is what a real engine cannot:
//! states, starts, stops, switches, ramps and every overflow check: it
//! assumes all products fit 64 bits. It rounds with one float-to-integer
//! conversion, as the engine does, so neither side gains from a library call.

use ecam_core::{CamCurve, Cursor, PointTable};
use ecam_engine::{AxisConfig, AxisState, SyncWindow, TickOutput};

/// One pulse in the limiter's credit unit (µs × Hz).
const PULSE: u64 = 1_000_000;

/// A hand-written repeat-cam axis (see the module docs).
pub struct MinimalAxis {
    table: PointTable,
    cursor: Cursor,
    mnum: i64,
    mden: i64,
    mden_f: f64,
    snum: i64,
    snum_f: f64,
    sden: i64,
    sden_f: f64,
    zoom_factor: f64,
    origin: i64,
    origin_f: f64,
    period_num: i64,
    stroke: i64,
    input_offset_num: i64,
    output_offset: i64,
    k_engage: i64,
    hz_dt: u64,
    credit: u64,
    emitted: i64,
    windows: [SyncWindow; 4],
    out: TickOutput,
}

impl MinimalAxis {
    /// Engaged at `master` with the slave at `slave` (relative alignment).
    pub fn engage(table: PointTable, config: &AxisConfig, master: i64, slave: i64) -> Option<Self> {
        let origin = table.master_first();
        let span = table.master_span();
        let stroke = table.stroke();
        let mnum = i64::from(config.master_zoom.num());
        let mden = i64::from(config.master_zoom.den());
        let snum = i64::from(config.slave_zoom.num());
        let sden = i64::from(config.slave_zoom.den());
        let hz = u64::try_from(config.max_frequency_hz).ok()?;
        let mut axis = Self {
            table,
            cursor: Cursor::new(),
            mnum,
            mden,
            mden_f: mden as f64,
            snum,
            snum_f: snum as f64,
            sden,
            sden_f: sden as f64,
            zoom_factor: (mnum as f64 / mden as f64) * (snum as f64 / sden as f64),
            origin,
            origin_f: origin as f64,
            period_num: span.checked_mul(mden)?,
            stroke,
            input_offset_num: 0,
            output_offset: 0,
            k_engage: 0,
            hz_dt: hz * u64::from(super::DT_US),
            credit: 0,
            emitted: slave,
            windows: config.sync_windows,
            out: TickOutput::default(),
        };
        let (k, _, slave_on_cam, _) = axis.cam(master);
        axis.k_engage = k;
        axis.output_offset = slave - slave_on_cam;
        Some(axis)
    }

    /// Cycle, offset into it (× mden), zoomed slave before the output
    /// offset, and the table's value and slope there.
    #[inline(always)]
    fn cam(&mut self, master: i64) -> (i64, i64, i64, ecam_core::Kinematics) {
        let t = master * self.mnum + self.input_offset_num - self.origin * self.mden;
        let k = t.div_euclid(self.period_num);
        let r = t.rem_euclid(self.period_num);
        let x = self.origin_f + r as f64 / self.mden_f;
        let kin = self.table.eval(x, &mut self.cursor);
        let accumulated = k * self.stroke * self.snum;
        let whole = accumulated.div_euclid(self.sden);
        let rem = accumulated.rem_euclid(self.sden);
        let fraction = round((rem as f64 + kin.s * self.snum_f) / self.sden_f);
        (k, r, whole + fraction as i64, kin)
    }

    /// One control cycle at `master`; the output record is updated in place.
    #[inline(never)]
    pub fn tick(&mut self, master: i64) -> &TickOutput {
        let (k, r, zoomed, kin) = self.cam(master);
        let slave = zoomed + self.output_offset;
        // Pulse limiter: credit in µs × Hz carries the fraction of a pulse.
        let owed = slave - self.emitted;
        let budget = self.credit + self.hz_dt;
        let allowed = budget / PULSE;
        let count = owed.unsigned_abs().min(allowed);
        self.credit = if count == owed.unsigned_abs() {
            0
        } else {
            budget - count * PULSE
        };
        let pulses = if owed >= 0 {
            count as i64
        } else {
            -(count as i64)
        };
        self.emitted += pulses;
        let in_cycle = self.origin + r / self.mden;
        let mut sync = 0u8;
        for (i, w) in self.windows.iter().enumerate() {
            if w.contains(in_cycle) {
                sync |= 1 << i;
            }
        }
        let out = &mut self.out;
        out.state = AxisState::Running;
        out.master = master;
        out.master_in_cycle = in_cycle;
        out.master_in_cycle_raw = r / self.mnum;
        out.cycle = k - self.k_engage;
        out.slave = slave;
        out.slave_unzoomed = k * self.stroke + round(kin.s) as i64;
        out.output_offset = slave - round(kin.s * self.snum_f / self.sden_f) as i64;
        out.input_offset = self.input_offset_num / self.mden;
        out.velocity_ratio = kin.v * self.zoom_factor;
        out.pulses = pulses;
        if pulses != 0 {
            out.direction_forward = pulses > 0;
        }
        out.emitted = self.emitted;
        out.backlog = slave - self.emitted;
        out.pulse_delayed = out.backlog != 0;
        out.sync = sync;
        out.in_sync = sync != 0;
        out.initialised = true;
        out.following = true;
        out.busy = true;
        out
    }
}

/// Rounds half away from zero with one conversion (`f64::round` is a
/// library call on baseline x86-64); values beyond 2^52 are whole already.
#[inline(always)]
fn round(v: f64) -> f64 {
    if v.abs() < 4.5e15 {
        let whole = v as i64 as f64;
        let fraction = v - whole;
        let up = if fraction >= 0.5 { 1.0 } else { 0.0 };
        let down = if fraction <= -0.5 { 1.0 } else { 0.0 };
        whole + up - down
    } else {
        v
    }
}
