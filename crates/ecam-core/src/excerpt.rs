//! How a message quotes what a user typed or a file held: at most
//! [`EXCERPT_CHARS`] characters of it, so that a 10 MB field or a 4 KB
//! expression gives a one-line message, never the input itself. Every
//! reader's message quotes through [`excerpt`]; where the input was (line,
//! row, column, key) the message says beside it.
//!
//! ```
//! use ecam_core::excerpt::excerpt;
//!
//! assert_eq!(format!("{:?}", excerpt("1.5")), "\"1.5\"");
//! let field = "9".repeat(10_000_000);
//! let quoted = format!("slave {:?} is not an integer", excerpt(&field));
//! assert_eq!(quoted.len(), 78);
//! assert!(quoted.ends_with("99…\" (10000000 bytes) is not an integer"));
//! ```

use core::fmt;

/// Most characters of an input a message quotes.
pub const EXCERPT_CHARS: usize = 32;

/// `text` as messages quote it: whole when it has at most
/// [`EXCERPT_CHARS`] characters, otherwise its first ones followed by `…`
/// and, after the quote, the input's length in bytes. `{}` writes it bare
/// (for backtick quoting), `{:?}` in double quotes with escapes.
pub fn excerpt(text: &str) -> Excerpt<'_> {
    Excerpt { text }
}

/// An input cut for a message (see [`excerpt`]).
#[derive(Clone, Copy)]
pub struct Excerpt<'a> {
    text: &'a str,
}

impl<'a> Excerpt<'a> {
    /// The part quoted, and whether the input was cut.
    fn shown(&self) -> (&'a str, bool) {
        match self.text.char_indices().nth(EXCERPT_CHARS) {
            Some((end, _)) => (&self.text[..end], true),
            None => (self.text, false),
        }
    }
}

impl fmt::Display for Excerpt<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.shown() {
            (shown, false) => f.write_str(shown),
            (shown, true) => write!(f, "{shown}… ({} bytes)", self.text.len()),
        }
    }
}

impl fmt::Debug for Excerpt<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (shown, cut) = self.shown();
        f.write_str("\"")?;
        for c in shown.chars() {
            write!(f, "{}", c.escape_debug())?;
        }
        if cut {
            write!(f, "…\" ({} bytes)", self.text.len())
        } else {
            f.write_str("\"")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::format;
    use alloc::string::String;

    #[test]
    fn short_inputs_are_quoted_whole() {
        assert_eq!(format!("{}", excerpt("x+1")), "x+1");
        assert_eq!(format!("{:?}", excerpt("a\"b\n")), "\"a\\\"b\\n\"");
        let exactly: String = "é".repeat(EXCERPT_CHARS);
        assert_eq!(format!("{}", excerpt(&exactly)), exactly);
    }

    #[test]
    fn long_inputs_are_cut_at_a_character_and_give_their_length() {
        let long: String = "é".repeat(100);
        let shown = format!("{}", excerpt(&long));
        assert_eq!(shown, format!("{}… (200 bytes)", "é".repeat(EXCERPT_CHARS)));
        let quoted = format!("{:?}", excerpt(&long));
        assert_eq!(
            quoted,
            format!("\"{}…\" (200 bytes)", "é".repeat(EXCERPT_CHARS))
        );
    }
}
