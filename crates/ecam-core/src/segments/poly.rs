//! Polynomials in the normalised master `u ∈ [0, 1]`: the shapes of the
//! `poly-5` and `poly-7` segments, solved for their boundary values, and
//! the extremes of their derivatives found from their coefficients.
//!
//! An extreme of a derivative on `[0, 1]` is at an end or at a root of the
//! next derivative. Roots are found exactly to rounding: those of a
//! polynomial lie between consecutive roots of its derivative (Rolle), so
//! the roots of each derivative, from the highest down, split `[0, 1]`
//! into pieces on which the polynomial is monotonic, and one bisection per
//! piece with a sign change finds its root. Nothing is sampled.

use alloc::vec::Vec;

/// Most coefficients a segment polynomial has (degree 7).
pub const MAX_COEFFICIENTS: usize = 8;

/// `Σ c[k] uᵏ`, degree at most 7.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Polynomial {
    /// Coefficients, lowest power first.
    pub coefficients: [f64; MAX_COEFFICIENTS],
}

impl Polynomial {
    /// The polynomial with these coefficients (lowest power first; missing
    /// ones are zero, extra ones ignored).
    pub fn new(coefficients: &[f64]) -> Self {
        let mut c = [0.0; MAX_COEFFICIENTS];
        for (slot, value) in c.iter_mut().zip(coefficients) {
            *slot = *value;
        }
        Self { coefficients: c }
    }

    /// Value at `u` (Horner).
    pub fn at(&self, u: f64) -> f64 {
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * u + c)
    }

    /// The first derivative.
    pub fn derivative(&self) -> Self {
        let mut d = [0.0; MAX_COEFFICIENTS];
        for k in 1..MAX_COEFFICIENTS {
            d[k - 1] = self.coefficients[k] * k as f64;
        }
        Self { coefficients: d }
    }

    /// Highest power with a non-zero coefficient (0 for a constant or zero).
    fn degree(&self) -> usize {
        self.coefficients
            .iter()
            .rposition(|&c| c != 0.0)
            .unwrap_or(0)
    }

    /// The roots in the open interval `(0, 1)`, ascending (a root of even
    /// multiplicity, where the sign does not change, may be missed; the
    /// extremes it stands for are then at a neighbouring root or an end,
    /// which [`Polynomial::max_abs`] also visits).
    pub fn roots_in_unit(&self) -> Vec<f64> {
        match self.degree() {
            0 => Vec::new(),
            1 => {
                let u = -self.coefficients[0] / self.coefficients[1];
                if u > 0.0 && u < 1.0 {
                    alloc::vec![u]
                } else {
                    Vec::new()
                }
            }
            _ => {
                let mut fences = alloc::vec![0.0];
                fences.extend(self.derivative().roots_in_unit());
                fences.push(1.0);
                let mut roots = Vec::new();
                for w in fences.windows(2) {
                    let (lo, hi) = (w[0], w[1]);
                    let (flo, fhi) = (self.at(lo), self.at(hi));
                    if fhi == 0.0 && hi < 1.0 {
                        roots.push(hi);
                    } else if flo * fhi < 0.0 {
                        roots.push(bisect(self, lo, hi, flo));
                    }
                }
                roots.dedup();
                roots
            }
        }
    }

    /// Largest `|p(u)|` on `[0, 1]`: at an end or at a root of the derivative.
    pub fn max_abs(&self) -> f64 {
        self.derivative()
            .roots_in_unit()
            .into_iter()
            .chain([0.0, 1.0])
            .map(|u| self.at(u).abs())
            .fold(0.0, f64::max)
    }
}

/// The root of `p` in `(lo, hi)`, where `p` is monotonic and changes sign,
/// bisected until the interval cannot shrink.
fn bisect(p: &Polynomial, mut lo: f64, mut hi: f64, flo: f64) -> f64 {
    let negative_at_lo = flo < 0.0;
    for _ in 0..200 {
        let mid = lo + (hi - lo) / 2.0;
        if mid <= lo || mid >= hi {
            break;
        }
        let f = p.at(mid);
        if f == 0.0 {
            return mid;
        }
        if (f < 0.0) == negative_at_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo + (hi - lo) / 2.0
}

/// `k·(k−1)·…·(k−r+1)`: the factor the `r`-th derivative puts on `uᵏ` (at u = 1).
fn falling(k: usize, r: usize) -> f64 {
    (0..r).fold(1.0, |acc, i| acc * k.saturating_sub(i) as f64)
}

/// The polynomial of degree `2m + 1` that starts at 0 with the derivatives
/// `start[r]` (r = 1..=m) and ends at `rise` with the derivatives `end[r]`,
/// all in units of `u` (a velocity ratio times the segment's master span,
/// an acceleration times its square, …). `start[0]` and `end[0]` are
/// ignored (the start is 0, the end `rise`); `m` is `start.len() − 1`,
/// at most 3.
pub fn solve(rise: f64, start: &[f64], end: &[f64]) -> Polynomial {
    let m = start.len().min(end.len()).saturating_sub(1).min(3);
    let mut c = [0.0; MAX_COEFFICIENTS];
    // The start fixes the low coefficients: c[r] = start[r] / r!.
    let mut factorial = 1.0;
    for r in 1..=m {
        factorial *= r as f64;
        c[r] = start[r] / factorial;
    }
    // The end: m + 1 linear equations in c[m+1 ..= 2m+1].
    let n = m + 1;
    let mut matrix = [[0.0_f64; 5]; 4];
    for (r, row) in matrix.iter_mut().enumerate().take(n) {
        let target = if r == 0 { rise } else { end[r] };
        let known: f64 = (0..=m).map(|k| falling(k, r) * c[k]).sum();
        for (i, slot) in row.iter_mut().take(n).enumerate() {
            *slot = falling(m + 1 + i, r);
        }
        row[n] = target - known;
    }
    let upper = gauss(&mut matrix, n);
    c[m + 1..m + 1 + n].copy_from_slice(&upper[..n]);
    Polynomial { coefficients: c }
}

/// Solves the `n × n` system in `m` (augmented, column `n` the right-hand
/// side) by elimination with partial pivoting. The matrices here are the
/// fixed, regular ones of [`solve`] (never singular).
fn gauss(m: &mut [[f64; 5]; 4], n: usize) -> [f64; 4] {
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap_or(col);
        m.swap(col, pivot);
        let pivot_row = m[col];
        for row in m.iter_mut().take(n).skip(col + 1) {
            let f = row[col] / pivot_row[col];
            for (x, p) in row.iter_mut().zip(pivot_row).take(n + 1).skip(col) {
                *x -= f * p;
            }
        }
    }
    let mut x = [0.0; 4];
    for row in (0..n).rev() {
        let tail: f64 = (row + 1..n).map(|k| m[row][k] * x[k]).sum();
        x[row] = (m[row][n] - tail) / m[row][row];
    }
    x
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn rest_to_rest_quintic_is_the_3_4_5_law() {
        let p = solve(1.0, &[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0]);
        let want = [0.0, 0.0, 0.0, 10.0, -15.0, 6.0, 0.0, 0.0];
        for (a, b) in p.coefficients.iter().zip(want) {
            assert!(close(*a, b), "{:?}", p.coefficients);
        }
        assert!(close(p.derivative().max_abs(), 1.875));
        assert!(close(
            p.derivative().derivative().max_abs(),
            10.0 / 3f64.sqrt()
        ));
        assert!(close(
            p.derivative().derivative().derivative().max_abs(),
            60.0
        ));
    }

    #[test]
    fn rest_to_rest_septic_is_the_4_5_6_7_law() {
        let p = solve(1.0, &[0.0; 4], &[1.0, 0.0, 0.0, 0.0]);
        let want = [0.0, 0.0, 0.0, 0.0, 35.0, -84.0, 70.0, -20.0];
        for (a, b) in p.coefficients.iter().zip(want) {
            assert!(close(*a, b), "{:?}", p.coefficients);
        }
        assert!(close(p.derivative().max_abs(), 2.1875));
    }

    #[test]
    fn boundary_values_are_met() {
        let p = solve(3.0, &[0.0, 1.5, -2.0, 7.0], &[0.0, -0.5, 4.0, 1.0]);
        let d1 = p.derivative();
        let d2 = d1.derivative();
        let d3 = d2.derivative();
        assert!(close(p.at(0.0), 0.0) && close(p.at(1.0), 3.0));
        assert!(close(d1.at(0.0), 1.5) && close(d1.at(1.0), -0.5));
        assert!(close(d2.at(0.0), -2.0) && close(d2.at(1.0), 4.0));
        assert!(close(d3.at(0.0), 7.0) && close(d3.at(1.0), 1.0));
    }

    #[test]
    fn roots_are_found_between_critical_points() {
        // (u − 0.2)(u − 0.5)(u − 0.9) = u³ − 1.6u² + 0.73u − 0.09
        let p = Polynomial::new(&[-0.09, 0.73, -1.6, 1.0]);
        let r = p.roots_in_unit();
        assert_eq!(r.len(), 3);
        for (a, b) in r.iter().zip([0.2, 0.5, 0.9]) {
            assert!((a - b).abs() < 1e-14, "{r:?}");
        }
        assert!(Polynomial::new(&[1.0]).roots_in_unit().is_empty());
        assert!(Polynomial::default().max_abs() == 0.0);
    }
}
