//! Fault 5 of issue 24: drives described by configuration. The master
//! configures each drive over CoE in PRE-OP and reads back what it took:
//! the PDO mapping (a drive that keeps its own order is decoded by it,
//! never silently wrong), the mode through 0x6061, the identity against
//! `[[drive]]`, the start-up SDO list, 0x1C32/0x1C33 and 0x60C2.

use std::sync::{Arc, Mutex};

use ecam_ethercat::EthercatError;
use ecam_ethercat::cia402::DriveState;
use ecam_ethercat::emulation::{DriveBehaviour, EMULATED_PRODUCT_CODE, EmulatedSegment};
use ecam_ethercat::pdo::MappingError;
use ecam_ethercat::startup::{DriveSetup, SdoValue, SdoWrite, StartupError};
use ecam_ethercat::{Segment, Transport};

use crate::test_config;

fn bring_up(
    drives: usize,
    behaviour: DriveBehaviour,
    setups: Vec<DriveSetup>,
) -> (Result<Segment, EthercatError>, Arc<Mutex<EmulatedSegment>>) {
    let mut emulated = EmulatedSegment::new(drives, behaviour);
    emulated.set_watchdog(None);
    let emulation = Arc::new(Mutex::new(emulated));
    let segment = Segment::bring_up_with(
        Transport::Emulated(Arc::clone(&emulation)),
        test_config(),
        setups,
    );
    (segment, emulation)
}

/// A drive whose TxPDO carries statusword, error code, position and
/// following error (the same 12 bytes in another order) and refuses
/// ecam's mapping: decoded by the order it reports.
#[test]
fn a_drive_with_its_own_pdo_order_is_decoded_right() {
    let behaviour = DriveBehaviour {
        fixed_mapping: true,
        ..DriveBehaviour::default()
    };
    let (segment, emulation) = bring_up(2, behaviour, Vec::new());
    let mut segment = segment.expect("a reordered CSP mapping is taken");
    assert!(segment.drive_info()[0].fixed_mapping);
    assert!(
        segment.drive_info()[0]
            .to_string()
            .contains("its own PDO order")
    );
    {
        let mut emu = emulation.lock().unwrap();
        let esc = emu.esc_mut(1).unwrap();
        esc.drive_mut().place(-123_456);
        esc.drive_mut().inject_fault(0x2310);
    }
    // The fault shows after the drive's next cycle.
    for _ in 0..3 {
        segment.exchange().unwrap();
    }
    let inputs = segment.drives()[1].inputs();
    assert_eq!(inputs.position_actual, -123_456);
    assert_eq!(inputs.error_code, 0x2310);
    assert_eq!(segment.drives()[1].state(), DriveState::Fault);
    assert_eq!(segment.drives()[0].inputs().error_code, 0);
    assert_eq!(segment.drives()[0].state(), DriveState::SwitchOnDisabled);
}

/// Drives that take the mapping: assignment, mapping, SYNC0 and the
/// interpolation period as the master wrote them; the start-up list
/// applied (a following-error window of 5 counts takes effect).
#[test]
fn the_master_configures_mapping_sync_and_the_start_up_list() {
    let setup = DriveSetup {
        position: 1,
        vendor_id: Some(0),
        product_code: Some(EMULATED_PRODUCT_CODE),
        revision: Some(1),
        sdo: vec![
            SdoWrite {
                index: 0x6065,
                sub_index: 0,
                value: SdoValue::U32(5),
            },
            SdoWrite {
                index: 0x6085,
                sub_index: 0,
                value: SdoValue::U32(50_000),
            },
        ],
    };
    let (segment, emulation) = bring_up(2, DriveBehaviour::default(), vec![setup]);
    let segment = segment.expect("bring-up");
    assert!(!segment.drive_info()[1].fixed_mapping);
    assert!(segment.drive_info()[1].sync_parameters);
    let emu = emulation.lock().unwrap();
    let read = |drive: usize, index, sub| emu.escs()[drive].sdo_read(index, sub).unwrap();
    for drive in 0..2 {
        assert_eq!(read(drive, 0x1C12, 0), vec![1]);
        assert_eq!(read(drive, 0x1C12, 1), 0x1600u16.to_le_bytes());
        assert_eq!(read(drive, 0x1600, 0), vec![3]);
        assert_eq!(read(drive, 0x1600, 2), 0x607A_0020u32.to_le_bytes());
        assert_eq!(read(drive, 0x1A00, 0), vec![4]);
        assert_eq!(read(drive, 0x1A00, 4), 0x603F_0010u32.to_le_bytes());
        assert_eq!(read(drive, 0x1C32, 1), 2u16.to_le_bytes(), "DC SYNC0");
        assert_eq!(read(drive, 0x1C33, 1), 2u16.to_le_bytes());
        assert_eq!(
            read(drive, 0x1C32, 2),
            1_000_000u32.to_le_bytes(),
            "cycle, ns"
        );
        assert_eq!(read(drive, 0x60C2, 1), vec![1], "1 × 10^-3 s");
        assert_eq!(read(drive, 0x60C2, 2), vec![(-3i8) as u8]);
        assert_eq!(read(drive, 0x6061, 0), vec![8], "CSP");
    }
    assert_eq!(read(1, 0x6065, 0), 5u32.to_le_bytes());
    assert_eq!(read(1, 0x6085, 0), 50_000u32.to_le_bytes());
    assert_eq!(
        read(0, 0x6065, 0),
        1_000_000u32.to_le_bytes(),
        "drive 0 untouched"
    );
    assert_eq!(emu.escs()[1].drive().behaviour().following_error_window, 5);
}

#[test]
fn a_drive_of_another_identity_is_refused() {
    let setup = DriveSetup {
        position: 0,
        product_code: Some(0x1234),
        ..DriveSetup::default()
    };
    let (segment, _) = bring_up(1, DriveBehaviour::default(), vec![setup]);
    let e = segment.unwrap_err();
    assert!(
        matches!(
            e,
            EthercatError::Startup {
                position: 0,
                error: StartupError::Identity {
                    key: "product_code",
                    expected: 0x1234,
                    found: EMULATED_PRODUCT_CODE
                },
                ..
            }
        ),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        "drive 0 (ecam emulated CSP drive) reports product_code 0x4543414d, \
         the configuration expects 0x00001234"
    );
    let beyond = DriveSetup {
        position: 3,
        ..DriveSetup::default()
    };
    let (segment, _) = bring_up(1, DriveBehaviour::default(), vec![beyond]);
    assert!(
        segment
            .unwrap_err()
            .to_string()
            .contains("drive 3 is described by the configuration but not on the segment")
    );
}

/// A drive that takes 0x6060 = 8 but stays in its mode: 0x6061 tells.
#[test]
fn a_drive_that_does_not_run_csp_is_refused() {
    let behaviour = DriveBehaviour {
        csp: false,
        ..DriveBehaviour::default()
    };
    let (segment, _) = bring_up(1, behaviour, Vec::new());
    let e = segment.unwrap_err();
    assert!(
        matches!(
            e,
            EthercatError::Startup {
                error: StartupError::Mode { shown: 0 },
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("0x6061"), "{e}");
}

/// A start-up write the drive refuses stops the bring-up with the
/// drive's abort code in words.
#[test]
fn a_refused_start_up_sdo_is_reported_with_its_abort_code() {
    let setup = DriveSetup {
        position: 0,
        sdo: vec![SdoWrite {
            index: 0x6041,
            sub_index: 0,
            value: SdoValue::U16(0),
        }],
        ..DriveSetup::default()
    };
    let (segment, _) = bring_up(1, DriveBehaviour::default(), vec![setup]);
    let text = segment.unwrap_err().to_string();
    assert!(
        text.contains("start-up SDO 0x6041:00 = 0 (u16) failed: abort 0x06010002"),
        "{text}"
    );
}

#[test]
fn mapping_errors_name_the_object() {
    let e = StartupError::Mapping {
        error: MappingError::Unknown {
            entry: 0x606C_0020,
            outputs: false,
        },
        refused: Some(0x0601_0002),
    };
    let text = e.to_string();
    assert!(
        text.contains("inputs (TxPDO) map 0x606c:00 (32 bits)"),
        "{text}"
    );
    assert!(
        text.contains("refused ecam's mapping: 0x06010002"),
        "{text}"
    );
}
