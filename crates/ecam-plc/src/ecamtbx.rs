//! `ECAMTBX S0 S1 D1 D2`: builds a cam table in the PLC's registers from a
//! parameter block (document 003 section 6.3 and appendix; the key-point
//! kind K2 from document 000).
//!
//! - `S0` (`params`): first word of the parameter block, laid out as the
//!   appendix tables say (offsets `NO.0`, `NO.1`…; 32-bit integers and
//!   IEEE-754 floats take two words, low word first).
//! - `S1` (`kind`): K0 or K1 S-curve, K2 key points, K100 rotary cut,
//!   K101 flying saw.
//! - `D1` (`table`): a DECAM register block; the table goes to `D1 + 38`
//!   (point count), `D1 + 39` (= 40) and `D1 + 40…` (master, slave pairs).
//!   Word `D1 + 31` (reserved in the manual) gets the table's end action:
//!   1 for a midCAMend table, which the cam runs once and then stops, 0 for
//!   any other. Words `D1 … D1 + 30` and `D1 + 32 … D1 + 37` are left alone.
//! - `D2` (`result`): the number of table points on success; on failure the
//!   negated error code (−6781, −6782, −6783), and nothing else is written
//!   (the previous table stays).
//!
//! The K0/K1 and K2 blocks get results written back (S-curve P8–P11 and P13
//! at `S0 + 10 … S0 + 19`, K2 `S0` and `S0 + 1`). Every parameter is read
//! and the whole table generated before anything is written, so a table
//! that covers parameter words read them intact; but a write-back word
//! inside the new table (`D1 + 38 …` its last point) would corrupt it, and
//! is refused with 6781. On any failure no word of the previous table
//! (`D1 + 38 …` as its point count says) is written: not D2, not a
//! write-back.
//!
//! The generators themselves live in [`ecam_core::generator`]; this module
//! only moves words in and out.
//!
//! ```
//! use ecam_plc::Devices;
//! use ecam_plc::ecamtbx;
//!
//! // Document 000's key-point case: 5 key points, total resolution 100.
//! let mut dev = Devices::new();
//! dev.set_word(102, 100)?;
//! dev.set_word(103, 5)?;
//! for (i, (m, s)) in [(600, 0), (1500, 2000), (1700, 2000), (1900, 600), (2000, 0)].into_iter().enumerate() {
//!     let at = 108 + 6 * i as u16;
//!     dev.set_dword(at, m)?;
//!     dev.set_dword(at + 2, s)?;
//! }
//! ecamtbx::execute(&mut dev, 100, 2, 2000, 500)?;
//! assert_eq!(dev.word(500)?, 100);     // D2: points written
//! assert_eq!(dev.word(2038)?, 100);    // the table's point count
//! assert_eq!(dev.dword(2040 + 4 * 99)?, 2000); // last master
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use ecam_core::generator::AccelCurve;
use ecam_core::generator::key_points::{self, CurveType, KeyPoint, MAX_KEY_POINTS};
use ecam_core::generator::{CamPlacement, CutParams, Field, schema};
use ecam_core::generator::{flying_saw, rotary_cut, s_curve};
use ecam_core::{
    CODE_PARAMETER, CODE_SECTION_COUNT, CamPoint, PointTable, TableError, register_image,
};

use crate::decam::offsets::{TABLE_END, TABLE_END_REPEAT, TABLE_END_STOP};
use crate::device::D_COUNT;
use crate::devices::Devices;
use crate::operation_error::OperationError;

/// Offset of the point count in the target block (`D1 + 38`).
pub(crate) const TABLE_SECTIONS: u16 = crate::decam::offsets::SECTIONS;
/// Most points a DECAM table holds.
pub(crate) const MAX_POINTS: usize = register_image::MAX_SECTIONS;

/// The table kinds S1 selects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TableKind {
    /// K0 / K1: S-type acceleration and deceleration.
    SCurve,
    /// K2: key points.
    KeyPoints,
    /// K100: rotary cut.
    RotaryCut,
    /// K101: flying saw.
    FlyingSaw,
}

impl TableKind {
    /// Decodes S1.
    pub(crate) fn from_code(kind: i32) -> Option<Self> {
        match kind {
            0 | 1 => Some(Self::SCurve),
            2 => Some(Self::KeyPoints),
            100 => Some(Self::RotaryCut),
            101 => Some(Self::FlyingSaw),
            _ => None,
        }
    }
}

/// Why ECAMTBX failed: the code and where in the parameter block.
#[derive(Clone, Debug, PartialEq)]
struct Failure {
    code: u16,
    message: String,
    /// K2 "error parameter position" (`S0 + 1`): the key point number, or
    /// the offset of the header word at fault; 0 when not tied to one.
    position: u16,
    /// The words of the table that was to be written (`D1 + 38 …`), when
    /// the refusal is about them: nothing is written there either.
    new_table: Option<core::ops::Range<u32>>,
}

impl Failure {
    fn parameter(position: u16, message: impl Into<String>) -> Self {
        Self {
            code: CODE_PARAMETER,
            message: message.into(),
            position,
            new_table: None,
        }
    }

    fn from_table(e: &TableError) -> Self {
        let position = match e {
            TableError::MasterNotIncreasing { section }
            | TableError::ValueOutOfRange { section } => {
                u16::try_from(*section).unwrap_or(u16::MAX)
            }
            TableError::Parameter { name, .. } => match *name {
                "total resolution" => 2,
                "key points number" => 3,
                _ => 0,
            },
            TableError::SectionCount { .. } => 2,
            TableError::Infeasible { .. } => 0,
        };
        Self {
            code: e.code(),
            message: e.to_string(),
            position,
            new_table: None,
        }
    }
}

/// `ECAMTBX S0 S1 D1 D2`.
///
/// # Errors
/// Operation error 6781 (bad parameter or unknown S1), 6782 (a table value
/// out of range, e.g. key points not increasing) or 6783 (more than 512
/// points, or the table does not fit below D8512); `D2` then holds the
/// negated code and the table is not touched.
pub fn execute(
    devices: &mut Devices,
    params: u16,
    kind: i32,
    table: u16,
    result: u16,
) -> Result<(), OperationError> {
    let kind_of = TableKind::from_code(kind);
    // The table before this execution, kept whole on any failure.
    let old_table = table_words(table, old_point_count(devices, table));
    let outcome = match kind_of {
        None => Err(Failure::parameter(
            0,
            format!("unknown table kind K{kind}: use K0, K1, K2, K100 or K101"),
        )),
        Some(kind) => generated_table(devices, params, kind),
    }
    .and_then(|generated| {
        let new_table = table_words(table, generated.points.len());
        let (first, last) = (new_table.start, new_table.end.saturating_sub(1));
        let refuse = |message: String| Failure {
            new_table: Some(new_table.clone()),
            ..Failure::parameter(0, message)
        };
        // D2 inside the words the table takes (D1+38 … its last point) would
        // be overwritten by the result, corrupting the table it describes.
        let end_action = u32::from(table) + u32::from(TABLE_END);
        if end_action == u32::from(result) {
            return Err(refuse(format!(
                "the result register D{result} (D2) is the table's end-action word D1 + 31: put it elsewhere"
            )));
        }
        if new_table.contains(&u32::from(result)) {
            return Err(refuse(format!(
                "the result register D{result} (D2) lies inside the table D{first}..D{last} it would describe: put it elsewhere"
            )));
        }
        // The same for the words written back into the parameter block.
        if let Some(kind) = kind_of
            && let Some(&offset) = written_back(kind)
                .iter()
                .find(|&&o| new_table.contains(&(u32::from(params) + u32::from(o))))
        {
            return Err(refuse(format!(
                "D{} ({}) lies inside the table D{first}..D{last} and would be overwritten: put S0 or D1 elsewhere",
                u32::from(params) + u32::from(offset),
                written_back_name(kind),
            )));
        }
        write_table(devices, table, &generated.points)?;
        let _ = devices.set_word(
            table.saturating_add(TABLE_END),
            (if generated.single_pass { TABLE_END_STOP } else { TABLE_END_REPEAT }) as i16,
        );
        for (offset, value) in generated.write_back {
            let _ = devices.set_dword(params.saturating_add(offset), value);
        }
        Ok(generated.points.len())
    });
    let (value, error) = match outcome {
        Ok(count) => (i16::try_from(count).unwrap_or(i16::MAX), None),
        Err(f) => (-(f.code as i16), Some(f)),
    };
    // After a failure, no word of the old table (nor of the table refused)
    // is written: a D2 or write-back there would corrupt the table kept.
    let protected = |at: u32| {
        error.as_ref().is_some_and(|f| {
            old_table.contains(&at) || f.new_table.as_ref().is_some_and(|r| r.contains(&at))
        })
    };
    let mut report = |at: u32, value: i16| {
        if !protected(at)
            && let Ok(at) = u16::try_from(at)
        {
            let _ = devices.set_word(at, value);
        }
    };
    report(u32::from(result), value);
    let params_at = |offset: u32| u32::from(params) + offset;
    if kind_of == Some(TableKind::SCurve) {
        // P13 (NO.19): "results of chart generation".
        report(params_at(19), value);
    }
    if kind_of == Some(TableKind::KeyPoints) {
        // K2 also reports in its own block: S0 result, S0 + 1 error position.
        report(params_at(0), value);
        report(
            params_at(1),
            error.as_ref().map_or(0, |f| f.position) as i16,
        );
    }
    match error {
        None => Ok(()),
        Some(f) => Err(OperationError::new(
            f.code,
            format!("ECAMTBX K{kind} at D{params}: {}", f.message),
        )),
    }
}

/// The words a table of `points` points takes in block `table`:
/// `D1 + 38` (count), `D1 + 39` and 4 words per point from `D1 + 40`.
fn table_words(table: u16, points: usize) -> core::ops::Range<u32> {
    let first = u32::from(table) + u32::from(TABLE_SECTIONS);
    let points = u16::try_from(points.min(MAX_POINTS)).unwrap_or(0);
    first..u32::from(table) + crate::decam::offsets::block_words(points)
}

/// The point count of the table already in block `table` (0 when `D1 + 38`
/// is not a count a table can have).
fn old_point_count(devices: &Devices, table: u16) -> usize {
    word(devices, table, TABLE_SECTIONS)
        .try_into()
        .unwrap_or(0usize)
        .min(MAX_POINTS)
}

/// Offsets in the parameter block that ECAMTBX writes (the results).
fn written_back(kind: TableKind) -> &'static [u16] {
    match kind {
        TableKind::SCurve => &[10, 11, 12, 13, 14, 15, 16, 17, 19],
        TableKind::KeyPoints => &[0, 1],
        TableKind::RotaryCut | TableKind::FlyingSaw => &[],
    }
}

fn written_back_name(kind: TableKind) -> &'static str {
    match kind {
        TableKind::KeyPoints => "K2's result and error position at S0, S0+1",
        _ => "the S-curve results P8-P11 and P13 at S0+10..S0+19",
    }
}

/// A generated table and the 32-bit results to write back into the
/// parameter block (offset, value), once the table is known to fit.
struct Generated {
    points: Vec<CamPoint>,
    write_back: Vec<(u16, i32)>,
    /// A midCAMend table: the cam stops when it completes.
    single_pass: bool,
}

impl From<Vec<CamPoint>> for Generated {
    fn from(points: Vec<CamPoint>) -> Self {
        Self {
            points,
            write_back: Vec::new(),
            single_pass: false,
        }
    }
}

/// Reads word `base + offset`; the whole block's range is checked first.
fn word(devices: &Devices, base: u16, offset: u16) -> i16 {
    base.checked_add(offset)
        .and_then(|n| devices.word(n).ok())
        .unwrap_or(0)
}

fn dword(devices: &Devices, base: u16, offset: u16) -> i32 {
    base.checked_add(offset)
        .and_then(|n| devices.dword(n).ok())
        .unwrap_or(0)
}

fn check_block(base: u16, words: u16) -> Result<(), Failure> {
    if u32::from(base) + u32::from(words) > u32::from(D_COUNT) {
        return Err(Failure::parameter(
            0,
            format!("parameter block D{base} needs {words} words below D8512"),
        ));
    }
    Ok(())
}

/// K2: `S0+2` total resolution, `S0+3` key point count, `S0+4/5` initial
/// slave, key point i (1-based) at `S0 + 8 + 6 (i − 1)`: master (32-bit),
/// slave (32-bit), curve type, resolution.
fn key_point_table(devices: &Devices, base: u16) -> Result<Vec<CamPoint>, Failure> {
    check_block(base, 8)?;
    let at = |key| register(schema::KEY_POINTS, key);
    // S0+3, the key point count, has no field of its own in the schema:
    // it is the length of the key point list, whose entries start at S0+8.
    let count = word(devices, base, 3);
    let count = usize::try_from(count)
        .ok()
        .filter(|c| (1..=MAX_KEY_POINTS).contains(c))
        .ok_or_else(|| {
            Failure::parameter(
                3,
                format!("key points number (S0+3) is {count}; allowed 1-10"),
            )
        })?;
    check_block(base, 8 + 6 * count as u16)?;
    let mut key_points = Vec::with_capacity(count);
    for i in 0..count as u16 {
        let at = at("key") + 6 * i;
        let number = i + 1;
        let code = word(devices, base, at + 4);
        let curve = CurveType::from_code(i32::from(code)).ok_or_else(|| {
            Failure::parameter(
                number,
                format!("key point {number}: curve type {code}; allowed 0-3"),
            )
        })?;
        // Checked here, not only by the generator, so S0+1 names the key point.
        let raw_resolution = word(devices, base, at + 5);
        let resolution = u16::try_from(raw_resolution)
            .ok()
            .filter(|&r| r <= ecam_core::table::MAX_SEGMENT_RESOLUTION)
            .ok_or_else(|| {
                Failure::parameter(
                    number,
                    format!(
                        "key point {number}: resolution {raw_resolution}; allowed 0 (shared) to {}",
                        ecam_core::table::MAX_SEGMENT_RESOLUTION
                    ),
                )
            })?;
        key_points.push(KeyPoint {
            master: i64::from(dword(devices, base, at)),
            slave: i64::from(dword(devices, base, at + 2)),
            curve,
            resolution,
        });
    }
    let total = word(devices, base, at("resolution"));
    let params = key_points::Params {
        total_resolution: u16::try_from(total).map_err(|_| {
            Failure::parameter(
                2,
                format!(
                    "total resolution (S0+2) is {total}; allowed {}-{}",
                    ecam_core::table::MIN_TOTAL_RESOLUTION,
                    ecam_core::table::MAX_TOTAL_RESOLUTION
                ),
            )
        })?,
        key_points,
        initial_slave: i64::from(dword(devices, base, at("initial_slave"))),
    };
    let generated = key_points::generate(&params).map_err(|e| Failure::from_table(&e))?;
    Ok(generated.table.into_points())
}

/// K0/K1 S-curve block: `NO.0` P1 pulses (32-bit), `NO.2` P2 top speed
/// (32-bit Hz), `NO.6` P4 and `NO.7` P5 ramp times (ms), `NO.8` P6
/// resolution; written back: `NO.10` P8, `NO.12` P9, `NO.14` P10, `NO.16` P11
/// (32-bit each) and `NO.19` P13 the result. Nothing is written here:
/// P8–P11 are returned for [`execute`] to write once the table is in.
fn s_curve_table(devices: &Devices, base: u16) -> Result<Generated, Failure> {
    check_block(base, 20)?;
    let unsigned = |offset: u16, name: &str| {
        u16::try_from(word(devices, base, offset)).map_err(|_| {
            Failure::parameter(offset, format!("{name} (NO.{offset}) must not be negative"))
        })
    };
    let at = |key| register(schema::S_CURVE, key);
    let params = s_curve::Params {
        total_pulses: i64::from(dword(devices, base, at("pulses"))),
        max_speed_hz: u32::try_from(dword(devices, base, at("max_speed"))).map_err(|_| {
            let offset = at("max_speed");
            Failure::parameter(
                offset,
                format!("max speed (P2, NO.{offset}) must not be negative"),
            )
        })?,
        accel_ms: unsigned(at("accel_ms"), "acceleration time P4")?,
        decel_ms: unsigned(at("decel_ms"), "deceleration time P5")?,
        resolution: unsigned(at("resolution"), "resolution P6")?,
        curve: AccelCurve::UniformAcceleration,
    };
    let generated = s_curve::generate(&params).map_err(|e| Failure::from_table(&e))?;
    let clamp = |v: i64| i32::try_from(v).unwrap_or(if v < 0 { i32::MIN } else { i32::MAX });
    let write_back = [
        (10, generated.last_section_master),
        (12, generated.last_section_slave),
        (14, generated.uniform_time),
        (16, generated.max_speed_hz),
    ]
    .into_iter()
    .map(|(offset, value)| (offset, clamp(value)))
    .collect();
    Ok(Generated {
        points: generated.table.into_points(),
        write_back,
        single_pass: false,
    })
}

/// The K100/K101 block: `NO.0` P1 master length, `NO.2` P2 slave length,
/// `NO.4` P3 sync length (32-bit each), `NO.6` P4 sync ratio and `NO.8` P5 max
/// ratio (floats), `NO.10` P6 low word acceleration curve, `NO.11` P6 high
/// word cam curve, `NO.12` P7 resolution (0: the generator's 100).
struct CutBlock {
    master_length: i64,
    slave_length: i64,
    sync_length: i64,
    sync_ratio: f64,
    max_ratio: f64,
    accel_curve: AccelCurve,
    cam_word: u16,
    resolution: u16,
}

/// The word offset of parameter `key` in a generator's ECAMTBX block: the
/// schema in `ecam_core::generator::schema` is the one home of the layout.
fn register(fields: &[Field], key: &str) -> u16 {
    fields
        .iter()
        .find(|f| f.key == key)
        .and_then(|f| f.register)
        .unwrap_or(u16::MAX)
}

fn cut_block(devices: &Devices, base: u16) -> Result<CutBlock, Failure> {
    check_block(base, 20)?;
    let float = |offset: u16, name: &str| {
        let v = base
            .checked_add(offset)
            .and_then(|n| devices.float(n).ok())
            .unwrap_or(f32::NAN);
        if v.is_finite() {
            Ok(f64::from(v))
        } else {
            Err(Failure::parameter(
                offset,
                format!("{name} (NO.{offset}) is not a finite float"),
            ))
        }
    };
    // Rotary cut and flying saw share the block (the manual's P1-P7).
    let at = |key| register(schema::ROTARY_CUT, key);
    let resolution = match word(devices, base, at("resolution")) {
        // The manual's demos leave P7 unset: the generator's default.
        0 => CutParams::default().resolution,
        r => u16::try_from(r).map_err(|_| {
            let offset = at("resolution");
            Failure::parameter(
                offset,
                format!("resolution (P7, NO.{offset}) must not be negative"),
            )
        })?,
    };
    Ok(CutBlock {
        master_length: i64::from(dword(devices, base, at("master"))),
        slave_length: i64::from(dword(devices, base, at("slave"))),
        sync_length: i64::from(dword(devices, base, at("sync"))),
        sync_ratio: float(at("ratio"), "sync ratio P4")?,
        max_ratio: float(at("max_ratio"), "max ratio P5")?,
        accel_curve: AccelCurve::from_code(word(devices, base, at("accel")) as u16)
            .map_err(|e| Failure::from_table(&e))?,
        cam_word: word(devices, base, at("placement")) as u16,
        resolution,
    })
}

/// Reads the whole parameter block and generates the table; writes nothing.
fn generated_table(devices: &Devices, base: u16, kind: TableKind) -> Result<Generated, Failure> {
    let table = |e: TableError| Failure::from_table(&e);
    match kind {
        TableKind::SCurve => s_curve_table(devices, base),
        TableKind::KeyPoints => key_point_table(devices, base).map(Generated::from),
        TableKind::RotaryCut => {
            let b = cut_block(devices, base)?;
            let params = rotary_cut::Params {
                master_length: b.master_length,
                slave_length: b.slave_length,
                sync_length: b.sync_length,
                sync_ratio: b.sync_ratio,
                max_ratio: b.max_ratio,
                accel_curve: b.accel_curve,
                placement: CamPlacement::from_code(b.cam_word).map_err(table)?,
                resolution: b.resolution,
            };
            let generated = rotary_cut::generate(&params).map_err(table)?;
            Ok(Generated {
                // Document 003: with midCAMend "electronic cam stops
                // automatically when completed".
                single_pass: params.placement == CamPlacement::MidCamEnd,
                ..generated.table.into_points().into()
            })
        }
        TableKind::FlyingSaw => {
            let b = cut_block(devices, base)?;
            // H1000 in the high word marks the return table; the sign of P2 decides.
            let (placement, _) = flying_saw::decode_cam_word(b.cam_word).map_err(table)?;
            let params = flying_saw::Params {
                master_length: b.master_length,
                slave_length: b.slave_length,
                sync_length: b.sync_length,
                sync_ratio: b.sync_ratio,
                max_ratio: b.max_ratio,
                accel_curve: b.accel_curve,
                placement,
                resolution: b.resolution,
            };
            Ok(flying_saw::generate(&params)
                .map_err(table)?
                .table
                .into_points()
                .into())
        }
    }
}

/// Writes the points at `D1 + 38…` after checking they all fit.
fn write_table(devices: &mut Devices, base: u16, points: &[CamPoint]) -> Result<(), Failure> {
    let failure = |code: u16, message: String, position: u16| Failure {
        code,
        message,
        position,
        new_table: None,
    };
    if points.len() > MAX_POINTS || points.len() < 2 {
        return Err(failure(
            CODE_SECTION_COUNT,
            format!("{} table points; a DECAM table holds 2-512", points.len()),
            0,
        ));
    }
    let table = PointTable::new(points.to_vec()).map_err(|e| Failure::from_table(&e))?;
    // One writer of the image for ECAMTBX and `--load`: the DECAM face's.
    crate::decam::load_table(devices, base, &table)
        .map(|_| ())
        .map_err(|e| {
            // 6782 names the point: D2's partner S0+1 reports its number.
            let position = points
                .iter()
                .position(|p| i32::try_from(p.master).is_err() || i32::try_from(p.slave).is_err())
                .map_or(0, |i| u16::try_from(i).unwrap_or(u16::MAX));
            failure(e.code, e.message, position)
        })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn every_register_the_instruction_reads_is_in_the_schema() {
        let reads: [(&[Field], &[&str]); 3] = [
            (
                schema::S_CURVE,
                &["pulses", "max_speed", "accel_ms", "decel_ms", "resolution"],
            ),
            (
                schema::ROTARY_CUT,
                &[
                    "master",
                    "slave",
                    "sync",
                    "ratio",
                    "max_ratio",
                    "accel",
                    "placement",
                    "resolution",
                ],
            ),
            (schema::KEY_POINTS, &["key", "resolution", "initial_slave"]),
        ];
        for (fields, keys) in reads {
            for key in keys {
                assert_ne!(register(fields, key), u16::MAX, "{key}");
            }
        }
        // The flying saw reads the rotary cut's block.
        for f in schema::FLY_SAW.iter().filter(|f| f.register.is_some()) {
            assert_eq!(Some(register(schema::ROTARY_CUT, f.key)), f.register);
        }
    }

    #[test]
    fn kinds_decode_as_the_manual_lists_them() {
        assert_eq!(TableKind::from_code(0), Some(TableKind::SCurve));
        assert_eq!(TableKind::from_code(1), Some(TableKind::SCurve));
        assert_eq!(TableKind::from_code(2), Some(TableKind::KeyPoints));
        assert_eq!(TableKind::from_code(100), Some(TableKind::RotaryCut));
        assert_eq!(TableKind::from_code(101), Some(TableKind::FlyingSaw));
        assert_eq!(TableKind::from_code(3), None);
    }

    #[test]
    fn a_table_past_d8511_is_6783_and_nothing_is_written() {
        let mut dev = Devices::new();
        let points = [
            CamPoint::new(0, 0),
            CamPoint::new(10, 5),
            CamPoint::new(20, 0),
        ];
        let err = write_table(&mut dev, 8470, &points).unwrap_err();
        assert_eq!(err.code, CODE_SECTION_COUNT);
        assert_eq!(dev.word(8508).unwrap(), 0);
        write_table(&mut dev, 8400, &points).unwrap();
        assert_eq!(dev.word(8438).unwrap(), 3);
        assert_eq!(dev.dword(8448).unwrap(), 20);
    }

    #[test]
    fn values_beyond_32_bits_are_6782() {
        let mut dev = Devices::new();
        let points = [
            CamPoint::new(0, 0),
            CamPoint::new(10, i64::from(i32::MAX) + 1),
        ];
        assert_eq!(
            write_table(&mut dev, 0, &points).unwrap_err().code,
            ecam_core::CODE_TABLE
        );
    }
}
