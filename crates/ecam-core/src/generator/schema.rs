//! The one description of every generator's parameters.
//!
//! Each parameter has one [`Field`]: its key (in parameter files, HTTP
//! bodies and, with `-` for `_`, as a command-line flag), its ECAMTBX
//! number and register, its range, its unit and how a form shows it. The
//! command line builds its flags from these fields, the designer page its
//! forms, the HTTP API checks bodies against them and ECAMTBX reads its
//! registers at their offsets; the values themselves are read into the
//! generators' parameter structs by serde, whose keys are these keys and
//! whose defaults are the structs' `Default`. Adding a parameter is adding
//! it to its `Params` and one `Field` here.
//!
//! ```
//! use ecam_core::generator::schema;
//!
//! let cut = schema::find("rotary-cut").unwrap();
//! let ratio = cut.field("ratio").unwrap();
//! assert_eq!(ratio.param, Some("P4"));
//! assert_eq!(ratio.label(), "P4 sync ratio (slave/master)");
//! assert_eq!(schema::find("flying-saw").unwrap().name, "fly-saw");
//! ```

use alloc::string::String;

use super::accel_curve::AccelCurve;
use super::cut_params::{MAX_RESOLUTION as CUT_MAX, MIN_RESOLUTION as CUT_MIN};
use super::placement::CamPlacement;
use super::s_curve;
use crate::table::{MAX_TOTAL_RESOLUTION, MIN_TOTAL_RESOLUTION};

/// One generator: its name, what it is, and its parameters in order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Generator {
    /// Name as `ecam table gen`, scenario files and the HTTP API spell it.
    pub name: &'static str,
    /// Other names accepted for it.
    pub aliases: &'static [&'static str],
    /// Title of the designer page's choice.
    pub title: &'static str,
    /// One-line description (the command line's help).
    pub about: &'static str,
    /// The parameters, in the order forms and help list them.
    pub fields: &'static [Field],
}

impl Generator {
    /// The field with key `key`.
    pub fn field(&self, key: &str) -> Option<&'static Field> {
        self.fields.iter().find(|f| f.key == key)
    }

    /// True if `name` is this generator's name or one of its aliases.
    pub fn is_called(&self, name: &str) -> bool {
        self.name == name || self.aliases.contains(&name)
    }
}

/// One parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Field {
    /// Key in parameter files and HTTP bodies; the flag is `--` and the
    /// key with `-` for `_`.
    pub key: &'static str,
    /// ECAMTBX parameter number (`"P4"`), where the instruction has one.
    pub param: Option<&'static str>,
    /// Short description, after the parameter number in a form's label.
    pub name: &'static str,
    /// What the parameter means, for help texts.
    pub help: &'static str,
    /// Unit, empty for counts of points and dimensionless values.
    pub unit: &'static str,
    /// Kind of value and its range.
    pub kind: FieldKind,
    /// How a form shows the default when not as the default value itself:
    /// a ratio as a fraction, a default that follows another parameter as
    /// empty, an example where there is no default.
    pub shown_default: Option<&'static str>,
    /// Word offset in the ECAMTBX parameter block (`NO.n`, `S0 + n`).
    pub register: Option<u16>,
}

impl Field {
    /// The form's label: the parameter number, if any, and the name.
    pub fn label(&self) -> String {
        match self.param {
            Some(p) => alloc::format!("{p} {}", self.name),
            None => String::from(self.name),
        }
    }

    /// The command-line flag, without its `--`.
    pub fn flag(&self) -> String {
        self.key.replace('_', "-")
    }
}

/// The Rust type a whole number is kept in (and so the values a flag or a
/// file may give before the generator checks the range).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// `i64`.
    I64,
    /// `u32`.
    U32,
    /// `u16`.
    U16,
    /// `usize`.
    Usize,
}

/// The kind of a parameter's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FieldKind {
    /// A whole number; the generator accepts `min..=max`.
    Integer {
        /// How it is stored.
        storage: Storage,
        /// Smallest value the generator accepts.
        min: i64,
        /// Largest value the generator accepts.
        max: i64,
    },
    /// A real number; front ends may accept arithmetic (`5/3`, `3*pi`).
    Number,
    /// One of these names (or, where the option has them, its code).
    Choice(&'static [&'static str]),
    /// Key points: a list of `{master, slave, curve, resolution}`, typed as
    /// lines ([`KeyPoint::parse_line`](super::key_points::KeyPoint::parse_line)).
    KeyPoints,
    /// An interpolation point `{master, slave, velocity, acceleration,
    /// jerk}` ([`InterpolationPoint`](crate::segments::InterpolationPoint)).
    Point,
    /// Segments: a list of `{law, master, slave, velocity, acceleration,
    /// jerk, resolution}` ([`SegmentSpec`](crate::segments::SegmentSpec)).
    Segments,
    /// Free text.
    Text,
    /// On or off.
    Switch,
}

impl FieldKind {
    /// The kind's name in `GET /api/generators` (`int`, `number`, `choice`,
    /// `keys`, `point`, `segments`, `text`, `bool`).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Integer { .. } => "int",
            Self::Number => "number",
            Self::Choice(_) => "choice",
            Self::KeyPoints => "keys",
            Self::Point => "point",
            Self::Segments => "segments",
            Self::Text => "text",
            Self::Switch => "bool",
        }
    }

    /// True if a value may be negative (a flag then accepts `-5`).
    pub const fn allows_negative(self) -> bool {
        match self {
            Self::Integer { min, .. } => min < 0,
            _ => false,
        }
    }
}

const I32: i64 = i32::MAX as i64;

const fn int(storage: Storage, min: i64, max: i64) -> FieldKind {
    FieldKind::Integer { storage, min, max }
}

const ACCEL_NAMES: [&str; 3] = [
    AccelCurve::Uniform.name(),
    AccelCurve::UniformAcceleration.name(),
    AccelCurve::BType.name(),
];

const PLACEMENT_NAMES: [&str; 5] = [
    CamPlacement::LeftCam.name(),
    CamPlacement::MidCamAll.name(),
    CamPlacement::MidCamBegin.name(),
    CamPlacement::MidCamEnd.name(),
    CamPlacement::RightCam.name(),
];

/// A flying saw's table has its sync zone at an end or in the middle only.
const SAW_PLACEMENT_NAMES: [&str; 3] = [
    CamPlacement::LeftCam.name(),
    CamPlacement::MidCamAll.name(),
    CamPlacement::RightCam.name(),
];

/// ECAMTBX K0/K1, [`s_curve::Params`].
pub const S_CURVE: &[Field] = &[
    Field {
        key: "pulses",
        param: Some("P1"),
        name: "total pulses",
        help: "pulses to move, negative backwards",
        unit: "pulses",
        kind: int(Storage::I64, -I32, I32),
        shown_default: None,
        register: Some(0),
    },
    Field {
        key: "max_speed",
        param: Some("P2"),
        name: "top speed (Hz)",
        help: "top speed in Hz",
        unit: "Hz",
        kind: int(Storage::U32, 1, s_curve::MAX_SPEED_HZ as i64),
        shown_default: None,
        register: Some(2),
    },
    Field {
        key: "accel_ms",
        param: Some("P4"),
        name: "acceleration time (ms)",
        help: "time from rest to top speed, ms",
        unit: "ms",
        kind: int(Storage::U16, 0, s_curve::MAX_RAMP_MS as i64),
        shown_default: None,
        register: Some(6),
    },
    Field {
        key: "decel_ms",
        param: Some("P5"),
        name: "deceleration time (ms)",
        help: "time from top speed to rest, ms",
        unit: "ms",
        kind: int(Storage::U16, 0, s_curve::MAX_RAMP_MS as i64),
        shown_default: None,
        register: Some(7),
    },
    Field {
        key: "resolution",
        param: Some("P6"),
        name: "points",
        help: "points in the table",
        unit: "",
        kind: int(
            Storage::U16,
            s_curve::MIN_RESOLUTION as i64,
            s_curve::MAX_RESOLUTION as i64,
        ),
        shown_default: None,
        register: Some(8),
    },
    Field {
        key: "curve",
        param: None,
        name: "ramp shape",
        help: "ramp shape (the instruction's is uniform-acceleration, S-type)",
        unit: "",
        kind: FieldKind::Choice(&ACCEL_NAMES),
        shown_default: None,
        register: None,
    },
];

const MASTER: Field = Field {
    key: "master",
    param: Some("P1"),
    name: "master length (pulses per cut)",
    help: "master length (material per cut), pulses",
    unit: "pulses",
    kind: int(Storage::I64, 1, I32),
    shown_default: None,
    register: Some(0),
};
const SLAVE: Field = Field {
    key: "slave",
    param: Some("P2"),
    name: "slave length (pulses per turn / stroke)",
    help: "slave length (knife pulses per revolution; fly saw: stroke, negative = return table)",
    unit: "pulses",
    kind: int(Storage::I64, -I32, I32),
    shown_default: None,
    register: Some(2),
};
const SYNC: Field = Field {
    key: "sync",
    param: Some("P3"),
    name: "sync length (slave pulses)",
    help: "sync length in slave pulses",
    unit: "pulses",
    kind: int(Storage::I64, 1, I32),
    shown_default: None,
    register: Some(4),
};
const RATIO: Field = Field {
    key: "ratio",
    param: Some("P4"),
    name: "sync ratio (slave/master)",
    help: "slave pulses per master pulse in the sync zone",
    unit: "",
    kind: FieldKind::Number,
    shown_default: Some("5/3"),
    register: Some(6),
};
const MAX_RATIO: Field = Field {
    key: "max_ratio",
    param: Some("P5"),
    name: "max ratio (empty: 10 × P4)",
    help: "highest ratio allowed anywhere (default 10 × P4)",
    unit: "",
    kind: FieldKind::Number,
    shown_default: Some(""),
    register: Some(8),
};
const ACCEL: Field = Field {
    key: "accel",
    param: Some("P6"),
    name: "acceleration curve",
    help: "low word: acceleration curve",
    unit: "",
    kind: FieldKind::Choice(&ACCEL_NAMES),
    shown_default: None,
    register: Some(10),
};
const PLACEMENT: Field = Field {
    key: "placement",
    param: Some("P6"),
    name: "cam placement",
    help: "high word: where the sync zone sits in the table",
    unit: "",
    kind: FieldKind::Choice(&PLACEMENT_NAMES),
    shown_default: None,
    register: Some(11),
};
const CUT_RESOLUTION: Field = Field {
    key: "resolution",
    param: Some("P7"),
    name: "points",
    help: "points in the table",
    unit: "",
    kind: int(Storage::U16, CUT_MIN as i64, CUT_MAX as i64),
    shown_default: None,
    register: Some(12),
};

/// ECAMTBX K100, [`CutParams`](super::CutParams).
pub const ROTARY_CUT: &[Field] = &[
    MASTER,
    SLAVE,
    SYNC,
    RATIO,
    MAX_RATIO,
    ACCEL,
    PLACEMENT,
    CUT_RESOLUTION,
];

/// ECAMTBX K101, [`CutParams`](super::CutParams) and whether to write the
/// whole cycle (forward and return table, [`generate_pair`](super::flying_saw::generate_pair)).
pub const FLY_SAW: &[Field] = &[
    MASTER,
    SLAVE,
    SYNC,
    RATIO,
    MAX_RATIO,
    ACCEL,
    Field {
        kind: FieldKind::Choice(&SAW_PLACEMENT_NAMES),
        ..PLACEMENT
    },
    CUT_RESOLUTION,
    Field {
        key: "cycle",
        param: None,
        name: "whole cycle (forward + return)",
        help: "the whole cut cycle: the forward table followed by its return table (master 0 .. 2·P1, slave 0 → P2 → 0)",
        unit: "",
        kind: FieldKind::Switch,
        shown_default: None,
        register: None,
    },
];

/// ECAMTBX K2, [`key_points::Params`](super::key_points::Params).
pub const KEY_POINTS: &[Field] = &[
    Field {
        key: "key",
        param: None,
        name: "key points: master slave curve [points] per line",
        help: "key points in master order (at most 10) in master order, each MASTER:SLAVE[:CURVE[:RESOLUTION]]; \
               CURVE is constant-acceleration (default), s-type, cycloid or constant-speed (or 0–3); \
               RESOLUTION 0 shares the rest of the total",
        unit: "",
        kind: FieldKind::KeyPoints,
        shown_default: None,
        register: Some(8),
    },
    Field {
        key: "resolution",
        param: None,
        name: "total points",
        help: "total points in the table",
        unit: "",
        kind: int(
            Storage::U16,
            MIN_TOTAL_RESOLUTION as i64,
            MAX_TOTAL_RESOLUTION as i64,
        ),
        shown_default: None,
        register: Some(2),
    },
    Field {
        key: "initial_slave",
        param: None,
        name: "initial slave",
        help: "slave position the table starts at, added to every key point",
        unit: "pulses",
        kind: int(Storage::I64, -I32, I32),
        shown_default: None,
        register: Some(4),
    },
];

/// A function of the master, [`function::Params`](super::function::Params).
pub const FUNCTION: &[Field] = &[
    Field {
        key: "expr",
        param: None,
        name: "slave(x) =",
        help: "slave position as a function of the master `x`, e.g. \"1000*sin(2*pi*x/36000)\"",
        unit: "pulses",
        kind: FieldKind::Text,
        shown_default: Some("1000*sin(2*pi*x/36000)"),
        register: None,
    },
    Field {
        key: "from",
        param: None,
        name: "first master",
        help: "first master position",
        unit: "counts",
        kind: int(Storage::I64, i64::MIN, i64::MAX),
        shown_default: None,
        register: None,
    },
    Field {
        key: "to",
        param: None,
        name: "last master",
        help: "last master position",
        unit: "counts",
        kind: int(Storage::I64, i64::MIN, i64::MAX),
        shown_default: None,
        register: None,
    },
    Field {
        key: "points",
        param: None,
        name: "points",
        help: "number of points, both ends included",
        unit: "",
        kind: int(Storage::Usize, 2, crate::limits::MAX_TABLE_POINTS as i64),
        shown_default: None,
        register: None,
    },
];

/// Segments between interpolation points, [`segments::Params`](super::segments::Params).
pub const SEGMENTS: &[Field] = &[
    Field {
        key: "start",
        param: None,
        name: "first point",
        help: "the first interpolation point: master, slave and, if the task fixes them, velocity \
               (pulses/count), acceleration (pulses/count²) and jerk (pulses/count³); \
               as a flag MASTER:SLAVE[:V[:A[:J]]], an empty field left free",
        unit: "",
        kind: FieldKind::Point,
        shown_default: None,
        register: None,
    },
    Field {
        key: "segment",
        param: None,
        name: "segments",
        help: "the segments in master order, each the law it follows to its end point \
               (poly-5, poly-7, vv-cycloid or a motion law) and that point; \
               as a flag LAW:MASTER:SLAVE[:V[:A[:J[:POINTS]]]], an empty field left free",
        unit: "",
        kind: FieldKind::Segments,
        shown_default: None,
        register: None,
    },
    Field {
        key: "resolution",
        param: None,
        name: "total points",
        help: "total points in the sampled table",
        unit: "",
        kind: int(
            Storage::U16,
            MIN_TOTAL_RESOLUTION as i64,
            MAX_TOTAL_RESOLUTION as i64,
        ),
        shown_default: None,
        register: None,
    },
    Field {
        key: "continuous",
        param: None,
        name: "make continuous",
        help: "fill every free velocity, acceleration and jerk from the neighbouring segments first",
        unit: "",
        kind: FieldKind::Switch,
        shown_default: None,
        register: None,
    },
];

/// Every generator, in the order front ends list them.
pub const GENERATORS: &[Generator] = &[
    Generator {
        name: "s-curve",
        aliases: &[],
        title: "S-curve point-to-point (ECAMTBX K0/K1)",
        about: "ECAMTBX K0/K1: an S-type point-to-point move (master = ms at a 1 kHz master).",
        fields: S_CURVE,
    },
    Generator {
        name: "rotary-cut",
        aliases: &[],
        title: "Rotary cut (ECAMTBX K100)",
        about: "ECAMTBX K100: rotary knife, synchronised while cutting (document 003 §3.1).",
        fields: ROTARY_CUT,
    },
    Generator {
        name: "fly-saw",
        aliases: &["flying-saw"],
        title: "Flying saw (ECAMTBX K101)",
        about: "ECAMTBX K101: flying saw, forward (P2 > 0) or return (P2 < 0) table (document 003 §3.2).",
        fields: FLY_SAW,
    },
    Generator {
        name: "keypoints",
        aliases: &["key-points"],
        title: "Key points (ECAMTBX K2)",
        about: "ECAMTBX K2: up to ten key points joined by motion curves (document 000 appendix).",
        fields: KEY_POINTS,
    },
    Generator {
        name: "function",
        aliases: &[],
        title: "Function of the master x",
        about: "A function of the master, sampled evenly (the PC editor's \"data setting\", document 003 §6.2).",
        fields: FUNCTION,
    },
    Generator {
        name: "segments",
        aliases: &[],
        title: "Segments between interpolation points (VDI 2143)",
        about: "Segments between interpolation points, each with its motion law, solved for the points' velocity, acceleration and jerk.",
        fields: SEGMENTS,
    },
];

/// The generator called `name` (or one of its aliases).
pub fn find(name: &str) -> Option<&'static Generator> {
    GENERATORS.iter().find(|g| g.is_called(name))
}

impl Field {
    /// For a [`FieldKind::Choice`] field, the canonical name of `text`: one
    /// of its names, or a code or alias the option accepts (`"1"` and
    /// `"s-type"` for `uniform-acceleration`), as long as the field offers
    /// it (a flying saw has no `mid-begin`). `None` for anything else, and
    /// for fields that are not choices. Front ends check a choice with this
    /// before anything runs.
    pub fn choice(&self, text: &str) -> Option<&'static str> {
        let FieldKind::Choice(names) = self.kind else {
            return None;
        };
        // Each option type reads its codes and aliases; the field's own
        // names decide which type it is (their names do not overlap).
        let offered = |name: &'static str| names.iter().copied().find(|n| *n == name);
        AccelCurve::from_name(text)
            .and_then(|c| offered(c.name()))
            .or_else(|| CamPlacement::from_name(text).and_then(|p| offered(p.name())))
            .or_else(|| names.iter().copied().find(|n| *n == text))
    }
}

/// Serde for an option chosen by name or code: written as its name, read
/// from a name or a code (integer or text) through `from_name`; anything
/// else is refused with "unknown WHAT "text"; use NAMES".
macro_rules! choice_serde {
    ($ty:ty, $what:literal) => {
        impl serde::Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Visitor;
                impl serde::de::Visitor<'_> for Visitor {
                    type Value = $ty;
                    fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                        write!(f, "a {} name or code", $what)
                    }
                    fn visit_str<E: serde::de::Error>(self, text: &str) -> Result<$ty, E> {
                        <$ty>::from_name(text).ok_or_else(|| {
                            E::custom(alloc::format!(
                                "unknown {} {:?}; use {}",
                                $what,
                                text,
                                <$ty>::NAMES
                            ))
                        })
                    }
                    fn visit_i64<E: serde::de::Error>(self, code: i64) -> Result<$ty, E> {
                        self.visit_str(&alloc::format!("{code}"))
                    }
                    fn visit_u64<E: serde::de::Error>(self, code: u64) -> Result<$ty, E> {
                        self.visit_str(&alloc::format!("{code}"))
                    }
                }
                d.deserialize_any(Visitor)
            }
        }
    };
}
pub(crate) use choice_serde;

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod choice_tests {
    use super::*;

    #[test]
    fn choices_accept_names_codes_and_aliases_the_field_offers() {
        let accel = S_CURVE.iter().find(|f| f.key == "curve").unwrap();
        assert_eq!(accel.choice("s-type"), Some("uniform-acceleration"));
        assert_eq!(accel.choice("2"), Some("b-type"));
        assert_eq!(accel.choice("foo"), None);
        let saw = find("fly-saw").unwrap();
        let placement = saw.fields.iter().find(|f| f.key == "placement").unwrap();
        assert_eq!(placement.choice("4"), Some("right"));
        assert_eq!(placement.choice("mid-begin"), None);
        assert_eq!(PLACEMENT.choice("mid-begin"), Some("mid-begin"));
        assert_eq!(PLACEMENT.choice("1"), Some("mid-all"));
        assert_eq!(accel.choice("left"), None);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn every_generator_is_found_by_its_names_and_keys_are_unique() {
        for g in GENERATORS {
            assert_eq!(find(g.name), Some(g));
            for a in g.aliases {
                assert_eq!(find(a), Some(g));
            }
            for (i, f) in g.fields.iter().enumerate() {
                assert!(g.fields[..i].iter().all(|o| o.key != f.key), "{}", f.key);
            }
        }
        assert_eq!(find("laser"), None);
    }

    /// The keys a generator's `Params` reads, in the order it writes them.
    fn params_keys(g: &str) -> alloc::vec::Vec<String> {
        let value = match g {
            "s-curve" => serde_json::to_value(s_curve::Params::default()),
            "rotary-cut" | "fly-saw" => serde_json::to_value(super::super::CutParams::default()),
            "keypoints" => serde_json::to_value(super::super::key_points::Params::default()),
            "segments" => serde_json::to_value(super::super::segments::Params::default()),
            _ => serde_json::to_value(super::super::function::Params::default()),
        };
        let serde_json::Value::Object(map) = value.unwrap() else {
            panic!("{g}: not an object");
        };
        map.keys().cloned().collect()
    }

    #[test]
    fn the_fields_are_the_params_keys() {
        for g in GENERATORS {
            let mut fields: alloc::vec::Vec<String> = g
                .fields
                .iter()
                // The flying saw's `cycle` is the front end's (it joins two tables).
                .filter(|f| !(g.name == "fly-saw" && f.key == "cycle"))
                .map(|f| String::from(f.key))
                .collect();
            let mut keys = params_keys(g.name);
            fields.sort();
            keys.sort();
            assert_eq!(fields, keys, "{}", g.name);
        }
    }

    #[test]
    fn defaults_read_back_and_p5_follows_p4() {
        use super::super::CutParams;
        let d = CutParams::default();
        assert_eq!(d.max_ratio, 50.0 / 3.0);
        let back: CutParams = serde_json::from_value(serde_json::to_value(d).unwrap()).unwrap();
        assert_eq!(back, d);
        let p: CutParams =
            serde_json::from_str(r#"{"ratio": 2, "accel": "s-type", "placement": 4}"#).unwrap();
        assert_eq!(p.max_ratio, 20.0);
        assert_eq!(p.accel_curve, AccelCurve::UniformAcceleration);
        assert_eq!(p.placement, CamPlacement::RightCam);
        let err = serde_json::from_str::<CutParams>(r#"{"accel": "wobbly"}"#).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("unknown acceleration curve \"wobbly\"; use uniform (0)"),
            "{err}"
        );
        let k: super::super::key_points::Params =
            serde_json::from_str(r#"{"key": [], "resolution": 20}"#).unwrap();
        assert_eq!(k.key_points.len(), 5);
    }

    #[test]
    fn labels_and_flags() {
        assert_eq!(MAX_RATIO.label(), "P5 max ratio (empty: 10 × P4)");
        assert_eq!(S_CURVE[5].label(), "ramp shape");
        assert_eq!(KEY_POINTS[2].flag(), "initial-slave");
    }
}
