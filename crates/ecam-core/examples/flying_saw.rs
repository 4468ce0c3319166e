//! The LX3V manual's flying-saw demo (ECAMTBX K101): a 660 mm cut on a
//! master of 60π mm per turn, a 40 mm saw stroke at 20 mm per turn, both
//! 1000 pulses per turn. The cut cycle (3501 master pulses) is two tables of
//! 1750: forward (+2000 pulses) and return (−2000, `H1000`).
//!
//! Run with `cargo run -p ecam-core --example flying_saw`.

use ecam_core::CamCurve;
use ecam_core::generator::flying_saw::{Params, generate_pair};

fn main() -> Result<(), ecam_core::TableError> {
    let params = Params {
        master_length: 1750,
        slave_length: 2000,
        sync_length: 667,
        sync_ratio: 3.0 * core::f64::consts::PI, // (1000/20) / (1000/60π) pulses per pulse
        max_ratio: 10.0,
        ..Params::default()
    };
    let (forward, back) = generate_pair(&params)?;
    for (name, g) in [("forward", &forward), ("return", &back)] {
        println!(
            "{name}: stroke {} pulses over {} master counts, constant zone {:?} at ratio {:.5}, peak {:.4}",
            g.table.stroke(),
            g.table.master_span(),
            g.constant_zone,
            g.sync_ratio,
            g.peak_ratio
        );
    }
    println!(
        "net travel over the cycle: {}",
        forward.table.stroke() + back.table.stroke()
    );
    println!("table,master,slave");
    for (name, g) in [("forward", &forward), ("return", &back)] {
        for p in g.table.points() {
            println!("{name},{},{}", p.master, p.slave);
        }
    }
    Ok(())
}
