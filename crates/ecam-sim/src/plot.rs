//! The picture of a run (`ecam simulate --plot`): master, slave,
//! velocity and backlog over time, the times a sync window was on shaded.
//!
//! A run may last millions of ticks; the plot keeps about [`PLOT_POINTS`]
//! evenly spaced rows (a year-long run must not hold every tick in
//! memory), each backlog spike between them, every sync span, and every
//! seam jump. A jump (a periodic cam's slave returning by its stroke at the
//! seam) moves the commanded slave within one tick: as a velocity it would
//! be a spike that swamps the motion, so the velocity panel leaves the
//! jump out (the tick's change less the motion of the ticks before) and
//! draws it as an impulse instead, labelled with its size in pulses (the
//! impulse's area).

use ecam_engine::TickOutput;
use ecam_plot::{Chart, ChartPanel, Style, Trace};

use crate::Row;

/// Most rows a trace plot draws (about two per pixel); longer runs are
/// thinned evenly.
pub const PLOT_POINTS: usize = 2_000;

/// Pulses a velocity window spans, where the run allows, so that whole-pulse
/// rounding moves the drawn speed by 2 % at most.
const QUIET_PULSES: i64 = 50;

/// What the trace plot keeps of a run, fed one tick at a time.
#[derive(Debug)]
pub struct TracePlot {
    step: u64,
    seen: u64,
    kept: Vec<Row>,
    last: Option<Row>,
    sync_from: Option<f64>,
    shaded: Vec<(f64, f64)>,
    /// Seam jumps: (time, slave change in that tick).
    jumps: Vec<(f64, f64)>,
    /// Slave moved by jumps so far (left out of the velocity).
    jumped: i64,
    previous_slave: Option<i64>,
    /// The slave's change per tick lately, ticks with a jump left out.
    motion: f64,
}

impl TracePlot {
    /// A plot of a run of `ticks` ticks.
    pub fn new(ticks: u64) -> Self {
        Self {
            step: ticks.div_ceil(PLOT_POINTS as u64).max(1),
            seen: 0,
            kept: Vec::new(),
            last: None,
            sync_from: None,
            shaded: Vec::new(),
            jumps: Vec::new(),
            jumped: 0,
            previous_slave: None,
            motion: 0.0,
        }
    }

    /// Takes one tick's row and engine output.
    pub fn add(&mut self, row: &Row, out: &TickOutput) {
        let change = self
            .previous_slave
            .map_or(0, |p| row.slave.saturating_sub(p));
        self.previous_slave = Some(row.slave);
        // The jump is the tick's change less the motion of the ticks
        // before (the cam keeps moving while it jumps).
        let jump = change.saturating_sub(self.motion.round() as i64);
        // A seam the slave passes without going back (an endless modulo
        // knife's) is flagged by the engine but moves nothing: no impulse.
        // A pulse more than the tick's own motion is rounding, not a jump.
        let jumps = out.events.seam_jump && jump.unsigned_abs() as f64 > 1.0 + self.motion.abs();
        if jumps {
            self.jumps.push((row.t, jump as f64));
            self.jumped = self.jumped.saturating_add(jump);
        } else {
            // Averaged: a few ticks' whole pulses give the speed better
            // than the last one's.
            self.motion += 0.25 * (change as f64 - self.motion);
        }
        // The velocity is drawn from the slave without its jumps.
        let smooth = Row {
            slave: row.slave.saturating_sub(self.jumped),
            ..*row
        };
        if self.seen.is_multiple_of(self.step) {
            self.kept.push(smooth);
        } else if let Some(k) = self.kept.last_mut() {
            // A backlog spike between kept rows must still show.
            if row.backlog.unsigned_abs() > k.backlog.unsigned_abs() {
                k.backlog = row.backlog;
            }
        }
        self.seen += 1;
        match (row.in_sync, self.sync_from) {
            (true, None) => self.sync_from = Some(row.t),
            (false, Some(from)) => {
                self.shaded.push((from, row.t));
                self.sync_from = None;
            }
            _ => {}
        }
        self.last = Some(smooth);
    }

    /// The plot, titled after the scenario file `name`.
    pub fn chart(mut self, name: &str) -> Chart {
        if let Some(last) = self.last {
            if self.kept.last().is_none_or(|k| k.t < last.t) {
                self.kept.push(last);
            }
            if let Some(from) = self.sync_from {
                self.shaded.push((from, last.t));
            }
        }
        // Velocity over a window of kept rows around each: per-tick (and
        // per-interval) values jump between whole pulses, which draws a
        // band instead of the motion. Each window widens until the slave
        // moved [`QUIET_PULSES`] (so a pulse more or less is a small part)
        // or spans 1 % of the run: fast motion keeps a short window and
        // its plateaus, slow motion is near zero either way.
        let widest = (self.kept.len() / 100).max(1);
        let last = self.kept.len().saturating_sub(1);
        let window = |i: usize, reach: usize| {
            // As wide at the ends as inside: shifted, not cut.
            let lo = i.saturating_sub(reach).min(last.saturating_sub(2 * reach));
            (self.kept.get(lo), self.kept.get((lo + 2 * reach).min(last)))
        };
        let velocity: Vec<f64> = (0..self.kept.len())
            .map(|i| {
                let mut reach = 1;
                while reach < widest {
                    match window(i, reach) {
                        (Some(a), Some(b)) if (b.slave - a.slave).abs() >= QUIET_PULSES => break,
                        _ => reach += 1,
                    }
                }
                match window(i, reach) {
                    (Some(a), Some(b)) if b.t > a.t => (b.slave - a.slave) as f64 / (b.t - a.t),
                    _ => 0.0,
                }
            })
            .collect();
        // Put the jumps back into the commanded slave drawn.
        let mut jumped = 0i64;
        let mut jumps = self.jumps.iter().peekable();
        let commanded: Vec<f64> = self
            .kept
            .iter()
            .map(|r| {
                while let Some(&&(t, size)) = jumps.peek().filter(|(t, _)| *t <= r.t) {
                    let _ = t;
                    jumped = jumped.saturating_add(size as i64);
                    jumps.next();
                }
                r.slave.saturating_add(jumped) as f64
            })
            .collect();
        let t: Vec<f64> = self.kept.iter().map(|r| r.t).collect();
        let column = |f: fn(&Row) -> f64| self.kept.iter().map(f).collect::<Vec<f64>>();
        let width = if t.len() > 1000 { 1 } else { 2 };
        let line = |name: &str, y: Vec<f64>| Trace::new(name, t.clone(), y, Style::Line { width });
        let mut speed = vec![line("commanded", velocity)];
        if !self.jumps.is_empty() {
            let mut trace = Trace::new(
                "seam jump (pulses)",
                self.jumps.iter().map(|j| j.0).collect(),
                self.jumps.iter().map(|j| j.1).collect(),
                Style::Impulses,
            );
            trace.tags = vec!["jump".into(); self.jumps.len()];
            speed.push(trace);
        }
        let panel = |title: &str, traces| ChartPanel {
            title: title.into(),
            traces,
        };
        Chart {
            title: format!("ecam simulate {name}"),
            x_label: "time (s)".into(),
            panels: vec![
                panel(
                    "master (counts)",
                    vec![line("master", column(|r| r.master as f64))],
                ),
                panel(
                    "slave (pulses)",
                    vec![
                        line("commanded", commanded),
                        line("emitted", column(|r| r.emitted as f64)),
                    ],
                ),
                panel("velocity (pulses/s)", speed),
                panel(
                    "backlog (pulses)",
                    vec![line("backlog", column(|r| r.backlog as f64))],
                ),
            ],
            shaded: self.shaded,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn row(t: f64, slave: i64, in_sync: bool) -> Row {
        Row {
            t,
            master: 0,
            slave,
            velocity: 0.0,
            pulses: 0,
            emitted: slave,
            backlog: 0,
            in_sync,
        }
    }

    fn out(jump: bool) -> TickOutput {
        let mut out = TickOutput::default();
        out.events.seam_jump = jump;
        out
    }

    #[test]
    fn long_runs_are_thinned_but_keep_sync_spans() {
        let ticks = 10 * PLOT_POINTS as u64;
        let mut p = TracePlot::new(ticks);
        for k in 0..=ticks {
            let on = (1000..=1004).contains(&k) || k >= ticks - 2;
            p.add(&row(k as f64, 0, on), &out(false));
        }
        let chart = p.chart("x.toml");
        let t = &chart.panels[0].traces[0].x;
        assert!(t.len() <= PLOT_POINTS + 2);
        assert_eq!(t.last(), Some(&(ticks as f64)));
        assert_eq!(
            chart.shaded,
            vec![(1000.0, 1005.0), ((ticks - 2) as f64, ticks as f64)]
        );
    }

    #[test]
    fn whole_pulse_steps_read_as_the_speed_not_a_band() {
        // 0.45 pulses a tick: each tick moves 0 or 1 pulse, each kept
        // interval (5 ticks) 2 or 3; the drawn speed stays within 2 %.
        let ticks = 5 * PLOT_POINTS as u64;
        let mut p = TracePlot::new(ticks);
        for k in 0..=ticks {
            let slave = (0.45 * k as f64).floor() as i64;
            p.add(&row(k as f64, slave, false), &out(false));
        }
        let chart = p.chart("x.toml");
        let speed = &chart.panels[2].traces[0].y;
        assert!(
            speed.iter().all(|v| (v - 0.45).abs() < 0.02 * 0.45),
            "{speed:?}"
        );
    }

    #[test]
    fn a_short_fast_stretch_keeps_its_speed() {
        // A long run at rest but for 50 ticks at 2 pulses a tick (a
        // rotary knife's sync zone): its plateau is drawn at its speed.
        let ticks = 5 * PLOT_POINTS as u64;
        let mut p = TracePlot::new(ticks);
        let mut slave = 0;
        for k in 0..=ticks {
            if (5000..5050).contains(&k) {
                slave += 2;
            }
            p.add(&row(k as f64, slave, false), &out(false));
        }
        let chart = p.chart("x.toml");
        let peak = chart.panels[2].traces[0]
            .y
            .iter()
            .fold(0.0_f64, |m, v| m.max(*v));
        assert!((peak - 2.0).abs() < 1e-9, "{peak}");
    }

    #[test]
    fn a_seam_passed_without_going_back_draws_no_impulse() {
        // An endless modulo knife: the engine flags the seam, the slave
        // keeps going forward at 3 pulses a tick.
        let mut p = TracePlot::new(100);
        for k in 0..=100i64 {
            p.add(&row(k as f64, 3 * k, false), &out(k % 25 == 0 && k > 0));
        }
        let chart = p.chart("x.toml");
        let speed = &chart.panels[2].traces;
        assert_eq!(speed.len(), 1, "{speed:?}");
        assert!(speed[0].y.iter().skip(1).all(|v| (v - 3.0).abs() < 1e-12));
    }

    #[test]
    fn a_seam_jump_is_an_impulse_not_a_velocity_spike() {
        // 1 pulse per tick, and at tick 50 the slave jumps back by 1000.
        let mut p = TracePlot::new(100);
        for k in 0..=100i64 {
            let slave = k - if k >= 50 { 1000 } else { 0 };
            p.add(&row(k as f64, slave, false), &out(k == 50));
        }
        let chart = p.chart("x.toml");
        let speed = &chart.panels[2].traces;
        assert!(
            speed[0].y.iter().skip(1).all(|v| (v - 1.0).abs() < 1e-12),
            "{:?}",
            speed[0].y
        );
        assert_eq!(speed[1].style, Style::Impulses);
        assert_eq!(
            (speed[1].x.clone(), speed[1].y.clone()),
            (vec![50.0], vec![-1000.0])
        );
        // The slave drawn still jumps.
        let slave = &chart.panels[1].traces[0].y;
        assert_eq!((slave[49], slave[50]), (49.0, -950.0));
    }
}
