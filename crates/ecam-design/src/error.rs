//! Why a table could not be designed: one error enum per concern (the
//! expressions users type, running a generator by name, a scenario's
//! `[table]`). Each message says everything, causes included, so a front
//! end prints it as it is (none has a `source`).

use core::fmt;

use ecam_core::TableError;
use ecam_core::budget::OverBudget;
use ecam_core::drive_check::DriveError;
use ecam_core::excerpt::excerpt;
use ecam_core::io::FileError;
use ecam_core::segments::SegmentError;

/// An expression that cannot be parsed or evaluated.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprError {
    /// Longer than [`ecam_core::limits::MAX_EXPRESSION_LEN`].
    TooLong {
        /// Its length in bytes.
        len: usize,
        /// The limit.
        limit: usize,
    },
    /// A syntax error.
    Syntax {
        /// The expression.
        text: String,
        /// The parser's message, without its internal dumps.
        message: String,
    },
    /// A name that is neither `x` (where the master is allowed) nor a
    /// constant.
    UnknownName {
        /// The name.
        name: String,
        /// The expression.
        text: String,
        /// Whether the master `x` was allowed.
        master_allowed: bool,
    },
    /// A number literal past the 64-bit float range.
    TooLarge {
        /// The literal.
        literal: String,
        /// The expression.
        text: String,
    },
    /// The evaluation failed at `x`.
    Eval {
        /// The expression.
        text: String,
        /// The master position.
        x: f64,
        /// The evaluator's message.
        message: String,
    },
    /// The value at `x` is not finite.
    NotFinite {
        /// The expression.
        text: String,
        /// The master position.
        x: f64,
    },
    /// A constant expression ([`crate::number`]) whose value failed.
    InConstant {
        /// The expression.
        text: String,
        /// Why.
        error: Box<ExprError>,
    },
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // The expression, names and literals are the author's input: quoted
        // as excerpts (a 4 KB expression gives a one-line message).
        match self {
            Self::TooLong { len, limit } => {
                write!(
                    f,
                    "the expression is {len} bytes long; the limit is {limit}"
                )
            }
            Self::Syntax { text, message } => {
                write!(f, "cannot parse expression {:?}: {message}", excerpt(text))
            }
            Self::UnknownName {
                name,
                text,
                master_allowed: true,
            } => write!(
                f,
                "unknown name {:?} in {:?}: the master position is `x`; constants are pi, tau, e",
                excerpt(name),
                excerpt(text)
            ),
            Self::UnknownName { name, text, .. } => {
                write!(
                    f,
                    "unknown name {:?} in {:?}: constants are pi, tau, e",
                    excerpt(name),
                    excerpt(text)
                )
            }
            Self::TooLarge { literal, text } => write!(
                f,
                "the number {} in {:?} is too large for a 64-bit float",
                excerpt(literal),
                excerpt(text)
            ),
            Self::Eval { text, x, message } => {
                write!(
                    f,
                    "cannot evaluate {:?} at x = {x}: {message}",
                    excerpt(text)
                )
            }
            Self::NotFinite { text, x } => {
                write!(f, "{:?} is not finite at x = {x}", excerpt(text))
            }
            Self::InConstant { text, error } => write!(f, "in {:?}: {error}", excerpt(text)),
        }
    }
}

impl std::error::Error for ExprError {}

/// A generator that could not run: an unknown name or parameter, a value
/// of the wrong kind, or parameters the generator refuses.
#[derive(Clone, Debug, PartialEq)]
pub enum GenerateError {
    /// No generator of this name.
    UnknownGenerator {
        /// The name asked for.
        name: String,
    },
    /// The designer's `params` is not an object.
    NotAnObject,
    /// Parameters of a named generator that do not read (unknown key,
    /// wrong kind).
    Params {
        /// The generator's name as given.
        generator: String,
        /// What is wrong, in the author's words.
        message: String,
    },
    /// Parameter values that do not read (unknown key, wrong kind, TOML
    /// syntax), in the author's words.
    Values(String),
    /// The generator (or the point-table checks) refused the parameters,
    /// with the PLC's error code.
    Table(TableError),
    /// A whole fly-saw cycle whose positions pass the 64-bit range.
    Overflow {
        /// `master` or `slave`.
        what: &'static str,
    },
    /// The `function` generator without an expression.
    MissingExpr,
    /// More points than [`ecam_core::limits::MAX_TABLE_POINTS`].
    TooManyPoints {
        /// The points asked for.
        points: usize,
        /// The limit.
        limit: usize,
    },
    /// A function table whose last master is not past its first.
    EmptyRange {
        /// The first master.
        from: i64,
        /// The last master.
        to: i64,
    },
    /// The expression of a function table.
    Expr(ExprError),
    /// The segment generator (or the segment checks) refused the design.
    Segments(SegmentError),
    /// The run's work budget is used up, or the request was given up.
    OverBudget {
        /// The work that did not fit, e.g. `361 points of an expression of
        /// 9 terms` (empty when the request was given up midway).
        work: String,
        /// Why.
        error: OverBudget,
    },
}

impl fmt::Display for GenerateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownGenerator { name } => {
                let known: Vec<&str> = ecam_core::generator::schema::GENERATORS
                    .iter()
                    .map(|g| g.name)
                    .collect();
                write!(f, "unknown generator {name:?}; known: {}", known.join(", "))
            }
            // In the project's words, not the parameter reader's.
            Self::NotAnObject => f.write_str(
                "\"params\" must be an object of numbers, strings and booleans, e.g. {\"points\": 361}",
            ),
            Self::Params { generator, message } => {
                write!(f, "parameters of generator {generator:?}: {message}")
            }
            Self::Values(message) => f.write_str(message),
            Self::Table(e) => write!(f, "{e}"),
            Self::Overflow { what } => write!(f, "{what} overflow"),
            // Worded for every face: `--expr` on the command line, `expr`
            // in a parameter file and over HTTP.
            Self::MissingExpr => f.write_str(
                "the function generator needs its expression `expr`, a function of the master x, e.g. 1000*sin(2*pi*x/36000)",
            ),
            Self::TooManyPoints { points, limit } => write!(
                f,
                "points {points} is above the limit of {limit} points per table"
            ),
            Self::EmptyRange { from, to } => write!(
                f,
                "table error ({}): the last master position ({to}) must be greater than the first ({from})",
                ecam_core::CODE_TABLE
            ),
            Self::Expr(e) => write!(f, "{e}"),
            Self::Segments(e) => write!(f, "{e}"),
            Self::OverBudget { work, error } if work.is_empty() => write!(f, "{error}"),
            Self::OverBudget { work, error } => write!(f, "{work}: {error}"),
        }
    }
}

impl std::error::Error for GenerateError {}

impl From<OverBudget> for GenerateError {
    fn from(error: OverBudget) -> Self {
        Self::OverBudget {
            work: String::new(),
            error,
        }
    }
}

impl From<SegmentError> for GenerateError {
    fn from(e: SegmentError) -> Self {
        Self::Segments(e)
    }
}

impl From<TableError> for GenerateError {
    fn from(e: TableError) -> Self {
        Self::Table(e)
    }
}

impl From<ExprError> for GenerateError {
    fn from(e: ExprError) -> Self {
        Self::Expr(e)
    }
}

/// A scenario's `[table]` that gives no cam.
#[derive(Debug)]
pub enum TableSourceError {
    /// None of the source keys.
    NoSource {
        /// The source keys a `[table]` may give.
        sources: &'static [&'static str],
    },
    /// More than one source key.
    ManySources {
        /// The source keys given.
        found: Vec<&'static str>,
    },
    /// Keys that do not belong to the source, or values of the wrong kind.
    Keys(toml::de::Error),
    /// A table the core refuses.
    Table(TableError),
    /// A table file that cannot be read.
    File(FileError),
    /// `generator` is not a name.
    GeneratorName,
    /// The expression or generator refused its parameters.
    Generate(GenerateError),
}

impl fmt::Display for TableSourceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoSource { sources } => write!(f, "give one of {}", sources.join(", ")),
            Self::ManySources { found } => {
                write!(
                    f,
                    "give only one table source, found {}",
                    found.join(" and ")
                )
            }
            // TOML quotes the input: cut it, in plain words.
            Self::Keys(e) => f.write_str(&ecam_core::io::plain_serde_message(&e.to_string())),
            Self::Table(e) => write!(f, "{e}"),
            Self::File(e) => {
                // The file's error and its causes (the system's reason, the
                // format error) on one line.
                write!(f, "{e}")?;
                let mut source = std::error::Error::source(e);
                while let Some(cause) = source {
                    write!(f, ": {cause}")?;
                    source = cause.source();
                }
                Ok(())
            }
            Self::GeneratorName => f.write_str("generator must be a name, e.g. \"rotary-cut\""),
            Self::Generate(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for TableSourceError {}

/// A drive file that does not read, or a cam the drive check does not take.
#[derive(Clone, Debug, PartialEq)]
pub enum DriveFileError {
    /// TOML syntax, unknown or missing keys, in the author's words.
    Keys(String),
    /// The drive's values are out of range, or the check refuses them.
    Drive(DriveError),
    /// A profile that is not a valid segment cam.
    Profile(SegmentError),
    /// An evenly spaced table.
    Uniform,
}

impl fmt::Display for DriveFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Keys(message) => f.write_str(message),
            Self::Drive(e) => write!(f, "{e}"),
            Self::Profile(e) => write!(f, "{e}"),
            Self::Uniform => f.write_str(
                "the drive check takes point tables, profiles and segment cams; write the evenly spaced table as points first",
            ),
        }
    }
}

impl std::error::Error for DriveFileError {}

impl From<DriveError> for DriveFileError {
    fn from(e: DriveError) -> Self {
        Self::Drive(e)
    }
}
