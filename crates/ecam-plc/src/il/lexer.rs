//! Splits IL source into lines of tokens.

/// One source line that holds an instruction.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Line<'a> {
    /// 1-based line number.
    pub number: usize,
    /// Mnemonic first, then operands.
    pub tokens: Vec<&'a str>,
}

/// Cuts comments (`;` to the end of the line), splits on blanks and commas,
/// and drops a leading step number such as `0  LD X0` copied from a
/// programming tool's listing. Empty lines are skipped.
pub(crate) fn lines(source: &str) -> Vec<Line<'_>> {
    source
        .lines()
        .enumerate()
        .filter_map(|(index, text)| {
            let code = text.split(';').next().unwrap_or("");
            let mut tokens: Vec<&str> = code
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|t| !t.is_empty())
                .collect();
            if tokens.len() > 1 && tokens[0].bytes().all(|b| b.is_ascii_digit()) {
                tokens.remove(0);
            }
            (!tokens.is_empty()).then_some(Line {
                number: index + 1,
                tokens,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_comments_steps_and_commas() {
        let src = "; header\n\n0  LD X0 ; start\nMOV K5, D0\n   \n";
        let got = lines(src);
        assert_eq!(got.len(), 2);
        assert_eq!(
            got[0],
            Line {
                number: 3,
                tokens: vec!["LD", "X0"]
            }
        );
        assert_eq!(
            got[1],
            Line {
                number: 4,
                tokens: vec!["MOV", "K5", "D0"]
            }
        );
    }
}
