//! Velocity, acceleration and jerk of a point table, where no exact curve
//! is known (tables read from files, or generators that give only points).
//!
//! Between its points a table is run as straight lines (both devices
//! interpolate linearly), so the velocity ratio the slave is *commanded*
//! after point `i` is the slope of the section that starts there. Each
//! derivative is therefore taken as a forward difference: the value at point
//! `i` holds until point `i + 1`, and the last point repeats the last
//! section's value. This keeps a dwell at exactly zero velocity, where a
//! centred estimate would smear the neighbouring ramps into it.

use ecam_core::{CamPoint, Kinematics};

/// Displacement and the forward-difference velocity, acceleration and jerk
/// at each point.
pub fn of_points(points: &[CamPoint]) -> Vec<Kinematics> {
    let x: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
    let s: Vec<f64> = points.iter().map(|p| p.slave as f64).collect();
    let v = forward(&x, &s);
    let a = forward(&x, &v);
    let j = forward(&x, &a);
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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn too_short_inputs_give_zeros() {
        assert_eq!(forward(&[1.0], &[2.0]), vec![0.0]);
        assert!(forward(&[], &[]).is_empty());
    }
}
