//! The font plotters draws its labels with.
//!
//! The workspace builds plotters without its system-font loader (`ttf` pulls
//! in native font libraries), so labels are drawn with `ab_glyph` from a
//! TrueType file that we register once. `ECAM_FONT` names one explicitly
//! (`ECAM_FONT=none` for no text); otherwise a few common system locations
//! are tried. Without any font the plots are still drawn, only without text,
//! and the caller says so.

use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

/// Family name the plots ask plotters for.
pub const FAMILY: &str = "sans-serif";

/// Common places of a sans-serif TrueType font (Debian/Ubuntu, Fedora, Arch,
/// macOS, Windows).
const CANDIDATES: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/liberation-sans/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
    "/Library/Fonts/Arial.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

/// Registers a font for [`FAMILY`] on first use; true when labels can be drawn.
pub fn available() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(register_first)
}

fn register_first() -> bool {
    let explicit = std::env::var_os("ECAM_FONT").map(std::path::PathBuf::from);
    // `ECAM_FONT=none` draws without text, as on a machine without fonts.
    if explicit.as_deref() == Some(std::path::Path::new("none")) {
        return false;
    }
    let paths = explicit
        .into_iter()
        .chain(CANDIDATES.iter().map(std::path::PathBuf::from));
    for path in paths {
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        // plotters keeps `&'static` font data; one font per process is a
        // bounded, deliberate leak.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        if register_font(FAMILY, FontStyle::Normal, bytes).is_ok() {
            return true;
        }
    }
    false
}
