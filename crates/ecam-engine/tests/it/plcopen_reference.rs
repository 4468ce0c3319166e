//! The PLCopen facade against reference traces (`fixtures/plcopen_reference.csv`,
//! written by `scripts/plcopen-oracle.py`; see its header for provenance):
//! the four points where PLCopen implementations read `MC_CamIn` the same
//! way and ecam's facade must too, to within 0.5 pulse. The fixture is data
//! in the repository: this test never runs Python.

use std::collections::BTreeMap;

use ecam_core::PointTable;
use ecam_engine::Zoom;
use ecam_engine::plcopen::{CamIn, CamTableSelect, McCamAxis};

const FIXTURE: &str = include_str!("fixtures/plcopen_reference.csv");

struct Row {
    master: i64,
    slave: f64,
    end_of_profile: Option<bool>,
}

struct Fixture {
    tables: BTreeMap<String, Vec<(i64, i64)>>,
    traces: BTreeMap<String, (String, Vec<Row>)>,
}

fn fixture() -> Fixture {
    let mut tables: BTreeMap<String, Vec<(i64, i64)>> = BTreeMap::new();
    let mut traces: BTreeMap<String, (String, Vec<Row>)> = BTreeMap::new();
    for line in FIXTURE
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let f: Vec<&str> = line.split(',').collect();
        match f[0] {
            "table" => tables
                .entry(f[1].to_string())
                .or_default()
                .push((f[2].parse().unwrap(), f[3].parse().unwrap())),
            "trace" => traces
                .entry(f[1].to_string())
                .or_insert_with(|| (f[2].to_string(), Vec::new()))
                .1
                .push(Row {
                    master: f[3].parse().unwrap(),
                    slave: f[4].parse().unwrap(),
                    end_of_profile: match f[5] {
                        "1" => Some(true),
                        "0" => Some(false),
                        _ => None,
                    },
                }),
            other => panic!("unknown row kind {other}"),
        }
    }
    Fixture { tables, traces }
}

/// Runs `case` through the facade and checks every row.
fn check(case: &str, select: CamTableSelect, params: &CamIn, slave_start: i64) {
    let f = fixture();
    let (table, rows) = &f.traces[case];
    let points = &f.tables[table];
    let mut axis = McCamAxis::new(PointTable::from_pairs(points).unwrap()).unwrap();
    axis.select(select).unwrap();
    axis.set_slave_position(slave_start).unwrap();
    axis.cam_in(params).unwrap();
    assert!(rows.len() > 20, "{case}: too few rows");
    for row in rows {
        let status = axis.tick(row.master, 1_000_000);
        let got = status.output.slave as f64;
        assert!(
            (got - row.slave).abs() <= 0.5,
            "{case}: master {}: ecam {got}, reference {}",
            row.master,
            row.slave
        );
        if let Some(eop) = row.end_of_profile {
            assert_eq!(status.end_of_profile, eop, "{case}: master {}", row.master);
            assert!(status.active, "{case}: still coupled at {}", row.master);
        }
    }
}

/// (1) Periodic with an absolute slave re-evaluates the table each cycle.
#[test]
fn periodic_absolute_slave_is_re_evaluated_each_cycle() {
    check(
        "periodic_absolute",
        CamTableSelect::default(),
        &CamIn::default(),
        0,
    );
}

/// (2) Non-periodic with an absolute master: the table's own range, then
/// coupled at the last value with EndOfProfile.
#[test]
fn non_periodic_absolute_master_holds_the_end_coupled() {
    check(
        "non_periodic_master_absolute",
        CamTableSelect {
            periodic: false,
            ..CamTableSelect::default()
        },
        &CamIn::default(),
        0,
    );
}

/// (3) MasterScaling multiplies the master: table input = 2 × master + 1000.
#[test]
fn master_scaling_multiplies_the_master() {
    check(
        "master_scaling_2_offset_1000",
        CamTableSelect::default(),
        &CamIn {
            master_scaling: Zoom::new(2, 1).unwrap(),
            master_offset: 1000,
            ..CamIn::default()
        },
        0,
    );
}

/// (4) SlaveAbsolute = false adds the slave's start position.
#[test]
fn slave_relative_adds_the_start_position() {
    check(
        "slave_relative_adds_start_5000",
        CamTableSelect {
            master_absolute: false,
            slave_absolute: false,
            ..CamTableSelect::default()
        },
        &CamIn::default(),
        5000,
    );
}
