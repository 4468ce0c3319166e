//! What `ecam table show` and the designer print of a segment cam: its
//! points as solved, the continuity at each point and each segment's peaks
//! (one home for both faces, so the report and the designer agree).

use serde_json::{Value, json};

/// What the designer shows of a segment cam: its points (as solved), the
/// continuity at every point and each segment's peaks.
pub fn segments_json(cam: &ecam_core::segments::SegmentCam) -> Value {
    json!({
        "start": cam.start(),
        "segment": cam.segments(),
        "continuity": cam.continuity(),
        "peaks": cam.peaks(),
    })
}

/// The lines `ecam table show` prints for a segment cam: the continuity at
/// every point and each segment's law, `Cv`/`Ca`/`Cj` and peaks.
pub fn segments_text(cam: &ecam_core::segments::SegmentCam) -> String {
    let report = cam.continuity();
    let short = |x: Option<f64>| match x {
        None => "–".to_string(),
        Some(v) if v.is_infinite() => "∞".to_string(),
        Some(v) => format!("{v:.4}"),
    };
    let mut out = format!(
        "segment cam:       continuity {} (seam {})\n",
        report.cam, report.seam
    );
    let points: Vec<String> = report
        .joints
        .iter()
        .map(|j| {
            format!(
                "{} at {}: {}",
                if j.seam { "seam" } else { "point" },
                j.master,
                j.class
            )
        })
        .collect();
    out.push_str(&format!("  points:          {}\n", points.join(", ")));
    for p in cam.peaks() {
        out.push_str(&format!(
            "  segment {:<2}      {:<26} master {} .. {}, rise {}: Cv {} Ca {} Cj {}; peaks {} pulses/count, {} pulses/count², {} pulses/count³\n",
            p.segment,
            p.law.name(),
            p.master.0,
            p.master.1,
            p.rise,
            short(p.cv),
            short(p.ca),
            short(p.cj),
            sig(p.peak_velocity),
            sig(p.peak_acceleration),
            sig(p.peak_jerk),
        ));
    }
    out
}

/// Six significant digits, plainly where that reads well.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_infinite() {
            "∞".into()
        } else {
            "0".into()
        };
    }
    if (1e-3..1e6).contains(&x.abs()) {
        let decimals = (5 - x.abs().log10().floor() as i32).max(0) as usize;
        let text = format!("{x:.decimals$}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{x:.5e}")
    }
}
