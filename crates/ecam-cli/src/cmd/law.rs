//! `ecam law`: the normalised motion laws of `ecam_core::law`.
//!
//! The output is a **contract** (see `docs/cli.md`): `--list` prints one law
//! name per line; `ecam law NAME` prints CSV `u,s,v,a,j` with `--points`
//! rows spread evenly over u ∈ [0, 1], both ends included.

use std::io::Write;

use anyhow::bail;
use ecam_core::law::MotionLaw;

/// Arguments of `ecam law`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["list", "name"])))]
pub struct Args {
    /// Print the name of every motion law, one per line.
    #[arg(long)]
    pub list: bool,
    /// The law to print as CSV (see `ecam law --list`).
    #[arg(value_parser = parse_law)]
    pub name: Option<MotionLaw>,
    /// Number of rows, both ends of u ∈ [0, 1] included (at least 2).
    #[arg(long, default_value_t = 1001)]
    pub points: usize,
}

/// Runs `ecam law`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
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

/// clap value parser: a law by name, so a wrong one is a usage error (exit 2).
fn parse_law(name: &str) -> Result<MotionLaw, String> {
    MotionLaw::from_name(name.trim()).ok_or_else(|| {
        let names: Vec<&str> = MotionLaw::ALL.iter().map(|l| l.name()).collect();
        format!("unknown motion law {name:?}; use {}", names.join(", "))
    })
}

/// Writes `points` rows of `law` as CSV `u,s,v,a,j`.
fn write_csv(law: MotionLaw, points: usize, out: &mut impl Write) -> anyhow::Result<()> {
    if points > ecam_core::limits::MAX_TABLE_POINTS {
        bail!(
            "--points {points} is above the limit of {} points",
            ecam_core::limits::MAX_TABLE_POINTS
        );
    }
    if points < 2 {
        bail!("--points must be at least 2 (both ends of u = 0..1), got {points}");
    }
    writeln!(out, "u,s,v,a,j")?;
    let last = (points - 1) as f64;
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
    fn refuses_fewer_than_two_points() {
        let mut buf = Vec::new();
        assert!(write_csv(MotionLaw::Cycloid, 1, &mut buf).is_err());
    }
}
