//! `ecam table gen`: the generators' subcommands and flags, built from
//! [`ecam_core::generator::schema`], one flag per field, named after its key.
//!
//! Every parameter starts at the document's default, then a `--params` file
//! overrides what it sets, then the flags override what they set; running
//! the generator is [`ecam_design`]'s. Numeric ratios accept arithmetic
//! (`5/3`, `3*pi`).

use std::path::PathBuf;

use anyhow::Context;
use clap::{Arg, ArgAction, ArgMatches, Args};
use ecam_core::generator::Generator as Schema;
use ecam_core::generator::key_points::KeyPoint;
use ecam_core::generator::schema::{self, Field, FieldKind, Storage};
use ecam_core::segments::{InterpolationPoint, SegmentSpec};
use ecam_design::{
    Generated, Param, Values, default_values, parse_key, parse_point_flag, parse_segment_flag,
};
use serde_json::Value;

// The output options every generator shares. (A plain comment: a doc
// comment here would become every generator's about text.)
#[derive(clap::Args, Debug, Clone, Default)]
pub struct Output {
    /// Write the table here (CSV or JSON by extension); CSV on stdout when absent.
    #[arg(short = 'o', long = "output", value_name = "FILE.csv|json", value_parser = crate::paths::table, value_hint = clap::ValueHint::FilePath)]
    pub output: Option<PathBuf>,
    /// Also plot the table (SVG or PNG by extension).
    #[arg(long, value_name = "FILE.svg|png", value_parser = crate::paths::picture, value_hint = clap::ValueHint::FilePath)]
    pub plot: Option<PathBuf>,
    /// Write only the `master,slave` columns.
    #[arg(long)]
    pub minimal: bool,
}

/// `ecam table gen NAME …`: the generator chosen, the parameters its flags
/// set, its `--params` file and the output options. The flags are built
/// from the generator's [`schema`] fields, one per field, named after its
/// key.
#[derive(Debug)]
pub struct GenCommand {
    generator: &'static Schema,
    flags: Values,
    params: Option<PathBuf>,
    output: Output,
}

impl GenCommand {
    /// The output options of whichever generator was chosen.
    pub fn output(&self) -> &Output {
        &self.output
    }
}

impl clap::FromArgMatches for GenCommand {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let (name, sub) = matches
            .subcommand()
            .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::MissingSubcommand))?;
        let generator = schema::find(name)
            .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::InvalidSubcommand))?;
        let mut flags = Values::new();
        for field in generator.fields {
            if let Some(value) = flag_value(field, sub) {
                flags.insert(field.key, value);
            }
        }
        Ok(Self {
            generator,
            flags,
            params: sub.get_one::<PathBuf>(PARAMS_ID).cloned(),
            output: Output::from_arg_matches(sub)?,
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Subcommand for GenCommand {
    fn augment_subcommands(command: clap::Command) -> clap::Command {
        schema::GENERATORS
            .iter()
            .fold(command, |command, g| command.subcommand(subcommand(g)))
    }

    fn augment_subcommands_for_update(command: clap::Command) -> clap::Command {
        Self::augment_subcommands(command)
    }

    fn has_subcommand(name: &str) -> bool {
        schema::find(name).is_some()
    }
}

const PARAMS_ID: &str = "params";

/// The subcommand of generator `g`: a flag per field, `--params` and the output options.
fn subcommand(g: &'static Schema) -> clap::Command {
    let defaults = default_values(g);
    let keys: Vec<String> = g.fields.iter().map(|f| format!("`{}`", f.key)).collect();
    let command = g.fields.iter().fold(
        clap::Command::new(g.name).about(g.about).aliases(g.aliases),
        |command, field| command.arg(flag(field, defaults.get(field.key))),
    );
    let command = command.arg(
        Arg::new(PARAMS_ID)
            .long(PARAMS_ID)
            .value_name("FILE.toml")
            .value_hint(clap::ValueHint::FilePath)
            .value_parser(clap::value_parser!(PathBuf))
            .help(format!(
                "Read parameters from a TOML file ({})",
                keys.join(", ")
            )),
    );
    Output::augment_args(command)
}

/// The flag of `field`; its help ends with the default, where there is one to show.
fn flag(field: &'static Field, default: Option<&Value>) -> Arg {
    let mut help = match field.param {
        Some(p) => format!("{p}: {}", field.help),
        None => upper_first(field.help),
    };
    if let FieldKind::Integer { min, max, .. } = field.kind {
        if min > i64::from(i32::MIN) && max < i64::from(i32::MAX) {
            help.push_str(&format!(", {min}–{max}"));
        }
    }
    let shown = match (field.shown_default, default) {
        (Some(text), _) if field.kind != FieldKind::Text => Some(text.to_string()),
        (None, Some(Value::Number(n))) => Some(n.to_string()),
        (None, Some(Value::String(s))) => Some(s.clone()),
        _ => None,
    };
    if let Some(shown) = shown.filter(|s| !s.is_empty()) {
        help.push_str(&format!(" (default {shown})"));
    }
    let arg = Arg::new(field.key)
        .long(field.flag())
        .help(help)
        .allow_hyphen_values(field.kind.allows_negative());
    match field.kind {
        // The schema's range (the core's limits) is clap's too: a value
        // outside it is a usage error naming the range.
        FieldKind::Integer { storage, min, max } => {
            let arg = arg.value_name(field.key.to_uppercase());
            match storage {
                Storage::I64 => arg.value_parser(clap::value_parser!(i64).range(min..=max)),
                Storage::U32 => arg.value_parser(clap::value_parser!(u32).range(min..=max)),
                Storage::U16 => arg.value_parser(clap::value_parser!(u16).range(min..=max)),
                Storage::Usize => arg.value_parser(clap::value_parser!(usize)),
            }
        }
        FieldKind::Number => arg
            .value_name(field.key.to_uppercase())
            .value_parser(parse_number),
        // Checked here, so a wrong choice is a usage error (exit 2) like
        // any other bad flag value; completions offer the names.
        FieldKind::Choice(_) => arg
            .value_name(field.key.to_uppercase())
            .value_parser(Choice(field)),
        FieldKind::Text => arg.value_name(field.key.to_uppercase()),
        FieldKind::Switch => arg.action(ArgAction::SetTrue),
        FieldKind::KeyPoints => arg
            .value_name("M:S[:CURVE[:RES]]")
            .action(ArgAction::Append)
            .value_parser(parse_key),
        FieldKind::Point => arg
            .value_name("M:S[:V[:A[:J]]]")
            .allow_hyphen_values(true)
            .value_parser(parse_point_flag),
        FieldKind::Segments => arg
            .value_name("LAW:M:S[:V[:A[:J[:POINTS]]]]")
            .allow_hyphen_values(true)
            .action(ArgAction::Append)
            .value_parser(parse_segment_flag),
    }
}

/// A choice field's flag value: a name (or code, or alias) the field
/// accepts, as its name; completions and `--help` list the names.
#[derive(Clone, Copy)]
struct Choice(&'static Field);

impl clap::builder::TypedValueParser for Choice {
    type Value = String;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&Arg>,
        value: &std::ffi::OsStr,
    ) -> Result<String, clap::Error> {
        let text = value.to_string_lossy();
        self.0
            .choice(text.trim())
            .map(str::to_string)
            .ok_or_else(|| {
                let mut err = clap::Error::new(clap::error::ErrorKind::InvalidValue).with_cmd(cmd);
                use clap::error::{ContextKind, ContextValue};
                if let Some(arg) = arg {
                    err.insert(
                        ContextKind::InvalidArg,
                        ContextValue::String(arg.to_string()),
                    );
                }
                err.insert(
                    ContextKind::InvalidValue,
                    ContextValue::String(text.into_owned()),
                );
                if let FieldKind::Choice(names) = self.0.kind {
                    let names = names.iter().map(|n| n.to_string()).collect();
                    err.insert(ContextKind::ValidValue, ContextValue::Strings(names));
                }
                err
            })
    }

    fn possible_values(
        &self,
    ) -> Option<Box<dyn Iterator<Item = clap::builder::PossibleValue> + '_>> {
        match self.0.kind {
            FieldKind::Choice(names) => Some(Box::new(
                names.iter().map(|n| clap::builder::PossibleValue::new(*n)),
            )),
            _ => None,
        }
    }
}

fn upper_first(text: &str) -> String {
    let mut chars = text.chars();
    chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}

/// The value a flag gave, if it was given.
fn flag_value(field: &Field, matches: &ArgMatches) -> Option<Param> {
    let key = field.key;
    match field.kind {
        FieldKind::Integer { storage, .. } => match storage {
            Storage::I64 => matches.get_one::<i64>(key).map(|&v| Param::Int(v)),
            Storage::U32 => matches.get_one::<u32>(key).map(|&v| Param::Int(v.into())),
            Storage::U16 => matches.get_one::<u16>(key).map(|&v| Param::Int(v.into())),
            Storage::Usize => matches
                .get_one::<usize>(key)
                .map(|&v| Param::Uint(v as u64)),
        },
        FieldKind::Number => matches.get_one::<f64>(key).map(|&v| Param::Float(v)),
        FieldKind::Choice(_) | FieldKind::Text => matches
            .get_one::<String>(key)
            .map(|v| Param::Text(v.clone())),
        FieldKind::Switch => matches.get_flag(key).then_some(Param::Bool(true)),
        FieldKind::KeyPoints => {
            let keys: Vec<KeyPoint> = matches
                .get_many::<KeyPoint>(key)
                .map(|k| k.copied().collect())
                .unwrap_or_default();
            (!keys.is_empty()).then_some(Param::Keys(keys))
        }
        FieldKind::Point => matches
            .get_one::<InterpolationPoint>(key)
            .map(|p| Param::Point(*p)),
        FieldKind::Segments => {
            let segments: Vec<SegmentSpec> = matches
                .get_many::<SegmentSpec>(key)
                .map(|s| s.copied().collect())
                .unwrap_or_default();
            (!segments.is_empty()).then_some(Param::Segments(segments))
        }
    }
}

/// Generates the table `command` asks for.
///
/// # Errors
/// Unreadable parameter files, bad parameters (with the PLC's error code).
pub fn run(command: &GenCommand) -> anyhow::Result<Generated> {
    let mut values = match &command.params {
        None => Values::new(),
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read parameter file {}", path.display()))?;
            ecam_design::read_toml(command.generator, &text)
                .with_context(|| format!("in parameter file {}", path.display()))?
        }
    };
    values.extend(command.flags.clone());
    Ok(ecam_design::generate(command.generator, values)?)
}

/// clap value parser for numeric flags that accept arithmetic.
fn parse_number(text: &str) -> Result<f64, String> {
    ecam_design::number(text).map_err(|e| format!("{e:#}"))
}
