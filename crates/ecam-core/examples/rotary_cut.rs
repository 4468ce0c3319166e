//! The LX3V manual's rotary-cut demo (ECAMTBX K100): a 1000 mm cut from a
//! feed roll of 100π mm and a knife of 60π mm, both 1000 pulses per turn.
//!
//! Run with `cargo run -p ecam-core --example rotary_cut`.

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::rotary_cut::{Params, generate};

fn main() -> Result<(), ecam_core::TableError> {
    let params = Params {
        master_length: 3183,   // 1000 mm / (100π mm / 1000 pulses)
        slave_length: 1000,    // one knife turn
        sync_length: 333,      // about a third of the turn
        sync_ratio: 5.0 / 3.0, // slave pulses per master pulse at equal surface speed
        max_ratio: 50.0 / 3.0, // ten times the sync ratio
        // The demo sets P6 low word 0 and calls it "uniform acceleration"; the
        // register table names code 1 so. We show code 1 (S-type ramps); the
        // tests run every code, and the synchronisation is the same for all.
        accel_curve: AccelCurve::UniformAcceleration,
        placement: CamPlacement::LeftCam,
        resolution: 100,
    };
    let g = generate(&params)?;
    println!("regime: {:?}", g.regime);
    println!(
        "sync zone: master {:?}, slave {:?}, ratio {:.6} (asked {:.6})",
        g.sync, g.sync_slave, g.sync_ratio, params.sync_ratio
    );
    println!("peak ratio in the table: {:.4}", g.peak_ratio);
    println!("sections: {}", g.table.points().len() - 1);
    println!("master,slave");
    for p in g.table.points() {
        println!("{},{}", p.master, p.slave);
    }
    Ok(())
}
