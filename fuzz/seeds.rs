//! The stable side of the fuzz targets: the seed corpus of a target
//! (`fuzz/corpus/NAME/`) and proptest strategies for arbitrary bytes and
//! near-valid inputs (seeds with a few edits), so `cargo test` runs each
//! crate's `fuzz` harnesses on stable Rust.
//!
//! Included by each owning crate's `tests/it/fuzz.rs` with
//! `#[path = "../../../../fuzz/seeds.rs"] mod seeds;`: one copy of the
//! code, no crate to depend on.
#![allow(dead_code)]

use std::path::PathBuf;

use proptest::prelude::*;
use proptest::sample::{Index, select};

/// Fragments spliced into seeds: numbers at and past the edges of the
/// integer and float types, separators and brackets of the formats read.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "1",
    "65535",
    "65536",
    "-32769",
    "2147483647",
    "2147483648",
    "-2147483649",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775808",
    "18446744073709551616",
    "99999999999999999999999",
    "1e308",
    "1e309",
    "-1e-320",
    "0.5",
    "NaN",
    "inf",
    "\n",
    "\r\n",
    " ",
    ",",
    ";",
    ":",
    "=",
    "\"",
    "[",
    "]",
    "{",
    "}",
    "#",
    "'",
    "\u{feff}",
    "é",
];

/// The seed inputs of fuzz target `target`, in name order.
///
/// # Panics
/// When the corpus folder cannot be read: the seeds are part of the tests.
pub fn corpus(target: &str) -> Vec<Vec<u8>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no seeds in {}", dir.display());
    files.iter().map(|f| std::fs::read(f).unwrap()).collect()
}

/// Arbitrary bytes, up to 512 of them.
pub fn bytes() -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(any::<u8>(), 0..512)
}

/// One change to a seed.
#[derive(Clone, Debug)]
enum Edit {
    /// Insert a fragment (a [`TOKENS`] one or the target's own).
    Insert(Index, &'static str),
    /// Remove up to this many bytes.
    Delete(Index, usize),
    /// Overwrite a byte.
    Replace(Index, u8),
    /// Copy a stretch of up to 32 bytes elsewhere.
    Copy(Index, Index, usize),
}

fn apply(mut data: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    for edit in edits {
        let len = data.len();
        match edit {
            Edit::Insert(at, text) => {
                let at = at.index(len + 1);
                data.splice(at..at, text.bytes());
            }
            Edit::Delete(at, n) if len > 0 => {
                let at = at.index(len);
                data.drain(at..(at + n).min(len));
            }
            Edit::Replace(at, byte) if len > 0 => {
                let at = at.index(len);
                data[at] = *byte;
            }
            Edit::Copy(from, to, n) if len > 0 => {
                let from = from.index(len);
                let chunk = data[from..(from + n).min(len)].to_vec();
                let to = to.index(len + 1);
                data.splice(to..to, chunk);
            }
            _ => {}
        }
    }
    data
}

/// A seed of `target` with one to eight edits; `tokens` are fragments of
/// the target's language (keywords, device names, keys) to insert besides
/// the common ones.
pub fn near_valid(target: &str, tokens: &'static [&'static str]) -> impl Strategy<Value = Vec<u8>> {
    let words: Vec<&'static str> = TOKENS.iter().chain(tokens).copied().collect();
    let edit = prop_oneof![
        (any::<Index>(), select(words)).prop_map(|(at, t)| Edit::Insert(at, t)),
        (any::<Index>(), 1usize..16).prop_map(|(at, n)| Edit::Delete(at, n)),
        (any::<Index>(), any::<u8>()).prop_map(|(at, b)| Edit::Replace(at, b)),
        (any::<Index>(), any::<Index>(), 1usize..32).prop_map(|(f, t, n)| Edit::Copy(f, t, n)),
    ];
    (
        select(corpus(target)),
        proptest::collection::vec(edit, 1..8),
    )
        .prop_map(|(seed, edits)| apply(seed, &edits))
}
