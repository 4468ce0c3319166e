//! The user guide cannot drift (issue 28): every `ecam` command README.md
//! and the pages of docs/ show is run, in page order, in a scratch folder
//! that sees the repository's `examples/`; it must succeed, and where the
//! page shows its output (`$ ecam …` followed by lines, in a `text` block)
//! the output must be what the page shows. A line `...` stands for any
//! lines; a line ending in `...` for any line starting with what precedes
//! it.
//!
//! A few commands cannot run here, each for a reason listed in
//! [`CANNOT_RUN`]; a servers' command runs until it has printed its
//! addresses (on free ports), then stops.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Commands shown but not run, and why (matched by their start).
const CANNOT_RUN: [(&str, &str); 3] = [
    (
        "ecam ethercat emulate",
        "answers frames on a network interface (docs/ethercat.md tests it on veth pairs)",
    ),
    (
        "ecam ethercat run examples/ethercat/rotary-knife.toml --cycles 3000",
        "needs the interface its configuration names",
    ),
    ("ecam completions zsh", "writes into the user's home"),
];

/// One command a page shows, and the output it shows for it, if any.
#[derive(Debug)]
struct Shown {
    page: String,
    line: usize,
    command: String,
    output: Option<Vec<String>>,
}

/// The commands of `text`'s code blocks (not rust, toml, json, python).
fn commands(page: &str, text: &str) -> Vec<Shown> {
    let mut shown = Vec::new();
    let mut in_block: Option<String> = None;
    let mut pending: Option<Shown> = None;
    let mut continued = String::new();
    for (i, line) in text.lines().enumerate() {
        if let Some(fence) = line.trim_start().strip_prefix("```") {
            match in_block.take() {
                Some(_) => shown.extend(pending.take()),
                None => in_block = Some(fence.trim().to_string()),
            }
            continue;
        }
        let Some(lang) = &in_block else { continue };
        if ["rust", "toml", "json", "python"].contains(&lang.as_str()) {
            continue;
        }
        let trimmed = line.trim();
        let start = trimmed
            .strip_prefix("$ ")
            .filter(|_| lang == "text")
            .or_else(|| (lang != "text").then_some(trimmed))
            .map(|c| {
                c.strip_prefix("cargo run --release -p ecam-cli -- ")
                    .map_or_else(|| c.to_string(), |rest| format!("ecam {rest}"))
            })
            .filter(|c| c.starts_with("ecam ") || !continued.is_empty());
        match start {
            Some(command) => {
                shown.extend(pending.take());
                let command = format!("{continued}{command}");
                if let Some(head) = command.strip_suffix('\\') {
                    continued = format!("{} ", head.trim_end());
                    continue;
                }
                continued.clear();
                pending = Some(Shown {
                    page: page.to_string(),
                    line: i + 1,
                    command,
                    output: (lang == "text").then(Vec::new),
                });
            }
            None => {
                if let Some(Shown {
                    output: Some(out), ..
                }) = pending.as_mut()
                {
                    out.push(line.trim_end().to_string());
                }
            }
        }
    }
    shown
}

/// The words of a command line as a shell splits them: quotes grouped,
/// a `#` comment dropped.
fn words(command: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut quote: Option<char> = None;
    let mut started = false;
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                started = true;
            }
            (None, '#') if !started => break,
            (None, c) if c.is_whitespace() => {
                if started {
                    words.push(std::mem::take(&mut word));
                    started = false;
                }
            }
            (None, c) => {
                word.push(c);
                started = true;
            }
        }
    }
    if started {
        words.push(word);
    }
    words
}

/// Whether `actual` is what the page shows.
fn matches(shown: &[String], actual: &[&str]) -> bool {
    let (mut s, mut a) = (0, 0);
    while s < shown.len() {
        let want = shown[s].as_str();
        if want.trim() == "..." {
            // Any lines, up to one that matches the next shown line.
            let Some(next) = shown.get(s + 1) else {
                return true;
            };
            while a < actual.len() && !line_matches(next, actual[a]) {
                a += 1;
            }
            s += 1;
            continue;
        }
        match actual.get(a) {
            Some(got) if line_matches(want, got) => {
                s += 1;
                a += 1;
            }
            _ => return false,
        }
    }
    a == actual.len()
}

fn line_matches(want: &str, got: &str) -> bool {
    match want.strip_suffix("...") {
        Some(head) => got.starts_with(head.trim_end_matches([',', ' '])),
        None => want.trim_end() == got.trim_end(),
    }
}

/// Runs a server's command until it prints its two addresses.
fn serve(mut args: Vec<String>, dir: &Path) -> Result<(), String> {
    args.extend(["--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"].map(String::from));
    let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(&args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| e.to_string())?;
    let stdout = child.stdout.take().ok_or("no stdout")?;
    let lines: Vec<String> = BufReader::new(stdout)
        .lines()
        .take(2)
        .map_while(Result::ok)
        .collect();
    let _ = child.kill();
    let _ = child.wait();
    match lines.as_slice() {
        [m, h] if m.starts_with("modbus ") && h.starts_with("http ") => Ok(()),
        other => Err(format!("printed {other:?}")),
    }
}

#[test]
fn every_command_the_docs_show_runs_and_prints_what_they_show() {
    let dir = crate::common::scratch_dir("docs-commands");
    std::os::unix::fs::symlink(root().join("examples"), dir.join("examples")).unwrap();
    let mut pages = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    let (mut ran, mut compared) = (0, 0);
    let mut failures = Vec::new();
    for page in &pages {
        let name = page
            .strip_prefix(root())
            .unwrap_or(page)
            .display()
            .to_string();
        let text = std::fs::read_to_string(page).unwrap();
        for shown in commands(&name, &text) {
            let at = format!("{}:{}: {}", shown.page, shown.line, shown.command);
            // A synopsis (`ecam pmd run SCRIPT [--define NAME=VALUE]...`)
            // shows a form, not a command.
            if shown.command.contains("...") || shown.command.contains(" [") {
                continue;
            }
            if CANNOT_RUN.iter().any(|(c, _)| shown.command.starts_with(c)) {
                continue;
            }
            let args: Vec<String> = words(&shown.command).into_iter().skip(1).collect();
            let args: Vec<String> = args
                .into_iter()
                .take_while(|a| a != ">" && a != "&")
                .collect();
            ran += 1;
            if args.first().is_some_and(|a| a == "serve") {
                if let Err(e) = serve(args, &dir) {
                    failures.push(format!("{at}\n  {e}"));
                }
                continue;
            }
            let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
                .args(&args)
                .current_dir(&dir)
                .output()
                .unwrap();
            if !out.status.success() {
                failures.push(format!(
                    "{at}\n  failed: {}",
                    String::from_utf8_lossy(&out.stderr).trim()
                ));
                continue;
            }
            if let Some(expected) = shown.output.filter(|o| !o.is_empty()) {
                compared += 1;
                let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
                let actual: Vec<&str> = stdout.lines().collect();
                if !matches(&expected, &actual) {
                    failures.push(format!(
                        "{at}\n  the page shows:\n{}\n  it prints:\n{}",
                        expected.join("\n"),
                        stdout.trim_end()
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran > 30 && compared >= 7, "ran {ran}, compared {compared}");
}

#[test]
fn the_shown_output_rules_hold() {
    let shown: Vec<String> = ["a", "...", "d", "note: x, ..."].map(String::from).to_vec();
    assert!(matches(&shown, &["a", "b", "c", "d", "note: x, y"]));
    assert!(!matches(&shown, &["a", "d"]));
    assert_eq!(
        words(r#"ecam table gen fly-saw --ratio "3*pi" -o t.csv  # forward"#),
        [
            "ecam", "table", "gen", "fly-saw", "--ratio", "3*pi", "-o", "t.csv"
        ]
    );
    let page = "```text\n$ ecam law --list\nconstant-velocity\n```\n```sh\necam table show \\\n    t.csv\n```\n";
    let c = commands("p", page);
    assert_eq!(c.len(), 2);
    assert_eq!(
        c[0].output.as_deref(),
        Some(&["constant-velocity".to_string()][..])
    );
    assert_eq!(c[1].command, "ecam table show t.csv");
}
