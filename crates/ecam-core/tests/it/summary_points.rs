//! `Summary::of` on point tables: the peak acceleration is estimated from
//! the change of section velocity at each joint, not reported as zero.
#![allow(clippy::unwrap_used)]

use ecam_core::PointTable;
use ecam_core::generator::rotary_cut;
use ecam_core::table::{Continuity, Summary, sample_function};

#[test]
fn document_001_table() {
    // Slopes 0.1, −0.05, 0.1 over sections of 10000: both joints change
    // velocity by 0.15 over a mean section length of 10000.
    let t =
        PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap();
    let s = Summary::of(&t);
    assert!(
        (s.peak_acceleration - 1.5e-5).abs() < 1e-12,
        "{}",
        s.peak_acceleration
    );
    assert_eq!(s.continuity, Continuity::C0);
    assert!((s.peak_velocity - 0.1).abs() < 1e-12);
}

#[test]
fn uneven_sections_use_the_mean_length() {
    // Slope 1 over 10 counts, then 3 over 30: Δv = 2 over (10 + 30)/2.
    let t = PointTable::from_pairs(&[(0, 0), (10, 10), (40, 100)]).unwrap();
    assert!((Summary::of(&t).peak_acceleration - 0.1).abs() < 1e-12);
}

#[test]
fn a_sampled_parabola_gives_its_acceleration() {
    // s = 0.01·x² sampled every 10 counts is exact on whole pulses; its
    // second derivative is 0.02 everywhere.
    let t = sample_function(|x| 0.01 * x * x, 0, 1000, 101).unwrap();
    let s = Summary::of(&t);
    assert!(
        (s.peak_acceleration - 0.02).abs() < 1e-9,
        "{}",
        s.peak_acceleration
    );
    assert_eq!(s.continuity, Continuity::C0);
}

#[test]
fn a_straight_line_has_none() {
    let t = PointTable::from_pairs(&[(0, 0), (10, 30), (20, 60), (35, 105)]).unwrap();
    let s = Summary::of(&t);
    assert_eq!(s.peak_acceleration, 0.0);
    assert_eq!(s.continuity, Continuity::C2);
}

#[test]
fn a_rotary_cut_table_is_near_its_design() {
    // The demo's uniform ramps accelerate at a constant rate; the estimate
    // from the rounded points is of the same size (rounding adds up to
    // ~1 pulse over two short sections).
    let g = rotary_cut::generate(&rotary_cut::Params {
        master_length: 3183,
        sync_length: 333,
        ..rotary_cut::Params::default()
    })
    .unwrap();
    let designed = g
        .design
        .sample_pieces(16)
        .iter()
        .map(|(_, k)| k.a.abs())
        .fold(0.0, f64::max);
    let estimated = Summary::of(&g.table).peak_acceleration;
    assert!(designed > 0.0);
    assert!(
        estimated > 0.5 * designed && estimated < 0.1,
        "{estimated} vs {designed}"
    );
}
