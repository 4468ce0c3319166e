//! What the master checks and writes on each drive in PRE-OP, over CoE,
//! before the process data is set up: the identity against the
//! configuration, the mode (0x6060 = 8, checked through 0x6061), the CSP
//! PDO assignment and mapping (written, then read back: the layout the
//! cycle decodes by), the sync managers' synchronisation for DC SYNC0
//! (0x1C32/0x1C33), the interpolation period (0x60C2) and the drive's
//! start-up SDO list from the configuration.
//!
//! The order follows the usual start-up of an EtherCAT master (ETG1020,
//! an ENI's PRE-OP → SAFE-OP init commands): everything here runs in
//! PRE-OP, then ethercrab reads the assignment again to size the sync
//! managers.

use std::ops::Deref;
use std::time::Duration;

use ethercrab::error::{Error, MailboxError};
use ethercrab::{EtherCrabWireWrite, SubDevice, SubDeviceRef};

use crate::coe::{SdoAbort, abort_text};
use crate::pdo::{MappingError, PdoEntry, PdoLayout, RX_PDO_ENTRIES, TX_PDO_ENTRIES};

/// A value a start-up SDO writes, with its CoE type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SdoValue {
    /// UNSIGNED8.
    U8(u8),
    /// INTEGER8.
    I8(i8),
    /// UNSIGNED16.
    U16(u16),
    /// INTEGER16.
    I16(i16),
    /// UNSIGNED32.
    U32(u32),
    /// INTEGER32.
    I32(i32),
}

impl core::fmt::Display for SdoValue {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::U8(v) => write!(f, "{v} (u8)"),
            Self::I8(v) => write!(f, "{v} (i8)"),
            Self::U16(v) => write!(f, "{v} (u16)"),
            Self::I16(v) => write!(f, "{v} (i16)"),
            Self::U32(v) => write!(f, "{v} (u32)"),
            Self::I32(v) => write!(f, "{v} (i32)"),
        }
    }
}

/// One write of a drive's start-up list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SdoWrite {
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub sub_index: u8,
    /// The value.
    pub value: SdoValue,
}

impl core::fmt::Display for SdoWrite {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{:#06x}:{:02x} = {}",
            self.index, self.sub_index, self.value
        )
    }
}

/// What the configuration says of one drive (`[[drive]]`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DriveSetup {
    /// Position in the line.
    pub position: usize,
    /// The vendor id it must report (omit: any).
    pub vendor_id: Option<u32>,
    /// The product code it must report (omit: any).
    pub product_code: Option<u32>,
    /// The revision it must report (omit: any).
    pub revision: Option<u32>,
    /// Written in PRE-OP, in order, after ecam's own configuration.
    pub sdo: Vec<SdoWrite>,
}

/// Why a drive was refused at start-up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartupError {
    /// Its identity is not the configured one.
    Identity {
        /// `vendor_id`, `product_code` or `revision`.
        key: &'static str,
        /// The configured value.
        expected: u32,
        /// What the drive reports (SII).
        found: u32,
    },
    /// It has no CoE mailbox (a CiA 402 drive on EtherCAT has one).
    NoCoe,
    /// An SDO transfer failed.
    Sdo {
        /// What the master was doing.
        doing: &'static str,
        /// Object index.
        index: u16,
        /// Sub-index.
        sub_index: u8,
        /// ethercrab's error (an abort carries the drive's code).
        error: Error,
    },
    /// 0x6061 does not show CSP after 0x6060 = 8.
    Mode {
        /// The mode it shows.
        shown: i8,
    },
    /// Its PDO mapping is not the CSP objects.
    Mapping {
        /// What is wrong with the mapping it reports.
        error: MappingError,
        /// The abort with which it refused ecam's mapping, if it did.
        refused: Option<u32>,
    },
    /// 0x1C32/0x1C33:01 does not show DC SYNC0 after it was written.
    SyncMode {
        /// The object.
        index: u16,
        /// The synchronisation type it shows.
        shown: u16,
    },
    /// The cycle is shorter than the drive's minimum (0x1C32:05).
    CycleTooShort {
        /// The drive's minimum, ns.
        min_ns: u32,
    },
    /// A write of the configuration's start-up list failed.
    StartupSdo {
        /// The write.
        write: SdoWrite,
        /// ethercrab's error.
        error: Error,
    },
    /// The configuration describes a drive the segment does not have.
    NotOnSegment,
}

fn error_text(error: &Error) -> String {
    match error {
        Error::Mailbox(MailboxError::Aborted { code, .. }) => {
            format!("abort {}", abort_text(u32::from(*code)))
        }
        other => other.to_string(),
    }
}

impl core::fmt::Display for StartupError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Identity {
                key,
                expected,
                found,
            } => write!(
                f,
                "reports {key} {found:#010x}, the configuration expects {expected:#010x}"
            ),
            Self::NoCoe => f.write_str(
                "has no CoE mailbox: ecam configures and checks CiA 402 drives over CoE",
            ),
            Self::Sdo {
                doing,
                index,
                sub_index,
                error,
            } => write!(
                f,
                "{doing}: SDO {index:#06x}:{sub_index:02x} failed: {}",
                error_text(error)
            ),
            Self::Mode { shown } => write!(
                f,
                "shows mode {shown} in 0x6061 after 0x6060 = 8 was written: it does not run CSP"
            ),
            Self::Mapping { error, refused } => {
                write!(f, "its process data is not the CSP mapping: {error}")?;
                if let Some(code) = refused {
                    write!(f, " (it refused ecam's mapping: {})", abort_text(*code))?;
                }
                Ok(())
            }
            Self::SyncMode { index, shown } => write!(
                f,
                "shows synchronisation type {shown} in {index:#06x}:01 after 2 (DC SYNC0) was written"
            ),
            Self::CycleTooShort { min_ns } => write!(
                f,
                "needs a cycle of at least {} µs (0x1C32:05)",
                min_ns / 1000
            ),
            Self::StartupSdo { write, error } => {
                write!(f, "start-up SDO {write} failed: {}", error_text(error))
            }
            Self::NotOnSegment => {
                f.write_str("is described by the configuration but not on the segment")
            }
        }
    }
}

impl std::error::Error for StartupError {}

/// What the start-up found on a drive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Configured {
    /// Where the CSP objects sit in its process data.
    pub layout: PdoLayout,
    /// It kept its own mapping (refused ecam's): the layout was read back.
    pub fixed_mapping: bool,
    /// 0x1C32/0x1C33 were set to DC SYNC0 (false: the drive has none).
    pub sync_parameters: bool,
}

/// The abort code of an error, if it is an SDO abort.
fn abort_of(error: &Error) -> Option<u32> {
    match error {
        Error::Mailbox(MailboxError::Aborted { code, .. }) => Some(u32::from(*code)),
        _ => None,
    }
}

fn sdo_error(doing: &'static str, index: u16, sub_index: u8) -> impl Fn(Error) -> StartupError {
    move |error| StartupError::Sdo {
        doing,
        index,
        sub_index,
        error,
    }
}

/// The interpolation period of a cycle as 0x60C2 gives it: value (1–255)
/// × 10^index s with the fewest digits, if the cycle can be said so
/// exactly.
pub fn interpolation_period(cycle: Duration) -> Option<(u8, i8)> {
    let mut value = cycle.as_nanos();
    let mut index: i8 = -9;
    if value == 0 {
        return None;
    }
    while value.is_multiple_of(10) {
        value /= 10;
        index += 1;
    }
    Some((u8::try_from(value).ok()?, index))
}

/// Checks and configures one drive in PRE-OP.
///
/// # Errors
/// [`StartupError`] naming what the drive refused or reported.
pub async fn configure<S>(
    drive: &SubDeviceRef<'_, S>,
    setup: Option<&DriveSetup>,
    cycle: Duration,
) -> Result<Configured, StartupError>
where
    S: Deref<Target = SubDevice>,
{
    if let Some(setup) = setup {
        check_identity(drive, setup)?;
    }
    // The first transfer tells whether there is a CoE mailbox at all.
    match drive.sdo_write(0x6060, 0, 8i8).await {
        Err(Error::Mailbox(MailboxError::NoReadMailbox | MailboxError::NoWriteMailbox)) => {
            return Err(StartupError::NoCoe);
        }
        Ok(()) => check_mode(drive).await?,
        // Some drives take the mode only from the process data: then CSP
        // must be among the modes it supports (0x6502 bit 7).
        Err(e) if abort_of(&e).is_some() => {
            let modes = drive.sdo_read::<u32>(0x6502, 0).await;
            if !modes.is_ok_and(|m| m & (1 << 7) != 0) {
                return Err(sdo_error("setting CSP (0x6060 = 8)", 0x6060, 0)(e));
            }
        }
        Err(e) => return Err(sdo_error("setting CSP (0x6060 = 8)", 0x6060, 0)(e)),
    }
    let (layout, fixed_mapping) = map_process_data(drive).await?;
    let sync_parameters = synchronise(drive, cycle).await?;
    if let Some((value, index)) = interpolation_period(cycle) {
        // Optional in CiA 402: a drive without it keeps its own.
        if write_or_absent(drive, 0x60C2, 1, value, "0x60C2").await? {
            write_or_absent(drive, 0x60C2, 2, index, "0x60C2").await?;
        }
    }
    for &write in setup.map_or(&[][..], |s| &s.sdo[..]) {
        let written = match write.value {
            SdoValue::U8(v) => drive.sdo_write(write.index, write.sub_index, v).await,
            SdoValue::I8(v) => drive.sdo_write(write.index, write.sub_index, v).await,
            SdoValue::U16(v) => drive.sdo_write(write.index, write.sub_index, v).await,
            SdoValue::I16(v) => drive.sdo_write(write.index, write.sub_index, v).await,
            SdoValue::U32(v) => drive.sdo_write(write.index, write.sub_index, v).await,
            SdoValue::I32(v) => drive.sdo_write(write.index, write.sub_index, v).await,
        };
        written.map_err(|error| StartupError::StartupSdo { write, error })?;
    }
    Ok(Configured {
        layout,
        fixed_mapping,
        sync_parameters,
    })
}

fn check_identity<S>(drive: &SubDeviceRef<'_, S>, setup: &DriveSetup) -> Result<(), StartupError>
where
    S: Deref<Target = SubDevice>,
{
    let id = drive.identity();
    for (key, expected, found) in [
        ("vendor_id", setup.vendor_id, id.vendor_id),
        ("product_code", setup.product_code, id.product_id),
        ("revision", setup.revision, id.revision),
    ] {
        if let Some(expected) = expected {
            if expected != found {
                return Err(StartupError::Identity {
                    key,
                    expected,
                    found,
                });
            }
        }
    }
    Ok(())
}

/// 0x6061 shows CSP within 100 ms of 0x6060 = 8 (a drive may take a few
/// milliseconds to switch).
async fn check_mode<S>(drive: &SubDeviceRef<'_, S>) -> Result<(), StartupError>
where
    S: Deref<Target = SubDevice>,
{
    let mut shown = 0i8;
    for _ in 0..10 {
        shown = drive.sdo_read::<i8>(0x6061, 0).await.map_err(sdo_error(
            "reading the mode display",
            0x6061,
            0,
        ))?;
        if shown == crate::cia402::MODE_CSP {
            return Ok(());
        }
        crate::poll_sleep::async_io_free_sleep(Duration::from_millis(10)).await;
    }
    Err(StartupError::Mode { shown })
}

/// Writes the CSP assignment and mapping (0x1C12 → 0x1600, 0x1C13 →
/// 0x1A00), then reads back what the drive holds and lays the process
/// data out by it. A drive that refuses the writes (a fixed mapping) is
/// taken as it is if it maps the CSP objects in some order.
async fn map_process_data<S>(drive: &SubDeviceRef<'_, S>) -> Result<(PdoLayout, bool), StartupError>
where
    S: Deref<Target = SubDevice>,
{
    let mut refused = None;
    for (assign, pdo, entries) in [
        (0x1C12u16, 0x1600u16, RX_PDO_ENTRIES),
        (0x1C13, 0x1A00, TX_PDO_ENTRIES),
    ] {
        if let Err(e) = write_mapping(drive, assign, pdo, entries).await {
            match abort_of(&e) {
                Some(code) => refused = refused.or(Some(code)),
                None => return Err(sdo_error("writing the PDO mapping", assign, 0)(e)),
            }
        }
    }
    let outputs = read_mapping(drive, 0x1C12).await?;
    let inputs = read_mapping(drive, 0x1C13).await?;
    let layout = PdoLayout::from_mapping(&outputs, &inputs)
        .map_err(|error| StartupError::Mapping { error, refused })?;
    Ok((layout, refused.is_some()))
}

/// The CiA 301 way: assignment off, mapping off, entries, mapping on,
/// the PDO assigned, assignment on.
async fn write_mapping<S>(
    drive: &SubDeviceRef<'_, S>,
    assign: u16,
    pdo: u16,
    entries: &[PdoEntry],
) -> Result<(), Error>
where
    S: Deref<Target = SubDevice>,
{
    drive.sdo_write(assign, 0, 0u8).await?;
    drive.sdo_write(pdo, 0, 0u8).await?;
    for (k, entry) in entries.iter().enumerate() {
        let sub = u8::try_from(k + 1).unwrap_or(u8::MAX);
        drive.sdo_write(pdo, sub, entry.mapping()).await?;
    }
    let count = u8::try_from(entries.len()).unwrap_or(u8::MAX);
    drive.sdo_write(pdo, 0, count).await?;
    drive.sdo_write(assign, 1, pdo).await?;
    drive.sdo_write(assign, 0, 1u8).await
}

/// Every entry of every PDO an assignment object names, in order.
async fn read_mapping<S>(drive: &SubDeviceRef<'_, S>, assign: u16) -> Result<Vec<u32>, StartupError>
where
    S: Deref<Target = SubDevice>,
{
    const DOING: &str = "reading the PDO mapping back";
    let pdos = drive
        .sdo_read::<u8>(assign, 0)
        .await
        .map_err(sdo_error(DOING, assign, 0))?;
    let mut entries = Vec::new();
    for k in 1..=pdos {
        let pdo = drive
            .sdo_read::<u16>(assign, k)
            .await
            .map_err(sdo_error(DOING, assign, k))?;
        let n = drive
            .sdo_read::<u8>(pdo, 0)
            .await
            .map_err(sdo_error(DOING, pdo, 0))?;
        for sub in 1..=n {
            entries.push(
                drive
                    .sdo_read::<u32>(pdo, sub)
                    .await
                    .map_err(sdo_error(DOING, pdo, sub))?,
            );
        }
    }
    Ok(entries)
}

/// ETG1020: the outputs' and the inputs' sync manager run on SYNC0
/// (0x1C32/0x1C33:01 = 2) with the cycle announced (:02); a drive without
/// these objects is left as it is. False when it has none.
async fn synchronise<S>(drive: &SubDeviceRef<'_, S>, cycle: Duration) -> Result<bool, StartupError>
where
    S: Deref<Target = SubDevice>,
{
    const DOING: &str = "setting DC SYNC0 synchronisation";
    let cycle_ns = u32::try_from(cycle.as_nanos()).unwrap_or(u32::MAX);
    for index in [0x1C32u16, 0x1C33] {
        match drive.sdo_write(index, 1, 2u16).await {
            Err(e) if abort_of(&e) == Some(SdoAbort::NO_OBJECT.0) => return Ok(false),
            // A drive that keeps :01 read-only: what it shows decides.
            Err(e) if abort_of(&e).is_some() => {}
            other => other.map_err(sdo_error(DOING, index, 1))?,
        }
        // Many drives take the cycle from SYNC0 and keep :02 read-only.
        if let Err(e) = drive.sdo_write(index, 2, cycle_ns).await {
            if abort_of(&e).is_none() {
                return Err(sdo_error(DOING, index, 2)(e));
            }
        }
        let shown = drive
            .sdo_read::<u16>(index, 1)
            .await
            .map_err(sdo_error(DOING, index, 1))?;
        if shown != 2 {
            return Err(StartupError::SyncMode { index, shown });
        }
    }
    match drive.sdo_read::<u32>(0x1C32, 5).await {
        Ok(min_ns) if min_ns > cycle_ns => Err(StartupError::CycleTooShort { min_ns }),
        Ok(_) => Ok(true),
        Err(e) if abort_of(&e).is_some() => Ok(true),
        Err(e) => Err(sdo_error(DOING, 0x1C32, 5)(e)),
    }
}

/// Writes an optional object: an abort means the drive does not have it
/// (false); other errors fail.
async fn write_or_absent<S, T>(
    drive: &SubDeviceRef<'_, S>,
    index: u16,
    sub_index: u8,
    value: T,
    doing: &'static str,
) -> Result<bool, StartupError>
where
    S: Deref<Target = SubDevice>,
    T: EtherCrabWireWrite,
{
    match drive.sdo_write(index, sub_index, value).await {
        Ok(()) => Ok(true),
        Err(e) if abort_of(&e).is_some() => Ok(false),
        Err(e) => Err(sdo_error(doing, index, sub_index)(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_periods() {
        let p = |us: u64| interpolation_period(Duration::from_micros(us));
        assert_eq!(p(1000), Some((1, -3)));
        assert_eq!(p(250), Some((25, -5)));
        assert_eq!(p(500), Some((5, -4)));
        assert_eq!(p(1500), Some((15, -4)));
        assert_eq!(p(100_000), Some((1, -1)));
        assert_eq!(p(12_345), None, "not one byte times a power of ten");
    }

    #[test]
    fn errors_in_words() {
        let e = StartupError::Identity {
            key: "product_code",
            expected: 0x1234,
            found: 0x4543_414D,
        };
        assert_eq!(
            e.to_string(),
            "reports product_code 0x4543414d, the configuration expects 0x00001234"
        );
        let w = SdoWrite {
            index: 0x6065,
            sub_index: 0,
            value: SdoValue::U32(2000),
        };
        assert_eq!(w.to_string(), "0x6065:00 = 2000 (u32)");
        assert!(
            StartupError::Mode { shown: 1 }
                .to_string()
                .contains("does not run CSP")
        );
    }
}
