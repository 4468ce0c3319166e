//! Document 000's key-point application case (ECAMTBX K2), end to end:
//! the parameters, the generated table as CSV, its summary and the register
//! words the PLC would hold.
//!
//! Run with `cargo run -p ecam-core --example keypoints`.

use ecam_core::generator::key_points::{self, Params};
use ecam_core::table::Summary;
use ecam_core::{CamCurve, register_image};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Master 0–600: slave dwells at 0; 600–1500: rises to 2000; 1500–1700:
    // dwells; 1700–1900: returns to 600; 1900–2000: returns to 0. Curve type
    // 0 (constant acceleration) everywhere, total resolution 100.
    let params = Params::default();
    let generated = key_points::generate(&params)?;

    println!("# ECAMTBX K2, total resolution {}", params.total_resolution);
    for (i, (kp, r)) in params
        .key_points
        .iter()
        .zip(&generated.resolutions)
        .enumerate()
    {
        println!(
            "# key point {}: master {:5}, slave {:5}, curve type {}, {} points",
            i + 1,
            kp.master,
            kp.slave,
            kp.curve.code(),
            r
        );
    }
    let exact = Summary::of(&generated.profile);
    let table = Summary::of(&generated.table);
    println!(
        "# exact curve: peak velocity ratio {:.3}, peak acceleration {:.5} pulses/count², {}",
        exact.peak_velocity, exact.peak_acceleration, exact.continuity
    );
    println!(
        "# table: {} points, stroke {}, peak velocity ratio {:.3}",
        generated.table.points().len(),
        table.stroke,
        table.peak_velocity
    );
    let words = register_image::to_words(&generated.table)?;
    println!(
        "# register block: {} words, word 38 = {}, word 39 = {}",
        words.len(),
        words[register_image::SECTION_COUNT_OFFSET],
        words[register_image::TABLE_OFFSET_OFFSET]
    );
    print!("{}", ecam_core::io::to_csv(&generated.table));
    assert_eq!(generated.table.master_last(), 2000);
    Ok(())
}
