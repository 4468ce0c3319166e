//! The `[table]` of a scenario: where the cam comes from.
//!
//! Exactly one source key: `points`, `uniform` (with `counts`), `file`,
//! `expr` (with `from`, `to`, `points`) or `generator` (with that
//! generator's parameters, as `ecam table gen` takes them).

use std::path::{Path, PathBuf};

use ecam_core::budget::Budget;
use ecam_core::table::UniformTable;
use ecam_core::{CamCurve, PointTable};
use serde::Deserialize;

use crate::error::TableSourceError;
use crate::generate;

const SOURCES: [&str; 5] = ["points", "uniform", "file", "expr", "generator"];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Points {
    points: Vec<[i64; 2]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Uniform {
    uniform: Vec<i64>,
    counts: i64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    file: String,
}

/// Builds the cam a scenario's `[table]` describes; `base` is the folder
/// relative table files are in.
///
/// # Errors
/// No or several source keys, keys that do not belong to the source, or a
/// table the core refuses.
pub fn load(table: &toml::Table, base: &Path) -> Result<Box<dyn CamCurve>, TableSourceError> {
    load_within(table, base, &mut Budget::per_run())
}

/// As [`load`], taking a generator's or an expression's work from
/// `budget` (a scenario's tables and its run share one).
///
/// # Errors
/// As [`load`]; the budget used up.
pub fn load_within(
    table: &toml::Table,
    base: &Path,
    budget: &mut Budget,
) -> Result<Box<dyn CamCurve>, TableSourceError> {
    let given: Vec<&str> = SOURCES
        .iter()
        .copied()
        .filter(|k| table.contains_key(*k))
        .collect();
    // `expr` also has a `points` key (the sample count).
    let source = match given.as_slice() {
        [one] => *one,
        ["points", "expr"] => "expr",
        [] => return Err(TableSourceError::NoSource { sources: &SOURCES }),
        many => {
            return Err(TableSourceError::ManySources {
                found: many.to_vec(),
            });
        }
    };
    let value = toml::Value::Table(table.clone());
    Ok(match source {
        "points" => {
            let p: Points = value.try_into().map_err(TableSourceError::Keys)?;
            let pairs: Vec<(i64, i64)> = p.points.iter().map(|&[m, s]| (m, s)).collect();
            Box::new(PointTable::from_pairs(&pairs).map_err(TableSourceError::Table)?)
        }
        "uniform" => {
            let u: Uniform = value.try_into().map_err(TableSourceError::Keys)?;
            Box::new(UniformTable::new(u.uniform, u.counts).map_err(TableSourceError::Table)?)
        }
        "file" => {
            let f: File = value.try_into().map_err(TableSourceError::Keys)?;
            let path = resolve(base, &f.file);
            ecam_core::io::read(&path)
                .map_err(TableSourceError::File)?
                .into_curve()
        }
        // Exactly `ecam table gen function`'s keys and defaults (from 0,
        // to 36000, 361 points), as docs/simulate.md promises.
        "expr" => Box::new(
            generate::from_toml_within("function", table.clone(), budget)
                .map_err(TableSourceError::Generate)?
                .table,
        ),
        _ => {
            let mut params = table.clone();
            let name = params
                .remove("generator")
                .and_then(|v| v.as_str().map(str::to_string))
                .ok_or(TableSourceError::GeneratorName)?;
            Box::new(
                generate::from_toml_within(&name, params, budget)
                    .map_err(TableSourceError::Generate)?
                    .table,
            )
        }
    })
}

/// Resolves a table file path written in a scenario against its folder.
pub fn resolve(base: &Path, file: &str) -> PathBuf {
    let p = PathBuf::from(file);
    if p.is_absolute() { p } else { base.join(p) }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn table(text: &str) -> toml::Table {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn uniform_tables_follow_document_002() {
        let t = load(
            &table("uniform = [0, 100, 200]\ncounts = 100"),
            Path::new("."),
        )
        .unwrap();
        assert_eq!(t.master_last(), 100);
        assert_eq!(t.stroke(), 200);
    }

    #[test]
    fn one_source_only() {
        let err = load(
            &table("uniform = [0, 1]\ncounts = 10\nfile = \"a.csv\""),
            Path::new("."),
        )
        .err()
        .unwrap();
        assert!(err.to_string().contains("only one"));
        assert!(load(&table("counts = 10"), Path::new(".")).is_err());
    }

    #[test]
    fn stray_keys_are_refused() {
        assert!(
            load(
                &table("points = [[0, 0], [1, 1]]\ncounts = 3"),
                Path::new(".")
            )
            .is_err()
        );
    }

    #[test]
    fn core_json_files_of_any_kind() {
        let dir = std::env::temp_dir().join(format!("ecam-table-source-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("u.json"),
            r#"{"kind": "uniform", "values": [0, 100, 200], "cam_counts": 100}"#,
        )
        .unwrap();
        let t = load(&table("file = \"u.json\""), &dir).unwrap();
        assert_eq!(t.stroke(), 200);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn expressions_take_the_generators_defaults() {
        let t = load(&table("expr = \"x/36\""), Path::new(".")).unwrap();
        assert_eq!(t.master_last(), 36000);
        assert_eq!(t.slave_last(), 1000);
        assert!(load(&table("expr = \"x\"\ncolour = 1"), Path::new(".")).is_err());
    }

    #[test]
    fn a_segment_cam_from_a_scenario_table() {
        let t = load(
            &table(
                "generator = \"segments\"\nresolution = 20\ncontinuous = true\n\
                 [start]\nmaster = 0\nslave = 0\nvelocity = \"1/2\"\n\
                 [[segment]]\nlaw = \"constant-velocity\"\nmaster = 100\nslave = 50\n\
                 [[segment]]\nlaw = \"vv-cycloid\"\nmaster = 1000\nslave = 400\n",
            ),
            Path::new("."),
        )
        .unwrap();
        assert_eq!((t.master_last(), t.slave_last()), (1000, 400));
    }

    #[test]
    fn expressions_sample_the_master() {
        let t = load(
            &table("expr = \"2*x\"\nfrom = 0\nto = 100\npoints = 11"),
            Path::new("."),
        )
        .unwrap();
        assert_eq!(t.slave_last(), 200);
    }
}
