//! `ecam table gen`: the table generators, with parameters from flags, a
//! TOML file (`--params`), or a scenario's `[table]`.
//!
//! Every parameter starts at the document's default (the `Default` of the
//! generator's `Params` in `ecam_core::generator`), then a `--params` file
//! overrides what it sets, then the flags override what they set. Numeric
//! ratios accept arithmetic (`5/3`, `3*pi`).

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use ecam_core::generator::accel_curve::AccelCurve;
use ecam_core::generator::design_curve::DesignCurve;
use ecam_core::generator::key_points::{self, CurveType, KeyPoint};
use ecam_core::generator::placement::CamPlacement;
use ecam_core::generator::{flying_saw, rotary_cut, s_curve};
use ecam_core::{CamCurve, CamPoint, Cursor, Kinematics, PointTable};
use serde::Deserialize;
use serde::de::DeserializeOwned;

use crate::cmd::table::Output;
use crate::expr::{self, MasterFunction};

/// A generated table and what else the generator reported.
pub struct Generated {
    /// The table.
    pub table: PointTable,
    /// Master range of the synchronised zone, where the generator has one.
    pub sync: Option<(i64, i64)>,
    /// The generator's name as `ecam table gen` spells it.
    pub name: &'static str,
    /// Extra results (e.g. the S-curve's P8–P11), printed to stderr.
    pub outputs: Vec<(&'static str, String)>,
    /// Exact velocity, acceleration and jerk at each point, from the curve
    /// the table samples (the points themselves are rounded to whole pulses).
    pub kinematics: Option<Vec<Kinematics>>,
    /// The exact motion the S-curve, rotary-cut and flying-saw generators
    /// designed before rounding it into the table (what `--plot` draws).
    pub design: Option<DesignCurve>,
}

/// The design curve's derivatives at each point of `table`, keeping the
/// table's (rounded) positions.
fn design_along(table: &PointTable, design: &DesignCurve) -> Vec<Kinematics> {
    table
        .points()
        .iter()
        .map(|p| Kinematics {
            s: p.slave as f64,
            ..design.eval(p.master as f64)
        })
        .collect()
}

/// The exact curve's derivatives at each point of `table`, keeping the
/// table's (rounded) positions.
fn kinematics_along(table: &PointTable, curve: &impl CamCurve) -> Vec<Kinematics> {
    let mut cursor = Cursor::new();
    table
        .points()
        .iter()
        .map(|p| Kinematics {
            s: p.slave as f64,
            ..curve.eval(p.master as f64, &mut cursor)
        })
        .collect()
}

/// The generators of `ecam table gen`.
#[derive(clap::Subcommand, Debug)]
pub enum GenCommand {
    /// ECAMTBX K0/K1: an S-type point-to-point move (master = ms at a 1 kHz master).
    #[command(name = "s-curve")]
    SCurve(SCurveArgs),
    /// ECAMTBX K100: rotary knife, synchronised while cutting (document 003 §3.1).
    #[command(name = "rotary-cut")]
    RotaryCut(CutArgs),
    /// ECAMTBX K101: flying saw, forward (P2 > 0) or return (P2 < 0) table (document 003 §3.2).
    #[command(name = "fly-saw", alias = "flying-saw")]
    FlySaw(FlySawArgs),
    /// ECAMTBX K2: up to ten key points joined by motion curves (document 000 appendix).
    #[command(name = "keypoints", alias = "key-points")]
    Keypoints(KeyPointArgs),
    /// A function of the master, sampled evenly (the PC editor's "data setting", document 003 §6.2).
    Function(FunctionArgs),
}

impl GenCommand {
    /// The output options of whichever generator was chosen.
    pub fn output(&self) -> &Output {
        match self {
            Self::SCurve(a) => &a.output,
            Self::RotaryCut(a) => &a.output,
            Self::FlySaw(a) => &a.cut.output,
            Self::Keypoints(a) => &a.output,
            Self::Function(a) => &a.output,
        }
    }
}

/// Generates the table `command` asks for.
///
/// # Errors
/// Unreadable parameter files, bad parameters (with the PLC's error code).
pub fn run(command: &GenCommand) -> anyhow::Result<Generated> {
    match command {
        GenCommand::SCurve(a) => s_curve_table(&with_file(a, a.params.as_deref())?),
        GenCommand::RotaryCut(a) => rotary_cut_table(&with_file(a, a.params.as_deref())?),
        GenCommand::FlySaw(a) => fly_saw_table(&with_file(a, a.cut.params.as_deref())?),
        GenCommand::Keypoints(a) => key_points_table(&with_file(a, a.params.as_deref())?),
        GenCommand::Function(a) => function(&with_file(a, a.params.as_deref())?),
    }
}

/// Generates from a scenario's `[table]` (without the `generator` key).
///
/// # Errors
/// Unknown generator names or parameters, or bad values.
pub fn from_toml(name: &str, params: toml::Table) -> anyhow::Result<Generated> {
    let value = toml::Value::Table(params);
    let context = || format!("parameters of generator {name:?}");
    match name {
        "s-curve" => s_curve_table(&value.try_into().with_context(context)?),
        "rotary-cut" => rotary_cut_table(&value.try_into().with_context(context)?),
        "fly-saw" | "flying-saw" => fly_saw_table(&value.try_into().with_context(context)?),
        "keypoints" | "key-points" => key_points_table(&value.try_into().with_context(context)?),
        "function" => function(&value.try_into().with_context(context)?),
        other => bail!(
            "unknown generator {other:?}; known: s-curve, rotary-cut, fly-saw, keypoints, function"
        ),
    }
}

/// Arguments that can be overlaid: `self`'s set values win over `base`'s.
trait Overlay: DeserializeOwned + Clone {
    fn over(&self, base: Self) -> Self;
}

/// `args` over the contents of the `--params` file, if one was given.
fn with_file<A: Overlay>(args: &A, file: Option<&Path>) -> anyhow::Result<A> {
    let Some(path) = file else {
        return Ok(args.clone());
    };
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read parameter file {}", path.display()))?;
    let base: A =
        toml::from_str(&text).with_context(|| format!("in parameter file {}", path.display()))?;
    Ok(args.over(base))
}

/// A number written as a TOML number or as an arithmetic string (`"5/3"`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Int(i64),
            Float(f64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Int(i) => Ok(Self(i as f64)),
            Raw::Float(f) => Ok(Self(f)),
            Raw::Text(t) => expr::number(&t)
                .map(Self)
                .map_err(|e| serde::de::Error::custom(format!("{e:#}"))),
        }
    }
}

fn parse_number_flag(text: &str) -> Result<Number, String> {
    expr::parse_number(text).map(Number)
}

/// Reads an [`AccelCurve`] by name or P6 low-word code.
fn accel_named(text: &str) -> Option<AccelCurve> {
    match text {
        "0" | "uniform" => Some(AccelCurve::Uniform),
        "1" | "uniform-acceleration" | "s-type" => Some(AccelCurve::UniformAcceleration),
        "2" | "b-type" => Some(AccelCurve::BType),
        _ => None,
    }
}

const ACCEL_NAMES: &str = "uniform (0), uniform-acceleration (1, alias s-type), b-type (2)";

/// Reads a [`CamPlacement`] by name or P6 high-word code.
fn placement_named(text: &str) -> Option<CamPlacement> {
    match text {
        "0" | "left" => Some(CamPlacement::LeftCam),
        "1" | "mid-all" => Some(CamPlacement::MidCamAll),
        "2" | "mid-begin" => Some(CamPlacement::MidCamBegin),
        "3" | "mid-end" => Some(CamPlacement::MidCamEnd),
        "4" | "5" | "right" => Some(CamPlacement::RightCam),
        _ => None,
    }
}

const PLACEMENT_NAMES: &str =
    "left (0), mid-all (1), mid-begin (2), mid-end (3), right (5; 4 also accepted)";

/// A name or code read from a flag or TOML (an integer or a string).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Word(String);

impl<'de> Deserialize<'de> for Word {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Code(i64),
            Name(String),
        }
        Ok(Self(match Raw::deserialize(d)? {
            Raw::Code(c) => c.to_string(),
            Raw::Name(n) => n,
        }))
    }
}

fn parse_word(text: &str) -> Result<Word, String> {
    Ok(Word(text.trim().to_string()))
}

fn accel(word: Option<&Word>, default: AccelCurve) -> anyhow::Result<AccelCurve> {
    match word {
        None => Ok(default),
        Some(Word(w)) => accel_named(w)
            .with_context(|| format!("unknown acceleration curve {w:?}; use {ACCEL_NAMES}")),
    }
}

fn placement(word: Option<&Word>) -> anyhow::Result<CamPlacement> {
    match word {
        None => Ok(CamPlacement::LeftCam),
        Some(Word(w)) => placement_named(w)
            .with_context(|| format!("unknown placement {w:?}; use {PLACEMENT_NAMES}")),
    }
}

// ---------------------------------------------------------------- s-curve

/// Parameters of `ecam table gen s-curve` (defaults: document 003 §3.2's calculation case).
#[derive(clap::Args, Clone, Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SCurveArgs {
    /// P1: pulses to move, negative backwards (default 10000).
    #[arg(long, allow_hyphen_values = true)]
    pub pulses: Option<i64>,
    /// P2: top speed in Hz, 1–150000 (default 50000).
    #[arg(long)]
    pub max_speed: Option<u32>,
    /// P4: time from rest to top speed, ms (default 100).
    #[arg(long)]
    pub accel_ms: Option<u16>,
    /// P5: time from top speed to rest, ms (default 100).
    #[arg(long)]
    pub decel_ms: Option<u16>,
    /// P6: points in the table, 51–512 (default 200).
    #[arg(long)]
    pub resolution: Option<u16>,
    /// Ramp shape: uniform-acceleration (S-type, the instruction's; default), uniform or b-type.
    #[arg(long, value_parser = parse_word)]
    pub curve: Option<Word>,
    /// Read parameters from a TOML file (`pulses`, `max_speed`, `accel_ms`, `decel_ms`, `resolution`, `curve`).
    #[arg(long, value_name = "FILE.toml")]
    #[serde(skip)]
    pub params: Option<PathBuf>,
    #[command(flatten)]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub output: Output,
}

impl Overlay for SCurveArgs {
    fn over(&self, base: Self) -> Self {
        Self {
            pulses: self.pulses.or(base.pulses),
            max_speed: self.max_speed.or(base.max_speed),
            accel_ms: self.accel_ms.or(base.accel_ms),
            decel_ms: self.decel_ms.or(base.decel_ms),
            resolution: self.resolution.or(base.resolution),
            curve: self.curve.clone().or(base.curve),
            params: self.params.clone(),
            output: self.output.clone(),
        }
    }
}

fn s_curve_table(args: &SCurveArgs) -> anyhow::Result<Generated> {
    let d = s_curve::Params::default();
    let params = s_curve::Params {
        total_pulses: args.pulses.unwrap_or(d.total_pulses),
        max_speed_hz: args.max_speed.unwrap_or(d.max_speed_hz),
        accel_ms: args.accel_ms.unwrap_or(d.accel_ms),
        decel_ms: args.decel_ms.unwrap_or(d.decel_ms),
        resolution: args.resolution.unwrap_or(d.resolution),
        curve: accel(args.curve.as_ref(), d.curve)?,
    };
    let g = s_curve::generate(&params)?;
    Ok(Generated {
        outputs: vec![
            (
                "duration (master counts = ms at 1 kHz)",
                g.duration.to_string(),
            ),
            ("P8 last section master", g.last_section_master.to_string()),
            ("P9 last section slave", g.last_section_slave.to_string()),
            ("P10 uniform time", g.uniform_time.to_string()),
            ("P11 max speed (Hz)", g.max_speed_hz.to_string()),
        ],
        kinematics: Some(design_along(&g.table, &g.design)),
        table: g.table,
        sync: g.sync,
        name: "s-curve",
        design: Some(g.design),
    })
}

// ---------------------------------------------------------------- rotary cut, flying saw

/// Parameters of `ecam table gen rotary-cut` (and, flattened, of `fly-saw`).
/// Defaults: the manual's register table (3000, 1000, 300, 5/3); the max
/// ratio defaults to ten times the sync ratio (the demo's rule), the curve
/// to uniform, the placement to left, the resolution to 100.
#[derive(clap::Args, Clone, Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct CutArgs {
    /// P1: master length (material per cut), pulses.
    #[arg(long)]
    pub master: Option<i64>,
    /// P2: slave length (knife pulses per revolution; fly saw: stroke, negative = return table).
    #[arg(long, allow_hyphen_values = true)]
    pub slave: Option<i64>,
    /// P3: sync length in slave pulses.
    #[arg(long)]
    pub sync: Option<i64>,
    /// P4: slave pulses per master pulse in the sync zone; arithmetic allowed ("5/3", "3*pi").
    #[arg(long, value_parser = parse_number_flag)]
    pub ratio: Option<Number>,
    /// P5: highest ratio allowed anywhere (default 10 × ratio).
    #[arg(long, value_parser = parse_number_flag)]
    pub max_ratio: Option<Number>,
    /// P6 low word: uniform (0, default), uniform-acceleration (1), b-type (2).
    #[arg(long, value_parser = parse_word)]
    pub accel: Option<Word>,
    /// P6 high word: left (0, default), mid-all (1), mid-begin (2), mid-end (3), right (5).
    #[arg(long, value_parser = parse_word)]
    pub placement: Option<Word>,
    /// P7: points in the table, 10–512 (default 100).
    #[arg(long)]
    pub resolution: Option<u16>,
    /// Read parameters from a TOML file (`master`, `slave`, `sync`, `ratio`, `max_ratio`, `accel`, `placement`, `resolution`).
    #[arg(long, value_name = "FILE.toml")]
    #[serde(skip)]
    pub params: Option<PathBuf>,
    #[command(flatten)]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub output: Output,
}

impl Overlay for CutArgs {
    fn over(&self, base: Self) -> Self {
        Self {
            master: self.master.or(base.master),
            slave: self.slave.or(base.slave),
            sync: self.sync.or(base.sync),
            ratio: self.ratio.or(base.ratio),
            max_ratio: self.max_ratio.or(base.max_ratio),
            accel: self.accel.clone().or(base.accel),
            placement: self.placement.clone().or(base.placement),
            resolution: self.resolution.or(base.resolution),
            params: self.params.clone(),
            output: self.output.clone(),
        }
    }
}

/// The P1–P7 values common to both cutting generators.
struct CutParams {
    master: i64,
    slave: i64,
    sync: i64,
    ratio: f64,
    max_ratio: f64,
    accel: AccelCurve,
    placement: CamPlacement,
    resolution: u16,
}

fn cut_params(args: &CutArgs) -> anyhow::Result<CutParams> {
    let d = rotary_cut::Params::default();
    let ratio = args.ratio.map_or(d.sync_ratio, |n| n.0);
    Ok(CutParams {
        master: args.master.unwrap_or(d.master_length),
        slave: args.slave.unwrap_or(d.slave_length),
        sync: args.sync.unwrap_or(d.sync_length),
        ratio,
        max_ratio: args.max_ratio.map_or(10.0 * ratio, |n| n.0),
        accel: accel(args.accel.as_ref(), d.accel_curve)?,
        placement: placement(args.placement.as_ref())?,
        resolution: args.resolution.unwrap_or(d.resolution),
    })
}

fn rotary_cut_table(args: &CutArgs) -> anyhow::Result<Generated> {
    let p = cut_params(args)?;
    let g = rotary_cut::generate(&rotary_cut::Params {
        master_length: p.master,
        slave_length: p.slave,
        sync_length: p.sync,
        sync_ratio: p.ratio,
        max_ratio: p.max_ratio,
        accel_curve: p.accel,
        placement: p.placement,
        resolution: p.resolution,
    })?;
    Ok(Generated {
        outputs: vec![
            ("regime", format!("{:?}", g.regime)),
            (
                "sync zone",
                format!(
                    "master {}, slave {} .. {}, ratio {}",
                    g.sync
                        .map_or_else(|| "none".to_string(), |(lo, hi)| format!("{lo} .. {hi}")),
                    g.sync_slave.0,
                    g.sync_slave.1,
                    g.sync_ratio
                ),
            ),
            ("peak ratio", g.peak_ratio.to_string()),
            ("capped at max ratio", g.capped_at_max.to_string()),
        ],
        kinematics: Some(design_along(&g.table, &g.design)),
        table: g.table,
        sync: g.sync,
        name: "rotary-cut",
        design: Some(g.design),
    })
}

/// Parameters of `ecam table gen fly-saw`.
#[derive(clap::Args, Clone, Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct FlySawArgs {
    #[command(flatten)]
    #[serde(flatten)]
    #[allow(missing_docs)]
    pub cut: CutArgs,
    /// Write the whole cut cycle: the forward table followed by its return
    /// table (master 0 .. 2·P1, slave 0 → P2 → 0).
    #[arg(long)]
    #[serde(default)]
    pub cycle: bool,
}

impl Overlay for FlySawArgs {
    fn over(&self, base: Self) -> Self {
        Self {
            cut: self.cut.over(base.cut),
            cycle: self.cycle || base.cycle,
        }
    }
}

fn fly_saw_table(args: &FlySawArgs) -> anyhow::Result<Generated> {
    let p = cut_params(&args.cut)?;
    let params = flying_saw::Params {
        master_length: p.master,
        slave_length: p.slave,
        sync_length: p.sync,
        sync_ratio: p.ratio,
        max_ratio: p.max_ratio,
        accel_curve: p.accel,
        placement: p.placement,
        resolution: p.resolution,
    };
    if !args.cycle {
        let g = flying_saw::generate(&params)?;
        return Ok(Generated {
            outputs: vec![
                ("stroke", format!("{:?}", g.stroke)),
                (
                    "constant-speed zone (master)",
                    format!("{} .. {}", g.constant_zone.0, g.constant_zone.1),
                ),
                ("peak ratio", g.peak_ratio.to_string()),
            ],
            kinematics: Some(design_along(&g.table, &g.design)),
            table: g.table,
            sync: g.sync,
            name: "fly-saw",
            design: Some(g.design),
        });
    }
    let (forward, back) = flying_saw::generate_pair(&params)?;
    let (m_end, s_end) = (forward.table.master_last(), forward.table.slave_last());
    let mut points = forward.table.points().to_vec();
    for q in back.table.points().iter().skip(1) {
        let master = q.master.checked_add(m_end).context("master overflow")?;
        let slave = q.slave.checked_add(s_end).context("slave overflow")?;
        points.push(CamPoint::new(master, slave));
    }
    let table = PointTable::new(points)?;
    let design = forward.design.followed_by(&back.design);
    Ok(Generated {
        outputs: vec![(
            "peak ratio",
            forward.peak_ratio.max(back.peak_ratio).to_string(),
        )],
        kinematics: Some(design_along(&table, &design)),
        table,
        sync: forward.sync,
        name: "fly-saw",
        design: Some(design),
    })
}

// ---------------------------------------------------------------- keypoints

/// One `--key` value or `[[key]]` entry.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct KeyArg {
    master: i64,
    slave: i64,
    #[serde(default, deserialize_with = "curve_from_toml")]
    curve: Option<CurveType>,
    #[serde(default)]
    resolution: u16,
}

const CURVE_NAMES: &str = "constant-acceleration (0), s-type (1), cycloid (2), constant-speed (3)";

fn curve_named(text: &str) -> Option<CurveType> {
    match text {
        "0" | "constant-acceleration" => Some(CurveType::ConstantAcceleration),
        "1" | "s-type" => Some(CurveType::SType),
        "2" | "cycloid" => Some(CurveType::Cycloid),
        "3" | "constant-speed" => Some(CurveType::ConstantSpeed),
        _ => None,
    }
}

fn curve_from_toml<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<CurveType>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Raw {
        Code(i64),
        Name(String),
    }
    let text = match Raw::deserialize(d)? {
        Raw::Code(c) => c.to_string(),
        Raw::Name(n) => n,
    };
    curve_named(&text).map(Some).ok_or_else(|| {
        serde::de::Error::custom(format!("unknown curve {text:?}; use {CURVE_NAMES}"))
    })
}

fn parse_key(text: &str) -> Result<KeyArg, String> {
    let parts: Vec<&str> = text.split(':').map(str::trim).collect();
    let int = |s: &str, what: &str| -> Result<i64, String> {
        s.parse()
            .map_err(|_| format!("{what} {s:?} in --key {text:?} is not an integer"))
    };
    let (master, slave) = match parts.as_slice() {
        [m, s, ..] => (int(m, "master")?, int(s, "slave")?),
        _ => {
            return Err(format!(
                "--key {text:?}: expected MASTER:SLAVE[:CURVE[:RESOLUTION]]"
            ));
        }
    };
    let curve = match parts.get(2) {
        Some(c) => {
            Some(curve_named(c).ok_or_else(|| format!("unknown curve {c:?}; use {CURVE_NAMES}"))?)
        }
        None => None,
    };
    let resolution = match parts.get(3) {
        Some(r) => r
            .parse()
            .map_err(|_| format!("resolution {r:?} in --key {text:?} must be 0..=512"))?,
        None => 0,
    };
    if parts.len() > 4 {
        return Err(format!("--key {text:?}: too many fields"));
    }
    Ok(KeyArg {
        master,
        slave,
        curve,
        resolution,
    })
}

/// Parameters of `ecam table gen keypoints` (defaults: document 000's application case).
#[derive(clap::Args, Clone, Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct KeyPointArgs {
    /// A key point `MASTER:SLAVE[:CURVE[:RESOLUTION]]`, repeated in master order (at most 10);
    /// CURVE is constant-acceleration (default), s-type, cycloid or constant-speed (or 0–3);
    /// RESOLUTION 0 shares the rest of the total.
    #[arg(long = "key", value_name = "M:S[:CURVE[:RES]]", value_parser = parse_key)]
    #[serde(default)]
    pub key: Vec<KeyArg>,
    /// Total points in the table, 10–512 (default 100).
    #[arg(long)]
    pub resolution: Option<u16>,
    /// Slave position the table starts at, added to every key point (default 0).
    #[arg(long, allow_hyphen_values = true)]
    pub initial_slave: Option<i64>,
    /// Read parameters from a TOML file (`resolution`, `initial_slave`, `[[key]]` with `master`, `slave`, `curve`, `resolution`).
    #[arg(long, value_name = "FILE.toml")]
    #[serde(skip)]
    pub params: Option<PathBuf>,
    #[command(flatten)]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub output: Output,
}

impl Overlay for KeyPointArgs {
    fn over(&self, base: Self) -> Self {
        Self {
            key: if self.key.is_empty() {
                base.key
            } else {
                self.key.clone()
            },
            resolution: self.resolution.or(base.resolution),
            initial_slave: self.initial_slave.or(base.initial_slave),
            params: self.params.clone(),
            output: self.output.clone(),
        }
    }
}

fn key_points_table(args: &KeyPointArgs) -> anyhow::Result<Generated> {
    let mut params = key_points::Params::default();
    if !args.key.is_empty() {
        params.key_points = args
            .key
            .iter()
            .map(|k| KeyPoint {
                master: k.master,
                slave: k.slave,
                curve: k.curve.unwrap_or(CurveType::ConstantAcceleration),
                resolution: k.resolution,
            })
            .collect();
    }
    if let Some(r) = args.resolution {
        params.total_resolution = r;
    }
    if let Some(s) = args.initial_slave {
        params.initial_slave = s;
    }
    let generated = key_points::generate(&params)?;
    Ok(Generated {
        kinematics: Some(kinematics_along(&generated.table, &generated.profile)),
        table: generated.table,
        sync: generated.sync,
        name: "keypoints",
        design: None,
        outputs: vec![(
            "segment resolutions",
            generated
                .resolutions
                .iter()
                .map(u16::to_string)
                .collect::<Vec<_>>()
                .join(","),
        )],
    })
}

// ---------------------------------------------------------------- function

/// Parameters of `ecam table gen function`.
#[derive(clap::Args, Clone, Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct FunctionArgs {
    /// Slave position as a function of the master `x`, e.g. "1000*sin(2*pi*x/36000)".
    #[arg(long)]
    pub expr: Option<String>,
    /// First master position (default 0).
    #[arg(long, allow_hyphen_values = true)]
    pub from: Option<i64>,
    /// Last master position (default 36000).
    #[arg(long, allow_hyphen_values = true)]
    pub to: Option<i64>,
    /// Number of points, both ends included (default 361).
    #[arg(long)]
    pub points: Option<usize>,
    /// Read parameters from a TOML file (`expr`, `from`, `to`, `points`).
    #[arg(long, value_name = "FILE.toml")]
    #[serde(skip)]
    pub params: Option<PathBuf>,
    #[command(flatten)]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub output: Output,
}

impl Overlay for FunctionArgs {
    fn over(&self, base: Self) -> Self {
        Self {
            expr: self.expr.clone().or(base.expr),
            from: self.from.or(base.from),
            to: self.to.or(base.to),
            points: self.points.or(base.points),
            params: self.params.clone(),
            output: self.output.clone(),
        }
    }
}

fn function(args: &FunctionArgs) -> anyhow::Result<Generated> {
    let expr = args
        .expr
        .as_deref()
        .context("give the function with --expr, e.g. --expr \"1000*sin(2*pi*x/36000)\"")?;
    let (from, to, points) = (
        args.from.unwrap_or(0),
        args.to.unwrap_or(36000),
        args.points.unwrap_or(361),
    );
    let table = function_table(expr, from, to, points)?;
    let f = MasterFunction::parse(expr)?;
    // Central differences a quarter of the point spacing wide: small
    // against the curve's features, large against f64 round-off.
    let h = (to as f64 - from as f64) / (points.max(2) - 1) as f64 / 4.0;
    let kinematics = table
        .points()
        .iter()
        .map(|p| {
            let k = f.kinematics(p.master as f64, h)?;
            Ok(Kinematics {
                s: p.slave as f64,
                ..k
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok(Generated {
        table,
        sync: None,
        name: "function",
        outputs: Vec::new(),
        kinematics: Some(kinematics),
        design: None,
    })
}

/// Samples `expr` (a function of `x`) at `points` masters from `from` to `to`.
///
/// # Errors
/// Parse or evaluation errors (naming the master where it failed), or a
/// table the core refuses.
pub fn function_table(expr: &str, from: i64, to: i64, points: usize) -> anyhow::Result<PointTable> {
    let f = MasterFunction::parse(expr)?;
    // The core reports this as a non-increasing last point (6782), which
    // names a section the user never wrote; say which settings clash.
    if to <= from {
        bail!(
            "table error ({}): the last master position ({to}) must be greater than the first ({from})",
            ecam_core::CODE_TABLE
        );
    }
    let first_error = std::cell::RefCell::new(None);
    let sampled = ecam_core::table::sample_function(
        |x| match f.at(x) {
            Ok(y) => y,
            Err(e) => {
                first_error.borrow_mut().get_or_insert(e);
                f64::NAN
            }
        },
        from,
        to,
        points,
    );
    if let Some(e) = first_error.into_inner() {
        return Err(e);
    }
    Ok(sampled?)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use ecam_core::CamCurve;

    #[test]
    fn the_rotary_cut_demo() {
        let t: toml::Table = toml::from_str(
            "master = 3183\nslave = 1000\nsync = 333\nratio = \"5/3\"\nmax_ratio = \"50/3\"",
        )
        .unwrap();
        let g = from_toml("rotary-cut", t).unwrap();
        assert_eq!((g.table.master_last(), g.table.slave_last()), (3183, 1000));
        assert!(g.sync.is_some());
    }

    #[test]
    fn the_fly_saw_demo_as_a_whole_cycle() {
        let t: toml::Table = toml::from_str(
            "master = 1750\nslave = 2000\nsync = 667\nratio = \"3*pi\"\nmax_ratio = 10\ncycle = true",
        )
        .unwrap();
        let g = from_toml("fly-saw", t).unwrap();
        assert_eq!((g.table.master_last(), g.table.slave_last()), (3500, 0));
        let peak = g.table.points().iter().map(|p| p.slave).max().unwrap();
        assert_eq!(peak, 2000);
    }

    #[test]
    fn the_s_curve_example() {
        let g = from_toml("s-curve", toml::Table::new()).unwrap();
        assert_eq!(g.table.slave_last(), 10000);
        assert_eq!(g.table.master_last(), 300);
    }

    #[test]
    fn unknown_names_are_refused() {
        let t: toml::Table = toml::from_str("accel = \"wobbly\"").unwrap();
        let err = from_toml("rotary-cut", t).err().unwrap();
        assert!(format!("{err:#}").contains("wobbly"));
        assert!(from_toml("laser", toml::Table::new()).is_err());
        let t: toml::Table = toml::from_str("colour = 3").unwrap();
        assert!(from_toml("rotary-cut", t).is_err());
    }

    #[test]
    fn key_flags_parse() {
        let k = parse_key("1500:2000:cycloid:20").unwrap();
        assert_eq!(
            (k.master, k.slave, k.curve, k.resolution),
            (1500, 2000, Some(CurveType::Cycloid), 20)
        );
        assert_eq!(parse_key("600:0").unwrap().curve, None);
        assert!(parse_key("600").is_err());
        assert!(parse_key("600:0:wobble").is_err());
    }

    #[test]
    fn key_points_default_is_the_appendix_case() {
        let g = from_toml("keypoints", toml::Table::new()).unwrap();
        assert_eq!(g.table.points().len(), 100);
        assert_eq!(g.table.master_last(), 2000);
    }

    #[test]
    fn key_points_from_toml() {
        let t: toml::Table = toml::from_str(
            "resolution = 20\n[[key]]\nmaster = 100\nslave = 50\ncurve = \"cycloid\"\n",
        )
        .unwrap();
        let g = from_toml("keypoints", t).unwrap();
        assert_eq!(g.table.points().len(), 20);
        assert_eq!(g.table.slave_last(), 50);
    }

    #[test]
    fn the_sine_example() {
        let t = function_table("1000*sin(2*pi*x/36000)", 0, 36000, 361).unwrap();
        assert_eq!(t.points().len(), 361);
        assert_eq!(t.points()[90].slave, 1000);
        assert_eq!(t.points()[270].slave, -1000);
    }

    #[test]
    fn generated_tables_carry_exact_derivatives() {
        let t: toml::Table = toml::from_str("expr = \"x*x\"\nto = 100\npoints = 11").unwrap();
        let g = from_toml("function", t).unwrap();
        let k = g.kinematics.unwrap();
        assert!((k[5].v - 100.0).abs() < 1e-9);
        assert!((k[5].a - 2.0).abs() < 1e-9);
        assert!(k[5].j.abs() < 1e-9);
    }

    #[test]
    fn a_reversed_function_range_names_both_ends() {
        let e = function_table("x", 10, 10, 11).err().unwrap().to_string();
        assert!(
            e.contains("(10) must be greater than the first (10)"),
            "{e}"
        );
        assert!(function_table("x", 10, 0, 11).is_err());
    }

    #[test]
    fn function_errors_name_the_master() {
        let err = function_table("1/(x-50)", 0, 100, 11).unwrap_err();
        assert!(format!("{err:#}").contains("x = 50"), "{err:#}");
    }

    #[test]
    fn numbers_take_arithmetic() {
        let n: Number = toml::Value::String("50/3".into()).try_into().unwrap();
        assert!((n.0 - 50.0 / 3.0).abs() < 1e-12);
        let n: Number = toml::Value::Integer(3).try_into().unwrap();
        assert_eq!(n.0, 3.0);
    }
}
