//! The user guide stays true: files it names exist (examples, and the
//! source files that hold each fact and rule), the README's PLC demo
//! prints what the README says, and the one resolution range (the core's)
//! is the one the pages, the flags and the messages state.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use crate::common::{ecam, ok};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// README.md, packaging/README.md and every page of docs/.
fn pages() -> Vec<(PathBuf, String)> {
    let mut paths = vec![root().join("README.md"), root().join("packaging/README.md")];
    for entry in std::fs::read_dir(root().join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            paths.push(path);
        }
    }
    paths
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect()
}

/// Whether `name` (relative to the root, at most one `*` in its file name)
/// names an existing file or directory.
fn exists(name: &str) -> bool {
    let path = root().join(name);
    let Some((prefix, suffix)) = name.rsplit('/').next().and_then(|f| f.split_once('*')) else {
        return path.exists();
    };
    let Some(dir) = path.parent().filter(|d| d.is_dir()) else {
        return false;
    };
    std::fs::read_dir(dir).unwrap().any(|entry| {
        let file = entry.unwrap().file_name().to_string_lossy().into_owned();
        file.len() >= prefix.len() + suffix.len()
            && file.starts_with(prefix)
            && file.ends_with(suffix)
    })
}

#[test]
fn every_example_file_the_docs_name_exists() {
    let mut named = 0;
    for (page, text) in pages() {
        for (at, _) in text.match_indices("examples/") {
            // The path runs to the first character a path in prose or a
            // command line does not contain.
            let rest = &text[at..];
            let end = rest
                .find(|c: char| c.is_whitespace() || "`)\"',;|]>:".contains(c))
                .unwrap_or(rest.len());
            let name = rest[..end].trim_end_matches('.');
            // `../examples/...` links and bare directory mentions both count;
            // a `*` (`examples/plc/decam_*.il`) must match some file.
            assert!(
                exists(name),
                "{} names {name}, which does not exist",
                page.display()
            );
            named += 1;
        }
    }
    assert!(named > 20, "only {named} example paths found");
}

/// The `code spans` of `text` that name a file or folder of the tree: a
/// path under `crates/` (or a crate's own folder, `ecam-core/src/…`, as
/// docs/architecture.md writes them), or under docs/, fuzz/, scripts/,
/// packaging/ or .ci/. Placeholders (`corpus/NAME/`) are not paths.
fn code_paths(text: &str) -> Vec<String> {
    let roots = [
        "crates/",
        "docs/",
        "fuzz/",
        "scripts/",
        "packaging/",
        ".ci/",
    ];
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| !span.contains(char::is_whitespace) && span.contains('/'))
        .filter(|span| {
            !span.split('/').any(|part| {
                part.len() > 1
                    && part == part.to_uppercase()
                    && part.chars().all(char::is_alphabetic)
            })
        })
        .filter_map(|span| {
            if span.starts_with("ecam-") {
                Some(format!("crates/{span}"))
            } else {
                roots
                    .iter()
                    .any(|r| span.starts_with(r))
                    .then(|| span.to_string())
            }
        })
        .collect()
}

#[test]
fn every_code_path_the_docs_name_exists() {
    let mut named = 0;
    let mut missing = Vec::new();
    for (page, text) in pages() {
        for path in code_paths(&text) {
            if !exists(&path) {
                let page = page.file_name().unwrap_or_default().to_string_lossy();
                missing.push(format!("{page}: {path}"));
            }
            named += 1;
        }
    }
    assert!(missing.is_empty(), "named but missing: {missing:#?}");
    assert!(named > 100, "only {named} code paths found");
}

#[test]
fn the_architecture_page_names_every_file_with_its_path() {
    // "One home per fact" is only useful if each home can be opened as
    // written: a bare `write.rs` could be any crate's.
    let text = std::fs::read_to_string(root().join("docs/architecture.md")).unwrap();
    let bare: Vec<&str> = text
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| span.ends_with(".rs") && !span.contains('/'))
        .collect();
    assert!(
        bare.is_empty(),
        "docs/architecture.md names {bare:?} without a path"
    );
    let paths = code_paths(&text);
    assert!(
        paths
            .iter()
            .any(|p| p == "crates/ecam-core/src/script_line.rs"),
        "{paths:?}"
    );
}

#[test]
fn the_readme_plc_demo_prints_what_the_readme_shows() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let line = readme
        .lines()
        .find(|l| l.starts_with("ecam plc run examples/plc/decam_cyclic.il"))
        .unwrap();
    let args: Vec<&str> = line.split_whitespace().skip(1).collect();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(&args)
        .current_dir(root())
        .output()
        .unwrap();
    let printed = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(
        readme.contains(printed.trim()),
        "README does not show {printed}"
    );
    // It shows motion: the slave is away from 0 and in the sync area.
    let json: serde_json::Value = serde_json::from_str(&printed).unwrap();
    assert_ne!(json["DD2019"], 0);
    assert_eq!(json["Y7"], 1);
}

#[test]
fn one_resolution_range_for_the_cut_generators() {
    use ecam_core::generator::rotary_cut::{MAX_RESOLUTION, MIN_RESOLUTION};
    let range = format!("{MIN_RESOLUTION}–{MAX_RESOLUTION}");
    let cli = std::fs::read_to_string(root().join("docs/cli.md")).unwrap();
    let plc = std::fs::read_to_string(root().join("docs/plc.md")).unwrap();
    let generators = std::fs::read_to_string(root().join("docs/generators.md")).unwrap();
    let p7 = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|l| l.contains("P7"))
            .filter(|l| l.contains("resolution") || l.contains("points"))
            .map(str::to_string)
            .collect()
    };
    for line in p7(&cli).iter().chain(&p7(&plc)) {
        if line.starts_with('|') {
            assert!(line.contains(&range), "{line}");
        }
    }
    assert!(generators.contains(&format!("K100/K101 accept {range}")));
    // The flag's help, its check and the core's message say the same.
    let help = ok(ecam(&["table", "gen", "rotary-cut", "--help"]));
    assert!(
        help.contains(&format!("P7: points in the table, {range}")),
        "{help}"
    );
    let below = (MIN_RESOLUTION - 1).to_string();
    let out = ecam(&["table", "gen", "fly-saw", "--resolution", &below]);
    assert_eq!(out.status.code(), Some(2));
    let dir = crate::common::scratch_dir("docs-resolution");
    let params = dir.join("p.toml");
    std::fs::write(&params, format!("resolution = {below}\n")).unwrap();
    let out = ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--params",
        params.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!("between {MIN_RESOLUTION} and {MAX_RESOLUTION}")),
        "{err}"
    );
}

#[test]
fn bad_choices_and_output_names_are_usage_errors() {
    let dir = crate::common::scratch_dir("docs-usage");
    let xlsx = dir.join("t.xlsx");
    for args in [
        vec!["law", "no-such-law"],
        vec!["table", "gen", "rotary-cut", "--accel", "linear"],
        vec!["table", "gen", "fly-saw", "--placement", "mid-begin"],
        vec!["table", "gen", "s-curve", "--curve", "7"],
        vec!["table", "gen", "s-curve", "--curve", "left"],
        vec!["completions", "tcsh"],
        vec![
            "simulate",
            "../../examples/scenarios/001-repeat.toml",
            "--trace",
            xlsx.to_str().unwrap(),
        ],
        vec!["table", "gen", "keypoints", "-o", xlsx.to_str().unwrap()],
        vec!["table", "gen", "keypoints", "--plot", "p.pdf"],
    ] {
        let out = ecam(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
    assert!(!xlsx.exists(), "nothing is written");
    // Codes and aliases are still choices.
    ok(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--accel",
        "s-type",
        "--placement",
        "4",
    ]));
}

#[test]
fn the_table_show_json_keys_cli_md_lists_are_the_ones_printed() {
    let cli = std::fs::read_to_string(root().join("docs/cli.md")).unwrap();
    let at = cli
        .find("`--json` prints the\nsame as one JSON object (keys `")
        .unwrap();
    let rest = &cli[at..];
    let list = &rest[rest.find("(keys `").unwrap() + 7..];
    let list = &list[..list.find('`').unwrap()];
    let listed: Vec<String> = list
        .split(',')
        .map(|k| k.split_whitespace().collect::<String>())
        .collect();
    let out = ok(ecam(&[
        "table",
        "show",
        "--json",
        "../../examples/tables/doc001.csv",
    ]));
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let printed: Vec<String> = json.as_object().unwrap().keys().cloned().collect();
    let mut sorted = (listed.clone(), printed.clone());
    sorted.0.sort();
    sorted.1.sort();
    assert_eq!(
        sorted.0, sorted.1,
        "cli.md lists {listed:?}, ecam prints {printed:?}"
    );
}

#[test]
fn the_rotary_cut_scenario_example_turns_the_knife_forward() {
    // docs/simulate.md's `[table]` example of a generator, run as the page
    // shows it: a knife adds a revolution per cut, it never jumps back.
    let page = std::fs::read_to_string(root().join("docs/simulate.md")).unwrap();
    let block = page
        .split("```toml\n")
        .find(|b| b.contains("generator = \"rotary-cut\""))
        .and_then(|b| b.split("```").next())
        .unwrap();
    let dir = crate::common::scratch_dir("docs-rotary-scenario");
    let scenario = dir.join("knife.toml");
    std::fs::write(
        &scenario,
        format!("{block}\n[master]\nmoves = [[1.0, 10000]]\n"),
    )
    .unwrap();
    let out = ok(ecam(&["simulate", scenario.to_str().unwrap()]));
    let summary: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(summary["seam_jumps"], 0, "{out}");
    assert_eq!(summary["direction_changes"], 0, "{out}");
    assert!(summary["final_slave"].as_i64().unwrap() > 3000, "{out}");
}
