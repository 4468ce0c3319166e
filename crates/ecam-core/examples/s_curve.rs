//! The LX3V manual's S-curve calculation case (ECAMTBX K0/K1): 10000
//! pulses at up to 50 kHz with 100 ms acceleration and deceleration,
//! resolution 200. The master is time: one count per ms at a 1 kHz master.
//!
//! Run with `cargo run -p ecam-core --example s_curve`.

use ecam_core::CamCurve;
use ecam_core::generator::s_curve::{Params, generate};

fn main() -> Result<(), ecam_core::TableError> {
    let params = Params {
        total_pulses: 10_000,
        max_speed_hz: 50_000,
        accel_ms: 100,
        decel_ms: 100,
        resolution: 200,
        ..Params::default()
    };
    let g = generate(&params)?;
    println!("duration: {} ms at a 1 kHz master", g.duration);
    println!(
        "P8 master counts in the last (deceleration) section: {}",
        g.last_section_master
    );
    println!(
        "P9 slave pulses in the last section: {}",
        g.last_section_slave
    );
    println!("P10 uniform time: {}", g.uniform_time);
    println!("P11 max speed in the table: {} Hz", g.max_speed_hz);
    println!(
        "points: {}, ends at ({}, {})",
        g.table.points().len(),
        g.table.master_last(),
        g.table.slave_last()
    );
    println!("master,slave");
    for p in g.table.points() {
        println!("{},{}", p.master, p.slave);
    }
    Ok(())
}
