//! What `ecam table show` says about a table, as text or one JSON object;
//! the designer page's table endpoints answer the same facts.
//!
//! Every kind of table file is summarised as the curve it is: a point table
//! by its points (and the design columns a generator wrote beside them),
//! an evenly spaced table by its straight pieces, a segment profile by its
//! motion laws. Its steps (the impulses its plots draw) follow the one rule
//! of [`ecam_core::table::steps`].

use std::io::Write;

use ecam_core::drive_check::DriveReport;
use ecam_core::io::{AnyTable, TableFile};
use ecam_core::table::Summary;
use ecam_core::table::derivatives::{ripple_ratio, rounding_ripple};
use ecam_core::table::steps::{Corners, Step, Steps};
use ecam_core::{CamCurve, Kinematics};
use serde::Serialize;

use crate::machine::{AtSpeed, Machine, Peaks, Source, short};

/// Steps listed one by one in the text up to this many; more are counted.
const LISTED_STEPS: usize = 8;

/// The facts `ecam table show` prints.
#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    /// The file, as the user named it.
    pub file: String,
    /// The `kind` of the other table kinds (a point table's output
    /// predates it, and has none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<&'static str>,
    /// Points (values, key points) the file holds.
    pub points: usize,
    /// First master, counts.
    pub master_first: i64,
    /// Last master, counts.
    pub master_last: i64,
    /// First slave, pulses.
    pub slave_first: i64,
    /// Last slave, pulses.
    pub slave_last: i64,
    /// The synchronised zone a JSON table file holds.
    pub sync: Option<(i64, i64)>,
    /// Sections, spans, stroke, peaks, continuity, seam.
    #[serde(flatten)]
    pub summary: Summary,
    /// The design's peaks, from a file's derivative columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<Peaks>,
    /// The peaks at a master speed (`--master-speed`): the design's when
    /// known, else the table's (`of` says which). Set by [`TableReport::at`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_speed: Option<AtSpeed>,
    /// Where velocity steps (acceleration impulses) and acceleration steps
    /// (jerk impulses), the seam's at the last master.
    pub steps: Steps,
    /// A segment cam's points, continuity at every point and per-segment
    /// peaks (files of `ecam table gen segments`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segments: Option<serde_json::Value>,
    /// The drive check (`--drive`), set by [`TableReport::with_drive`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drive: Option<DriveReport>,
    /// The segment cam's lines for the text.
    #[serde(skip)]
    segments_text: Option<String>,
    /// The generator a file names.
    #[serde(skip)]
    generator: Option<String>,
    /// The kind in words, for the text.
    #[serde(skip)]
    what: Option<String>,
    /// Whose figures the table's peaks are.
    #[serde(skip)]
    source: Source,
    /// The shortest section, counts (for the rounding note).
    #[serde(skip)]
    shortest: Option<i64>,
    /// The machine the figures in physical units are for.
    #[serde(skip)]
    machine: Machine,
}

fn peaks(summary: &Summary) -> Peaks {
    Peaks {
        peak_velocity: summary.peak_velocity,
        peak_acceleration: summary.peak_acceleration,
    }
}

/// A segment cam's peaks, from its segments' closed forms.
fn cam_peaks(cam: &ecam_core::segments::SegmentCam) -> Peaks {
    let (v, a) = cam.peaks().iter().fold((0.0_f64, 0.0_f64), |(v, a), p| {
        (v.max(p.peak_velocity), a.max(p.peak_acceleration))
    });
    Peaks {
        peak_velocity: v,
        peak_acceleration: a,
    }
}

/// The design's peaks from a file's derivative columns.
fn column_peaks(known: &[Kinematics]) -> Peaks {
    let peak = |f: fn(&Kinematics) -> f64| known.iter().map(f).fold(0.0_f64, |m, v| m.max(v.abs()));
    Peaks {
        peak_velocity: peak(|k| k.v),
        peak_acceleration: peak(|k| k.a),
    }
}

impl TableReport {
    /// The report of `table`, read from the file called `file`.
    pub fn of(file: &str, table: &AnyTable) -> Self {
        match table {
            AnyTable::Points(f) => Self::of_points(file, f),
            AnyTable::Uniform(t) => {
                let values = t.values().len();
                // Document 002: N values make N − 1 pieces over CamCounts.
                let spacing = t.cam_counts() as f64 / values.saturating_sub(1).max(1) as f64;
                let what = format!(
                    "evenly spaced table, a value every {} counts",
                    short(spacing)
                );
                Self::of_curve(file, table.kind(), what, values, t, Source::UniformPieces)
            }
            AnyTable::Profile(p) => {
                let what = "segment profile, key points joined by motion laws, evaluated exactly";
                let keys = p.segments().len().saturating_add(1);
                Self::of_curve(
                    file,
                    table.kind(),
                    what.into(),
                    keys,
                    p,
                    Source::ProfileLaws,
                )
            }
        }
    }

    fn of_curve(
        file: &str,
        kind: &'static str,
        what: String,
        points: usize,
        curve: &(impl CamCurve + Corners),
        source: Source,
    ) -> Self {
        Self {
            file: file.to_string(),
            kind: Some(kind),
            points,
            master_first: curve.master_first(),
            master_last: curve.master_last(),
            slave_first: curve.slave_first(),
            slave_last: curve.slave_last(),
            sync: None,
            summary: Summary::of(curve),
            design: None,
            at_speed: None,
            steps: Steps::of(curve),
            segments: None,
            drive: None,
            segments_text: None,
            generator: None,
            what: Some(what),
            source,
            shortest: None,
            machine: Machine::default(),
        }
    }

    fn of_points(file: &str, f: &TableFile) -> Self {
        let points = f.table.points();
        let known = f.kinematics.as_deref().filter(|k| k.len() == points.len());
        let shortest = points
            .windows(2)
            .filter_map(|w| match w {
                [a, b] => b.master.checked_sub(a.master),
                _ => None,
            })
            .min();
        Self {
            file: file.to_string(),
            kind: None,
            points: points.len(),
            master_first: f.table.master_first(),
            master_last: f.table.master_last(),
            slave_first: f.table.slave_first(),
            slave_last: f.table.slave_last(),
            sync: f.sync,
            summary: Summary::of(&f.table),
            // A segment cam's own peaks are exact (closed forms), not those
            // at the points.
            design: match &f.segments {
                Some(cam) => Some(cam_peaks(cam)),
                None => known.map(column_peaks),
            },
            at_speed: None,
            // A segment cam's corners; else the design the columns
            // describe, where the file has them; else the straight sections
            // the table is run as.
            steps: match (&f.segments, known) {
                (Some(cam), _) => Steps::of(&**cam),
                (None, Some(known)) => Steps::of_columns(points, known),
                (None, None) => Steps::of(&f.table),
            },
            segments: f.segments.as_deref().map(crate::segments_json),
            drive: None,
            segments_text: f.segments.as_deref().map(crate::segments_text),
            generator: f.generator.clone(),
            what: None,
            source: Source::SampledTable,
            shortest,
            machine: Machine::default(),
        }
    }

    /// This report with figures at `machine`'s speed (the design's when
    /// known, else the table's).
    pub fn at(mut self, machine: Machine) -> Self {
        self.machine = machine;
        self.at_speed = match &self.design {
            Some(design) => machine.at_speed(design, self.design_source()),
            None => machine.at_speed(&peaks(&self.summary), self.source),
        };
        self
    }

    /// This report with a drive check (`ecam table show --drive`).
    pub fn with_drive(mut self, drive: Option<DriveReport>) -> Self {
        self.drive = drive;
        self
    }

    /// Whose the design peaks are: a segment cam's laws, or a file's columns.
    fn design_source(&self) -> Source {
        if self.segments.is_some() {
            Source::ProfileLaws
        } else {
            Source::DesignColumns
        }
    }

    /// The rounding note, when the table's acceleration is mostly ripple.
    pub fn note(&self) -> Option<String> {
        ripple_note(
            self.summary.peak_acceleration,
            self.design?.peak_acceleration,
            self.shortest?,
        )
    }

    /// The report as `ecam table show` prints it.
    ///
    /// # Errors
    /// A failed write.
    pub fn write_text(&self, out: &mut impl Write) -> std::io::Result<()> {
        writeln!(out, "file:              {}", self.file)?;
        if let Some(generator) = &self.generator {
            writeln!(out, "generator:         {generator}")?;
        }
        if let (Some(kind), Some(what)) = (self.kind, &self.what) {
            writeln!(out, "kind:              {kind} ({what})")?;
        }
        let s = &self.summary;
        writeln!(out, "points:            {}", self.points)?;
        writeln!(out, "sections:          {}", s.sections)?;
        writeln!(
            out,
            "master:            {} .. {} (span {})",
            self.master_first, self.master_last, s.master_span
        )?;
        writeln!(
            out,
            "slave:             {} .. {} (stroke {}, range {} .. {})",
            self.slave_first, self.slave_last, s.stroke, s.slave_min, s.slave_max
        )?;
        let table = peaks(s);
        let rows: Vec<(&Peaks, Source)> = self
            .design
            .iter()
            .map(|d| (d, self.design_source()))
            .chain([(&table, self.source)])
            .collect();
        for (k, (p, source)) in rows.iter().enumerate() {
            let label = if k == 0 { "peak velocity:" } else { "" };
            let v = short(p.peak_velocity);
            writeln!(out, "{label:<19}{v} pulses/count ({})", source.velocity())?;
        }
        for (k, (p, source)) in rows.iter().enumerate() {
            let label = if k == 0 { "peak acceleration:" } else { "" };
            let a = short(p.peak_acceleration);
            writeln!(
                out,
                "{label:<19}{a} pulses/count² ({})",
                source.acceleration()
            )?;
        }
        if let Some(note) = self.note() {
            writeln!(out, "note:              {note}")?;
        }
        for (p, source) in &rows {
            let Some(at) = self.machine.at_speed(p, *source) else {
                break;
            };
            let unit = at.unit.map(|u| u.symbol()).unwrap_or_default();
            let speed = at.slave_speed.map(|v| format!(" = {} {unit}/s", short(v)));
            let accel = at
                .slave_acceleration
                .map(|a| format!(" = {} {unit}/s²", short(a)));
            writeln!(
                out,
                "slave speed:       {} Hz{} ({} at master {} counts/s)",
                short(at.slave_hz),
                speed.unwrap_or_default(),
                at.of,
                short(at.master_hz)
            )?;
            writeln!(
                out,
                "slave accel.:      {} Hz/s{} ({})",
                short(at.slave_hz_per_s),
                accel.unwrap_or_default(),
                at.of
            )?;
        }
        // A file's design columns describe a smoother curve than the
        // straight sections its points are run as: both are given.
        let design = match self.design {
            Some(_) => {
                let (inside, seam) = self.steps.continuity();
                format!("; the design's: {inside} (seam {seam})")
            }
            None => String::new(),
        };
        writeln!(
            out,
            "continuity:        {} (seam {}){design}",
            s.continuity, s.seam
        )?;
        let of = if self.design.is_some() {
            " (the design's)"
        } else {
            ""
        };
        writeln!(
            out,
            "velocity steps:    {}{of}",
            steps_text(&self.steps.velocity)
        )?;
        writeln!(
            out,
            "accel. steps:      {}{of}",
            steps_text(&self.steps.acceleration)
        )?;
        if let Some((lo, hi)) = self.sync {
            writeln!(out, "sync zone:         master {lo} .. {hi}")?;
        }
        if let Some(text) = &self.segments_text {
            write!(out, "{text}")?;
        }
        if let Some(drive) = &self.drive {
            writeln!(out, "{drive}")?;
        }
        Ok(())
    }
}

/// The note `ecam table show` prints (and the designer's summary carries)
/// when a table's peak acceleration is mostly whole-pulse rounding ripple
/// against its design's ([`ripple_ratio`]); `shortest` is its shortest
/// section in counts.
pub fn ripple_note(table_peak: f64, design_peak: f64, shortest: i64) -> Option<String> {
    let ratio = ripple_ratio(table_peak, design_peak)?;
    let length = shortest.max(1) as f64;
    Some(format!(
        "the table's acceleration is {ratio:.1} times the design's: its points are \
         rounded to whole pulses, which moves a joint's estimate by up to 2/L² (L: section \
         length; {} for the shortest, {} counts). The drive follows the table, the motion \
         law asks for the design's value.",
        short(rounding_ripple(length)),
        short(length),
    ))
}

/// `none`, each step as `MASTER: SIZE` (the seam's as `seam MASTER`), or,
/// for many, how many and the largest.
fn steps_text(steps: &[Step]) -> String {
    let one = |s: &Step| {
        let at = short(s.master);
        let size = short(s.size);
        if s.seam {
            format!("seam {at}: {size}")
        } else {
            format!("{at}: {size}")
        }
    };
    match steps {
        [] => "none".into(),
        few if few.len() <= LISTED_STEPS => few.iter().map(one).collect::<Vec<_>>().join(", "),
        many => {
            let largest = many
                .iter()
                .max_by(|a, b| a.size.abs().total_cmp(&b.size.abs()))
                .map(one)
                .unwrap_or_default();
            format!("{} (largest at {largest}; --json lists them)", many.len())
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::Unit;
    use ecam_core::PointTable;

    fn text(report: &TableReport) -> String {
        let mut out = Vec::new();
        report.write_text(&mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_ripple_is_labelled_as_the_tables_and_explained() {
        let g = crate::from_json(
            "rotary-cut",
            serde_json::json!({"master": 3183, "sync": 333, "max_ratio": "50/3"}),
        )
        .unwrap();
        let file = TableFile {
            table: g.table,
            sync: g.sync,
            generator: Some("rotary-cut".into()),
            kinematics: g.kinematics,
            segments: None,
        };
        let t = text(&TableReport::of("r.csv", &AnyTable::Points(file)));
        assert!(t.contains("pulses/count² (design"), "{t}");
        assert!(t.contains("pulses/count² (table as sampled"), "{t}");
        assert!(
            t.contains("note:") && t.contains("2/L²") && t.contains("8 counts"),
            "{t}"
        );
        assert!(!t.contains("slave speed"), "{t}");
        // The design's four acceleration steps, the seam's last.
        assert!(t.contains("velocity steps:    none"), "{t}");
        let steps = t.lines().find(|l| l.starts_with("accel. steps:")).unwrap();
        assert_eq!(steps.matches(": ").count(), 5, "{steps}");
        assert!(steps.contains("seam 3183: -0.004177"), "{steps}");
    }

    #[test]
    fn machine_units_follow_the_chain_rule() {
        let t = PointTable::from_pairs(&[(0, 0), (100, 200), (300, 200)]).unwrap();
        let file = AnyTable::Points(TableFile {
            table: t,
            sync: None,
            generator: None,
            kinematics: None,
            segments: None,
        });
        let machine = Machine {
            master_speed: Some(1000.0),
            unit: Some((Unit::Mm, 0.01)),
        };
        let report = TableReport::of("t.csv", &file).at(machine);
        let t = text(&report);
        assert!(t.contains("slave speed:       2000 Hz = 20 mm/s"), "{t}");
        assert_eq!(report.at_speed.unwrap().slave_hz, 2000.0);
        // Straight sections: the velocity steps at 100 and at the seam.
        assert!(t.contains("velocity steps:    100: -2, seam 300: 2"), "{t}");
    }

    #[test]
    fn many_steps_are_counted_not_listed() {
        let pairs: Vec<(i64, i64)> = (0..20).map(|i| (i * 10, i * i)).collect();
        let file = AnyTable::Points(TableFile {
            table: PointTable::from_pairs(&pairs).unwrap(),
            sync: None,
            generator: None,
            kinematics: None,
            segments: None,
        });
        let t = text(&TableReport::of("t.csv", &file));
        let line = t
            .lines()
            .find(|l| l.starts_with("velocity steps:"))
            .unwrap();
        assert!(line.contains("19 (largest at seam 190: -3.6"), "{line}");
    }
}
