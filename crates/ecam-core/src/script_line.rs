//! One line of a command script: the reader shared by the motion-processor
//! (`ecam pmd run`, document 002) and motion-controller (`ecam mc run`,
//! document 001) scripts, so that both faces read a line the same way.
//!
//! - `'` starts a comment, and so do the typographic quotes `‘ ’` that the
//!   documents' listings print instead;
//! - a line holding only `…` or `...` (a listing's elision) is skipped, as
//!   are blank and comment-only lines, and a byte-order mark before the
//!   first word;
//! - words are separated by blanks or commas, the command word first;
//! - a number is decimal or `0x` hex, with an optional sign (document 002
//!   writes `SetBufferStart 2 0x1000`).
//!
//! What the words mean (command names, named values) is each face's own.
//! No I/O: it works on `&str` and needs only `alloc`.
//!
//! ```
//! use ecam_core::script_line::{NumberError, ScriptLine, parse_number};
//!
//! let line = ScriptLine::read("SetBufferStart 2, 0x1000  ‘ table in buffer 2").unwrap();
//! assert_eq!(line.command(), "SetBufferStart");
//! assert_eq!(line.args(), ["2", "0x1000"]);
//! assert_eq!(parse_number(line.args()[1]), Ok(4096));
//! assert!(ScriptLine::read("  ' only a comment").is_none());
//! assert!(ScriptLine::read("…").is_none());
//! assert_eq!(parse_number("99999999999999999999"), Err(NumberError::OutOfRange));
//! assert_eq!(parse_number("1.5"), Err(NumberError::NotANumber));
//! ```

use alloc::vec::Vec;
use core::fmt;

/// The characters that start a comment: `'` and the typographic quotes
/// `‘` and `’` of the documents' listings.
pub const COMMENT_STARTS: [char; 3] = ['\'', '‘', '’'];

/// A line that holds a command: its code (comment removed, trimmed), the
/// command word and the argument words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScriptLine<'a> {
    code: &'a str,
    command: &'a str,
    args: Vec<&'a str>,
}

impl<'a> ScriptLine<'a> {
    /// Reads one line; `None` for a blank, comment-only or elision line.
    pub fn read(line: &'a str) -> Option<Self> {
        // A byte-order mark may open a script saved by a Windows editor.
        let code = strip_comment(line.trim_start_matches('\u{feff}')).trim();
        if code.is_empty() || code == "…" || code == "..." {
            return None;
        }
        let mut words = code
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty());
        let command = words.next()?;
        Some(Self {
            code,
            command,
            args: words.collect(),
        })
    }

    /// The command word, as written.
    pub fn command(&self) -> &'a str {
        self.command
    }

    /// The words after the command.
    pub fn args(&self) -> &[&'a str] {
        &self.args
    }

    /// The text after the command word, trimmed, for an argument that may
    /// hold blanks and commas (a file path).
    pub fn rest(&self) -> &'a str {
        self.code
            .get(self.command.len()..)
            .unwrap_or_default()
            .trim()
    }
}

/// Removes the comment from a line: from the first [`COMMENT_STARTS`]
/// character to the end.
pub fn strip_comment(line: &str) -> &str {
    line.find(COMMENT_STARTS)
        .map_or(line, |i| line.get(..i).unwrap_or(line))
}

/// A word that is not a usable number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberError {
    /// Written as a number (decimal or `0x` hex, optional sign) but past
    /// the signed 64-bit range.
    OutOfRange,
    /// Not written as a number.
    NotANumber,
}

impl fmt::Display for NumberError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::OutOfRange => "out of range (a signed 64-bit number)",
            Self::NotANumber => "not a number (decimal or 0x hex)",
        })
    }
}

impl core::error::Error for NumberError {}

/// Parses a number: decimal or `0x`/`0X` hex digits, with an optional `+`
/// or `-` in front.
///
/// # Errors
/// [`NumberError::OutOfRange`] for a well-formed number past the signed
/// 64-bit range, [`NumberError::NotANumber`] for anything else.
pub fn parse_number(text: &str) -> Result<i64, NumberError> {
    let (negative, unsigned) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.strip_prefix('+').unwrap_or(text)),
    };
    let (digits, radix) = match unsigned
        .strip_prefix("0x")
        .or_else(|| unsigned.strip_prefix("0X"))
    {
        Some(hex) => (hex, 16),
        None => (unsigned, 10),
    };
    if digits.is_empty() || !digits.chars().all(|c| c.is_digit(radix)) {
        return Err(NumberError::NotANumber);
    }
    // Well formed: anything that does not fit is out of range.
    let magnitude = u64::from_str_radix(digits, radix).map_err(|_| NumberError::OutOfRange)?;
    if negative {
        0i64.checked_sub_unsigned(magnitude)
    } else {
        i64::try_from(magnitude).ok()
    }
    .ok_or(NumberError::OutOfRange)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn lines_split_into_command_and_words() {
        let line = ScriptLine::read("\u{feff}MoveTo 0 -75000,750 ' master").unwrap();
        assert_eq!(line.command(), "MoveTo");
        assert_eq!(line.args(), ["0", "-75000", "750"]);
        let line = ScriptLine::read("ECAMTableFile t my tables/a, b.csv’ note").unwrap();
        assert_eq!(line.rest(), "t my tables/a, b.csv");
        for skipped in ["", "   ", "' comment", "‘ comment", " … ", "..."] {
            assert_eq!(ScriptLine::read(skipped), None, "{skipped:?}");
        }
    }

    #[test]
    fn numbers_are_decimal_or_hex_with_a_sign() {
        assert_eq!(parse_number("-0x10"), Ok(-16));
        assert_eq!(parse_number("0X1f"), Ok(31));
        assert_eq!(parse_number("+7"), Ok(7));
        assert_eq!(parse_number("-9223372036854775808"), Ok(i64::MIN));
        assert_eq!(parse_number("9223372036854775807"), Ok(i64::MAX));
        assert_eq!(
            parse_number("9223372036854775808"),
            Err(NumberError::OutOfRange)
        );
        assert_eq!(
            parse_number("0x1FFFFFFFFFFFFFFFF"),
            Err(NumberError::OutOfRange)
        );
        for bad in [
            "", "-", "0x", "1e3", "1.5", "--5", "+-5", "0x-5", "x10", "٣",
        ] {
            assert_eq!(parse_number(bad), Err(NumberError::NotANumber), "{bad:?}");
        }
    }
}
