//! Velocity, acceleration and jerk of a point table, where no exact curve
//! is known (tables read from files without derivative columns).
//!
//! Between its points a table is run as straight lines (both devices
//! interpolate linearly), so the velocity ratio the slave is *commanded*
//! after point `i` is the slope of the section that starts there: the
//! velocity is a forward difference, the value at point `i` holding until
//! point `i + 1` (the last point repeats the last section's value). This
//! keeps a dwell at exactly zero velocity, where a centred estimate would
//! smear the neighbouring ramps into it.
//!
//! The acceleration of straight sections is all at the joints, so it is
//! *estimated* for the motion the points sample: at joint `i`, the change of
//! section velocity over the mean length of the two sections meeting there,
//! `(v_i − v_{i−1}) / ((x_{i+1} − x_{i−1})/2)` (the central second
//! difference; a forward difference of the velocity would put the change
//! half a section late and alternate in sign with the rounding). The jerk is
//! the central difference of that estimate. Both are 0 at the first and last
//! point, where one side of the joint is unknown.
//!
//! That per-joint estimate is what the table commands, whole-pulse rounding
//! included: on short sections the rounding (up to ½ pulse per point) makes
//! it alternate around the motion law. [`over_sections`] estimates the law
//! itself: the same difference of slopes, but of chords spanning `k`
//! sections on each side, which divides the rounding ripple by about `k²`
//! and is still exact for a table sampled from a parabola.
//!
//! [`joint_acceleration`] is the one home of the per-joint estimate:
//! [`at_joints`] applies it at every point, and
//! [`Summary::peak_acceleration`](super::Summary::peak_acceleration) takes
//! its largest magnitude over a curve of straight sections.
//!
//! ```
//! use ecam_core::CamPoint;
//! use ecam_core::table::derivatives;
//!
//! // Slope 1 over 10 counts, then 3 over 30: the velocity changes by 2
//! // over a mean section of 20 counts.
//! let k = derivatives::of_points(&[
//!     CamPoint::new(0, 0),
//!     CamPoint::new(10, 10),
//!     CamPoint::new(40, 100),
//! ]);
//! assert_eq!(k[0].v, 1.0);
//! assert_eq!(k[1].v, 3.0);
//! assert_eq!(k[1].a, 0.1);
//! ```

use alloc::vec;
use alloc::vec::Vec;

use crate::{CamPoint, Kinematics};

/// Displacement, section velocity, and the estimated acceleration and jerk
/// at each point (see the module documentation).
pub fn of_points(points: &[CamPoint]) -> Vec<Kinematics> {
    let x: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
    let s: Vec<f64> = points.iter().map(|p| p.slave as f64).collect();
    let v = forward(&x, &s);
    let a = at_joints(&x, &v);
    let j = centred(&x, &a);
    s.iter()
        .zip(v.iter().zip(a.iter().zip(j.iter())))
        .map(|(&s, (&v, (&a, &j)))| Kinematics { s, v, a, j })
        .collect()
}

/// Slope of the section starting at each x (the last x repeats the last
/// slope); `x` strictly increasing.
pub fn forward(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len().min(y.len());
    let mut out: Vec<f64> = x
        .windows(2)
        .zip(y.windows(2))
        .take(n.saturating_sub(1))
        .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
        .collect();
    match out.last() {
        Some(&last) => out.push(last),
        None => out.resize(n, 0.0),
    }
    out
}

/// The acceleration estimated at a joint between two straight sections:
/// the velocity step `dv` there over the mean length of the two sections,
/// which run from `x_before` to the joint and on to `x_after`:
/// `dv / ((x_after − x_before)/2)` (the central second difference). 0 when
/// the sections have no length.
///
/// ```
/// use ecam_core::table::derivatives::joint_acceleration;
///
/// // Slope 1 from 0 to 10, slope 3 from 10 to 40.
/// assert_eq!(joint_acceleration(3.0 - 1.0, 0.0, 40.0), 0.1);
/// assert_eq!(joint_acceleration(2.0, 5.0, 5.0), 0.0);
/// ```
pub fn joint_acceleration(dv: f64, x_before: f64, x_after: f64) -> f64 {
    let mean_len = 0.5 * (x_after - x_before);
    if mean_len > 0.0 { dv / mean_len } else { 0.0 }
}

/// The most whole-pulse rounding moves a joint's acceleration estimate on
/// sections of `section` counts: each point lies within ½ pulse of the
/// curve it samples, so a section's slope moves by up to `1/L` and the
/// joint estimate by up to `2/L²`. On short sections this ripple can dwarf
/// a design's acceleration: both figures are true, of different things.
///
/// ```
/// use ecam_core::table::derivatives::rounding_ripple;
///
/// assert_eq!(rounding_ripple(8.0), 0.03125);
/// ```
pub fn rounding_ripple(section: f64) -> f64 {
    let l = section.max(1.0);
    2.0 / (l * l)
}

/// A table's peak acceleration above this multiple of its design's is
/// mostly rounding ripple, and summaries say so.
pub const RIPPLE_NOTE_RATIO: f64 = 1.5;

/// How many times the design's peak acceleration the table's is, when that
/// is more than [`RIPPLE_NOTE_RATIO`] (a summary then notes the ripple);
/// `None` otherwise, or without a design acceleration.
pub fn ripple_ratio(table_peak: f64, design_peak: f64) -> Option<f64> {
    let ratio = table_peak / design_peak;
    (design_peak > 0.0 && ratio > RIPPLE_NOTE_RATIO).then_some(ratio)
}

/// [`joint_acceleration`] at each interior point; 0 at both ends. `v[i]`
/// is the slope of the section starting at `x[i]`.
pub fn at_joints(x: &[f64], v: &[f64]) -> Vec<f64> {
    let n = x.len().min(v.len());
    let mut out = vec![0.0; n];
    let inner = out.iter_mut().skip(1).take(n.saturating_sub(2));
    for ((slot, xw), vw) in inner.zip(x.windows(3)).zip(v.windows(2)) {
        if let (&[x0, _, x2], &[v0, v1]) = (xw, vw) {
            *slot = joint_acceleration(v1 - v0, x0, x2);
        }
    }
    out
}

/// Acceleration and jerk at each interior point (`1..n−1`) from chords
/// over up to `k` sections on each side (fewer near the ends): the
/// acceleration is the change of chord slope over the distance between the
/// chords' middles, `(slope_right − slope_left) / ((x_{i+k} − x_{i−k})/2)`;
/// the jerk the change of that acceleration over the same window.
/// Returns `(x, acceleration, jerk)` of the interior points.
pub fn over_sections(points: &[CamPoint], k: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
    let s: Vec<f64> = points.iter().map(|p| p.slave as f64).collect();
    let n = x.len();
    let k = k.max(1);
    let window = |i: usize| (i - k.min(i), i + k.min(n - 1 - i));
    let slope = |a: usize, b: usize| match (x.get(a), x.get(b), s.get(a), s.get(b)) {
        (Some(xa), Some(xb), Some(sa), Some(sb)) if xb > xa => (sb - sa) / (xb - xa),
        _ => 0.0,
    };
    let inner: Vec<usize> = (1..n.saturating_sub(1)).collect();
    let acceleration: Vec<f64> = inner
        .iter()
        .map(|&i| {
            let (lo, hi) = window(i);
            let half = 0.5 * (x.get(hi).unwrap_or(&0.0) - x.get(lo).unwrap_or(&0.0));
            if half > 0.0 {
                cancelled(slope(lo, i), slope(i, hi)) / half
            } else {
                0.0
            }
        })
        .collect();
    // `acceleration[m]` belongs to point `m + 1`.
    let jerk = inner
        .iter()
        .enumerate()
        .map(|(m, _)| {
            let (lo, hi) = (
                m - k.min(m),
                (m + k).min(acceleration.len().saturating_sub(1)),
            );
            match (
                acceleration.get(lo),
                acceleration.get(hi),
                x.get(lo + 1),
                x.get(hi + 1),
            ) {
                (Some(a0), Some(a1), Some(x0), Some(x1)) if x1 > x0 => {
                    (cancelled(*a0, *a1)) / (x1 - x0)
                }
                _ => 0.0,
            }
        })
        .collect();
    let xs = inner.iter().filter_map(|&i| x.get(i).copied()).collect();
    (xs, acceleration, jerk)
}

/// `after − before`, exactly 0 where the two agree to floating-point
/// rounding (equal chords computed over different spans differ in the last
/// bits; that difference divided by a span is noise, not a derivative).
fn cancelled(before: f64, after: f64) -> f64 {
    let change = after - before;
    if change.abs() <= 1e-12 * before.abs().max(after.abs()) {
        0.0
    } else {
        change
    }
}

/// Central difference of `y` at each interior point; 0 at both ends.
pub fn centred(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len().min(y.len());
    let mut out = vec![0.0; n];
    let inner = out.iter_mut().skip(1).take(n.saturating_sub(2));
    for ((slot, xw), yw) in inner.zip(x.windows(3)).zip(y.windows(3)) {
        if let (&[x0, _, x2], &[y0, _, y2]) = (xw, yw) {
            if x2 > x0 {
                *slot = (y2 - y0) / (x2 - x0);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    #[test]
    fn slopes_of_sections_on_uneven_spacing() {
        let x = [0.0, 1.0, 3.0, 4.0];
        let y = [0.0, 2.0, 2.0, 5.0];
        assert_eq!(forward(&x, &y), vec![2.0, 0.0, 3.0, 3.0]);
    }

    #[test]
    fn a_dwell_stays_at_rest() {
        let pts = [
            CamPoint::new(0, 0),
            CamPoint::new(10, 100),
            CamPoint::new(1000, 100),
            CamPoint::new(1010, 0),
        ];
        let k = of_points(&pts);
        assert_eq!(k[1].v, 0.0);
        assert_eq!(k[0].v, 10.0);
        assert_eq!(k[2].v, -10.0);
    }

    #[test]
    fn straight_line_has_constant_velocity_and_no_acceleration() {
        let pts: Vec<CamPoint> = (0..5).map(|i| CamPoint::new(i * 10, i * 30)).collect();
        for k in of_points(&pts) {
            assert_eq!(k.v, 3.0);
            assert_eq!(k.a, 0.0);
            assert_eq!(k.j, 0.0);
        }
    }

    #[test]
    fn acceleration_is_the_velocity_change_over_the_mean_section() {
        // Slope 1 over 10 counts, then 3 over 30: Δv = 2 over 20.
        let pts = [
            CamPoint::new(0, 0),
            CamPoint::new(10, 10),
            CamPoint::new(40, 100),
        ];
        let k = of_points(&pts);
        assert_eq!(
            k.iter().map(|k| k.a).collect::<Vec<_>>(),
            vec![0.0, 0.1, 0.0]
        );
    }

    #[test]
    fn a_sampled_parabola_has_its_constant_acceleration() {
        // s = x²/100 every 10 counts: whole pulses, second derivative 0.02.
        let pts: Vec<CamPoint> = (0..20).map(|i| CamPoint::new(i * 10, i * i)).collect();
        let k = of_points(&pts);
        for k in &k[1..19] {
            assert!((k.a - 0.02).abs() < 1e-12, "{}", k.a);
        }
        for k in &k[2..18] {
            assert!(k.j.abs() < 1e-12);
        }
    }

    #[test]
    fn chords_over_sections_are_exact_on_a_parabola_and_calm_the_rounding() {
        let pts: Vec<CamPoint> = (0..20).map(|i| CamPoint::new(i * 10, i * i)).collect();
        let (x, a, j) = over_sections(&pts, 4);
        assert_eq!(x.len(), 18);
        assert_eq!(x[0], 10.0);
        for (a, j) in a.iter().zip(&j) {
            assert!((a - 0.02).abs() < 1e-12 && j.abs() < 1e-12, "{a} {j}");
        }
        // s = 0.0013·x² rounded to whole pulses every 7 counts: per joint
        // the rounding swamps the 0.0026 acceleration; over ±4 sections it
        // does not.
        let pts: Vec<CamPoint> = (0..60)
            .map(|i| {
                let x = f64::from(i) * 7.0;
                CamPoint::new(i64::from(i) * 7, (0.0013 * x * x).round() as i64)
            })
            .collect();
        let rough = of_points(&pts);
        let worst_rough = rough[1..59]
            .iter()
            .map(|k| (k.a - 0.0026).abs())
            .fold(0.0, f64::max);
        let (_, a, _) = over_sections(&pts, 4);
        let worst_smooth = a[3..55]
            .iter()
            .map(|a| (a - 0.0026).abs())
            .fold(0.0, f64::max);
        assert!(worst_rough > 0.01, "{worst_rough}");
        // Chords of 28 counts: at most 2·(1/28)/28 off.
        assert!(
            worst_smooth < 0.0026 && worst_smooth < worst_rough / 10.0,
            "{worst_smooth}"
        );
    }

    #[test]
    fn too_short_inputs_give_zeros() {
        let (x, a, j) = over_sections(&[CamPoint::new(0, 0), CamPoint::new(1, 1)], 4);
        assert!(x.is_empty() && a.is_empty() && j.is_empty());
        assert!(
            at_joints(&[0.0, 1.0], &[1.0, 1.0])
                .iter()
                .all(|a| *a == 0.0)
        );
        assert!(centred(&[], &[]).is_empty());
        assert_eq!(forward(&[1.0], &[2.0]), vec![0.0]);
        assert!(forward(&[], &[]).is_empty());
    }
}
