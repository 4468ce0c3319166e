//! clap value parsers for output files whose format follows the extension:
//! a name that ends in anything else is a usage error (exit 2) before
//! anything runs, not a file silently written in another format.

use std::path::PathBuf;

/// `--trace FILE.csv`: traces are CSV only.
pub fn csv(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    match ecam_core::io::extension(&path).as_deref() {
        Some("csv") => Ok(path),
        _ => Err(format!(
            "a trace is written as CSV: the file name must end in .csv (got {text})"
        )),
    }
}

/// `--plot FILE.svg|png`, `-o OUT.svg|png`: the picture formats plots have.
pub fn picture(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    ecam_plot::Format::of(&path)
        .map(|_| path)
        .map_err(|e| e.to_string())
}

/// `-o FILE.csv|json`: the table file formats.
pub fn table(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    ecam_core::io::FileFormat::of(&path)
        .map(|_| path)
        .map_err(|e| e.to_string())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn formats_follow_the_extension_or_are_refused() {
        assert!(csv("t.CSV").is_ok());
        assert!(csv("t.xlsx").unwrap_err().contains(".csv"));
        assert!(csv("t").is_err());
        assert!(picture("p.png").is_ok() && picture("p.pdf").is_err());
        assert!(table("t.json").is_ok() && table("t.xlsx").is_err());
    }
}
