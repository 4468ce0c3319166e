//! The font plotters draws its labels with: DejaVu Sans, embedded.
//!
//! The workspace builds plotters without its system-font loader (`ttf` pulls
//! in native font libraries), so labels are drawn with `ab_glyph` from
//! TrueType bytes registered once. The bytes are compiled in (see
//! `fonts/LICENSE-DejaVu.txt` for the font's licence): a PNG is drawn the
//! same on every machine, without a font installed. An SVG keeps its text
//! as text (searchable, sharp at any size) and names the font: a viewer
//! with DejaVu Sans draws it as the PNG is, another falls back to its own
//! sans-serif (labels are laid out with room to spare for that).

use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

/// Family name the plots ask plotters for, and the font list an SVG names:
/// DejaVu Sans, else the viewer's sans-serif.
pub const FAMILY: &str = "DejaVu Sans, sans-serif";

/// DejaVu Sans 2.37 (Bitstream Vera licence, DejaVu changes public domain):
/// it covers the symbols the labels use (², ³, ±, Δ, µ).
static DEJAVU_SANS: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

/// Registers the embedded font for [`FAMILY`] on first use; true when
/// labels can be drawn (false only if the embedded bytes failed to parse,
/// which the unit test below rules out).
pub fn available() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok())
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_embedded_font_registers() {
        assert!(super::available());
    }
}
