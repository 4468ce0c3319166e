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

use alloc::string::String;
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

/// Longest line of a message that quotes input through a library's
/// wording (a parser that shows the line it stopped at).
pub const MAX_MESSAGE_LINE: usize = 160;

/// `message` with every quote of the input in it (`"…"` or `` `…` ``)
/// cut as [`excerpt`] cuts, and every line still longer than
/// [`MAX_MESSAGE_LINE`] characters cut there: for messages built by a
/// library (serde, TOML, CSV) that quote the input themselves.
///
/// ```
/// use ecam_core::excerpt::cut_quotes;
///
/// let long = format!("invalid type: string \"{}\", expected u32", "x".repeat(5000));
/// let cut = cut_quotes(&long);
/// assert!(cut.starts_with("invalid type: string \"xxxx"));
/// assert!(cut.ends_with("…\" (5000 bytes), expected u32"));
/// ```
pub fn cut_quotes(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4 * MAX_MESSAGE_LINE));
    for (k, line) in message.split('\n').enumerate() {
        if k > 0 {
            out.push('\n');
        }
        let cut = cut_line_quotes(line);
        match cut.char_indices().nth(MAX_MESSAGE_LINE) {
            Some((end, _)) => {
                out.push_str(&cut[..end]);
                out.push('…');
            }
            None => out.push_str(&cut),
        }
    }
    out
}

/// One line with its long quotes cut.
fn cut_line_quotes(line: &str) -> String {
    use core::fmt::Write as _;
    let mut out = String::new();
    let mut rest = line;
    while let Some(open) = rest.find(['"', '`']) {
        let quote = rest.as_bytes()[open] as char;
        out.push_str(&rest[..=open]);
        let inside = &rest[open + 1..];
        // A `"` quote may hold `\"`; a backtick quote holds none.
        let mut close = None;
        let mut escaped = false;
        for (i, c) in inside.char_indices() {
            if c == quote && !escaped {
                close = Some(i);
                break;
            }
            escaped = quote == '"' && c == '\\' && !escaped;
        }
        let Some(close) = close else {
            rest = inside;
            continue;
        };
        let quoted = &inside[..close];
        match quoted.char_indices().nth(EXCERPT_CHARS) {
            Some((end, _)) => {
                let _ = write!(out, "{}…{quote} ({} bytes)", &quoted[..end], quoted.len());
            }
            None => {
                out.push_str(quoted);
                out.push(quote);
            }
        }
        rest = &inside[close + 1..];
    }
    out.push_str(rest);
    out
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
    fn a_librarys_message_keeps_its_words_and_loses_the_long_input() {
        let toml = format!(
            "TOML parse error at line 1, column 10\n  |\n1 | pulses = \"{x}\"\n  |          {caret}\ninvalid type: string \"{x}\", expected u32",
            x = "x".repeat(100_000),
            caret = "^".repeat(100_002)
        );
        let cut = cut_quotes(&toml);
        assert!(cut.len() < 1000, "{cut}");
        assert!(cut.starts_with("TOML parse error at line 1, column 10\n"));
        assert!(cut.ends_with("(100000 bytes), expected u32"), "{cut}");
        assert_eq!(cut_quotes("a `b` and \"c\\\"d\""), "a `b` and \"c\\\"d\"");
        assert_eq!(cut_quotes("unmatched \"quote"), "unmatched \"quote");
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
