//! `ecam law`: the normalised motion laws of `ecam_core::law`.
//!
//! The output is a **contract** (see `docs/cli.md`): `--list` prints one law
//! name per line; `ecam law NAME` prints CSV `u,s,v,a,j` with `--points`
//! rows spread evenly over u ∈ [0, 1], both ends included.

use std::io::Write;

use ecam_core::law::MotionLaw;

/// Arguments of `ecam law`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["list", "name"])))]
pub struct Args {
    /// Print the name of every motion law, one per line.
    #[arg(long)]
    pub list: bool,
    /// The law to print as CSV (see `ecam law --list`).
    #[arg(value_parser = law())]
    pub name: Option<MotionLaw>,
    /// Number of rows, both ends of u ∈ [0, 1] included (at least 2).
    #[arg(long, default_value_t = 1001, value_parser = points)]
    pub points: usize,
}

/// Runs `ecam law`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    tracing::debug!("{} rows", args.points);
    if args.list {
        for law in MotionLaw::ALL {
            writeln!(out, "{}", law.name())?;
        }
    } else if let Some(law) = args.name {
        write_csv(law, args.points, &mut out)?;
    }
    out.flush()?;
    Ok(())
}

/// clap value parser: a law by name, so a wrong one is a usage error (exit
/// 2), and completions offer the names.
fn law() -> impl clap::builder::TypedValueParser<Value = MotionLaw> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(MotionLaw::ALL.map(MotionLaw::name))
        .map(|name| MotionLaw::from_name(&name).unwrap_or(MotionLaw::Cycloid))
}

/// `--points`: 2 up to the limit, or a usage error.
fn points(text: &str) -> Result<usize, String> {
    let max = ecam_core::limits::MAX_TABLE_POINTS;
    match text.trim().parse::<usize>() {
        Ok(n) if (2..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "must be a whole number from 2 (both ends of u = 0..1) to the limit of {max} points"
        )),
    }
}

/// Writes `points` rows (at least 2) of `law` as CSV `u,s,v,a,j`.
fn write_csv(law: MotionLaw, points: usize, out: &mut impl Write) -> anyhow::Result<()> {
    writeln!(out, "u,s,v,a,j")?;
    let last = points.saturating_sub(1).max(1) as f64;
    for i in 0..points {
        // The last row is exactly u = 1, not an accumulated sum.
        let u = if i + 1 == points {
            1.0
        } else {
            i as f64 / last
        };
        let k = law.eval(u);
        // `+ 0.0` turns a negative zero into 0: "-0" in a CSV surprises readers.
        writeln!(
            out,
            "{u},{},{},{},{}",
            k.s + 0.0,
            k.v + 0.0,
            k.a + 0.0,
            k.j + 0.0
        )?;
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn csv_has_header_and_both_ends() {
        let mut buf = Vec::new();
        write_csv(MotionLaw::Cycloid, 3, &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[0], "u,s,v,a,j");
        assert!(lines[1].starts_with("0,0,"));
        assert!(lines[3].starts_with("1,1,"));
    }

    #[test]
    fn points_are_two_up_to_the_limit() {
        assert!(points("1").is_err() && points("x").is_err());
        assert_eq!(points("2"), Ok(2));
    }
}
