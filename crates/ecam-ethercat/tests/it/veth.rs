//! The same path over a real network interface: a veth pair whose far end
//! sits in a network namespace the test creates, with the emulated drives
//! answering there. Needs root (CI runs as root); skipped otherwise.

use std::path::PathBuf;
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment, WireEmulation};
use ecam_ethercat::line::{CamDrive, CamLine, LineState, Master};
use ecam_ethercat::{Segment, Transport};

use crate::rotary_knife::knife_axis;

fn is_root() -> bool {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("Uid:"))
                .and_then(|l| l.split_whitespace().nth(2).map(|euid| euid == "0"))
        })
        .unwrap_or(false)
}

fn ip(args: &[&str]) -> bool {
    Command::new("ip")
        .args(args)
        .status()
        .is_ok_and(|s| s.success())
}

/// A veth pair, one end in a fresh namespace; removed when dropped.
struct VethPair {
    netns: String,
    master_end: String,
    drive_end: String,
}

impl VethPair {
    fn create() -> Option<Self> {
        let id = std::process::id();
        let pair = Self {
            netns: format!("ecam-it-{id}"),
            master_end: format!("ecm{id}a"),
            drive_end: format!("ecm{id}b"),
        };
        let ok = ip(&["netns", "add", &pair.netns])
            && ip(&[
                "link",
                "add",
                &pair.master_end,
                "type",
                "veth",
                "peer",
                "name",
                &pair.drive_end,
            ])
            && ip(&["link", "set", &pair.drive_end, "netns", &pair.netns])
            && ip(&["link", "set", &pair.master_end, "up"])
            && ip(&[
                "netns",
                "exec",
                &pair.netns,
                "ip",
                "link",
                "set",
                &pair.drive_end,
                "up",
            ]);
        ok.then_some(pair)
    }
}

impl Drop for VethPair {
    fn drop(&mut self) {
        ip(&["link", "del", &self.master_end]);
        ip(&["netns", "del", &self.netns]);
    }
}

#[test]
fn cam_runs_over_a_veth_pair_in_a_namespace() {
    if !is_root() {
        eprintln!("SKIPPED veth test: needs root to create a network namespace and raw sockets");
        return;
    }
    let Some(pair) = VethPair::create() else {
        eprintln!("SKIPPED veth test: `ip netns`/veth not available on this system");
        return;
    };
    let emulation = Arc::new(Mutex::new(EmulatedSegment::new(
        3,
        DriveBehaviour::default(),
    )));
    let _wire = WireEmulation::spawn(
        &pair.drive_end,
        Some(PathBuf::from(format!("/run/netns/{}", pair.netns))),
        Arc::clone(&emulation),
    )
    .expect("emulation on the veth end");
    let config = crate::exact_config();
    let segment = Segment::bring_up(Transport::Interface(pair.master_end.clone()), config)
        .expect("bring-up over veth");
    assert_eq!(segment.len(), 3);
    let axes = (0..3)
        .map(|drive| CamDrive {
            axis: knife_axis(),
            drive,
            master: Master::Virtual,
        })
        .collect();
    let mut line = CamLine::new(segment, axes, crate::LOST, Duration::ZERO).unwrap();
    line.virtual_speed = 13;
    line.start().unwrap();
    for _ in 0..20 {
        line.cycle().unwrap();
    }
    assert_eq!(line.state(), LineState::Running);
    for cycle in 0..500 {
        let report = line.cycle().unwrap();
        assert!(!report.bus.working_counter_error(), "cycle {cycle}");
        let outputs = line.outputs();
        let emu = emulation.lock().unwrap();
        for (i, esc) in emu.escs().iter().enumerate() {
            assert_eq!(
                i64::from(esc.drive().target()),
                outputs[i].slave,
                "cycle {cycle}"
            );
        }
    }
}
