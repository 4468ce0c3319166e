//! Plots that read at a glance (issue 28), checked on the SVG `ecam`
//! writes: impulse labels apart and inside the picture, legends in the
//! strip above each panel (never on the data), a periodic cam's seam jump
//! drawn as an impulse (not a velocity spike), the font an SVG names.

use crate::common::{ecam, ok, scratch_dir};

/// A `<text>` of an SVG: x, y, font size and content.
#[derive(Debug)]
struct Text {
    x: f64,
    y: f64,
    size: f64,
    text: String,
}

fn attr(tag: &str, name: &str) -> Option<f64> {
    let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
    tag[at..].split('"').next()?.parse().ok()
}

fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let (tag, rest) = t.split_once('>')?;
            Some(Text {
                x: attr(tag, "x")?,
                y: attr(tag, "y")?,
                size: attr(tag, "font-size")?,
                text: rest.split("</text>").next()?.trim().to_string(),
            })
        })
        .collect()
}

/// The picture's layout (`ecam_plot`): a 40-pixel title, then panels of
/// 260 pixels, each opening with a 20-pixel legend strip.
const TITLE: f64 = 40.0;
const PANEL: f64 = 260.0;
const STRIP: f64 = 20.0;

#[test]
fn impulse_labels_never_overlap_and_legends_stay_off_the_data() {
    let dir = scratch_dir("readable");
    let svg = dir.join("saw.svg");
    ok(ecam(&[
        "table",
        "gen",
        "fly-saw",
        "--params",
        "../../examples/tables/fly-saw.toml",
        "--plot",
        svg.to_str().unwrap(),
        "-q",
    ]));
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("font-family=\"DejaVu Sans, sans-serif\""));
    let all = texts(&svg);
    let labels: Vec<&Text> = all.iter().filter(|t| t.text.starts_with('Δ')).collect();
    // The saw's eight acceleration steps, each labelled (room enough).
    assert_eq!(labels.len(), 8, "{labels:?}");
    // An upper bound of each label's width (DejaVu Sans is under 0.62 em a
    // character) must not reach the next label on the same line.
    let width = |t: &Text| 0.62 * t.size * t.text.chars().count() as f64;
    for (i, a) in labels.iter().enumerate() {
        assert!(
            a.x >= 0.0 && a.x + width(a) <= 1100.0,
            "{a:?} leaves the picture"
        );
        for b in &labels[i + 1..] {
            let same_line = (a.y - b.y).abs() < a.size.max(b.size);
            let apart = a.x + width(a) <= b.x || b.x + width(b) <= a.x;
            assert!(!same_line || apart, "{a:?} overlaps {b:?}");
        }
    }
    // Legends: each name in the strip above its panel.
    for name in [
        "design",
        "table points",
        "impulse: acceleration step (pulses/count²)",
    ] {
        for t in all.iter().filter(|t| t.text == name) {
            let into_panel = (t.y - TITLE).rem_euclid(PANEL);
            assert!(
                into_panel < STRIP,
                "the legend {name} at y {} is on the data",
                t.y
            );
        }
    }
}

#[test]
fn a_seam_jump_is_an_impulse_not_a_velocity_spike() {
    let dir = scratch_dir("readable-jump");
    let scenario = dir.join("knife.toml");
    // A rotary knife as a periodic cam: it jumps back a revolution at
    // every seam.
    let text = std::fs::read_to_string("../../examples/scenarios/rotary-knife-switch.toml")
        .unwrap()
        .replace("kind = \"repeat\"", "kind = \"periodic\"");
    std::fs::write(&scenario, text).unwrap();
    let svg = dir.join("knife.svg");
    ok(ecam(&[
        "simulate",
        scenario.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]));
    let svg = std::fs::read_to_string(&svg).unwrap();
    let all = texts(&svg);
    assert!(all.iter().any(|t| t.text == "seam jump (pulses)"), "legend");
    let jumps: Vec<&Text> = all.iter().filter(|t| t.text.starts_with("jump ")).collect();
    assert!(
        !jumps.is_empty() && jumps.iter().all(|t| t.text == "jump -1000"),
        "{jumps:?}"
    );
    // The velocity axis is the knife's speed (up to about 17 000 pulses/s
    // at 10 kHz × 5/3), not a spike of a thousand pulses in one tick.
    let third_panel = |t: &&Text| (TITLE + 2.0 * PANEL..TITLE + 3.0 * PANEL).contains(&t.y);
    let ticks: Vec<f64> = all
        .iter()
        .filter(third_panel)
        .filter_map(|t| t.text.parse::<f64>().ok())
        .collect();
    let top = ticks.iter().copied().fold(f64::MIN, f64::max);
    assert!(
        (15_000.0..25_000.0).contains(&top),
        "velocity axis up to {top}: {ticks:?}"
    );
}
