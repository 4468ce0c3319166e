//! Arithmetic the user types: cam functions of the master and numeric
//! parameters.
//!
//! Expressions are parsed by `exmex` (floats: `+ - * / ^`, `sin`, `cos`,
//! `tan`, `exp`, `ln`, `sqrt`, `abs`, …). The master is the variable `x`;
//! `pi`, `tau` and `e` are accepted in lower case besides exmex's own `PI`,
//! `TAU`, `E`, so the PLC editor's `1000*sin(2*pi*x/36000)` reads as written.

use ecam_core::Kinematics;
use exmex::prelude::*;

use crate::error::ExprError;

/// A parsed function of the master position `x`.
pub struct MasterFunction {
    expr: FlatEx<f64>,
    /// For each of exmex's variables (alphabetical), where its value comes from.
    slots: Vec<Slot>,
    text: String,
}

#[derive(Clone, Copy)]
enum Slot {
    Master,
    Constant(f64),
}

impl MasterFunction {
    /// Parses `text`; the only free variable allowed is `x`.
    ///
    /// # Errors
    /// Syntax errors and unknown names.
    pub fn parse(text: &str) -> Result<Self, ExprError> {
        Self::with_variables(text, true)
    }

    fn with_variables(text: &str, master_allowed: bool) -> Result<Self, ExprError> {
        // Parsing time grows faster than the length: bound it.
        let limit = ecam_core::limits::MAX_EXPRESSION_LEN;
        if text.len() > limit {
            return Err(ExprError::TooLong {
                len: text.len(),
                limit,
            });
        }
        let plain = expand_exponents(text)?;
        let expr = exmex::parse::<f64>(&plain).map_err(|e| ExprError::Syntax {
            text: text.to_string(),
            message: plain_error(&e.to_string()),
        })?;
        let slots = expr
            .var_names()
            .iter()
            .map(|name| match name.as_str() {
                "x" if master_allowed => Ok(Slot::Master),
                "pi" => Ok(Slot::Constant(std::f64::consts::PI)),
                "tau" => Ok(Slot::Constant(std::f64::consts::TAU)),
                "e" => Ok(Slot::Constant(std::f64::consts::E)),
                other => Err(ExprError::UnknownName {
                    name: other.to_string(),
                    text: text.to_string(),
                    master_allowed,
                }),
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            expr,
            slots,
            text: text.to_string(),
        })
    }

    /// Work units one evaluation costs (`ecam_core::budget`): one per
    /// operator, function call or bracket of the expression, and one more.
    pub fn cost(&self) -> u64 {
        let terms = self.text.bytes().filter(|b| b"+-*/^(".contains(b)).count();
        u64::try_from(terms).unwrap_or(u64::MAX).saturating_add(1)
    }

    /// Value and first three derivatives in `x` (velocity ratio,
    /// acceleration, jerk) by central differences with a step of `h` counts
    /// on the exact function (not on the rounded table). Symbolic
    /// differentiation was tried and dropped: repeated derivatives of
    /// quotients grow deep enough to overflow the stack.
    ///
    /// # Errors
    /// As [`MasterFunction::at`].
    pub fn kinematics(&self, x: f64, h: f64) -> Result<Kinematics, ExprError> {
        let s = self.at(x)?;
        if !self.slots.iter().any(|s| matches!(s, Slot::Master)) {
            return Ok(Kinematics::at_rest(s));
        }
        let h = h.max(1e-3);
        let f = |k: f64| self.at(x + k * h);
        let (m2, m1, p1, p2) = (f(-2.0)?, f(-1.0)?, f(1.0)?, f(2.0)?);
        Ok(Kinematics {
            s,
            v: (p1 - m1) / (2.0 * h),
            a: (p1 - 2.0 * s + m1) / (h * h),
            j: (p2 - 2.0 * p1 + 2.0 * m1 - m2) / (2.0 * h * h * h),
        })
    }

    fn values(&self, x: f64) -> Vec<f64> {
        self.slots
            .iter()
            .map(|s| match s {
                Slot::Master => x,
                Slot::Constant(c) => *c,
            })
            .collect()
    }

    /// The value at master position `x`.
    ///
    /// # Errors
    /// Evaluation errors of exmex, or a result that is not finite.
    pub fn at(&self, x: f64) -> Result<f64, ExprError> {
        let values = self.values(x);
        let y = self.expr.eval(&values).map_err(|e| ExprError::Eval {
            text: self.text.clone(),
            x,
            message: e.to_string(),
        })?;
        if !y.is_finite() {
            return Err(ExprError::NotFinite {
                text: self.text.clone(),
                x,
            });
        }
        Ok(y)
    }
}

/// Rewrites number literals in scientific notation (`1.5e3`, `2E-4`) as
/// plain decimals. exmex reads `1e3` as the number 1 followed by a variable
/// `e3` and reports a cryptic syntax error, yet engineers type exponents
/// (and spreadsheets paste them). Rust's `Display` for `f64` never uses an
/// exponent and round-trips exactly, so the value is unchanged.
fn expand_exponents(text: &str) -> Result<String, ExprError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while let Some(&c) = chars.get(i) {
        let after_name = i > 0
            && chars
                .get(i - 1)
                .is_some_and(|p| p.is_alphanumeric() || *p == '_' || *p == '.');
        if !(c.is_ascii_digit() || c == '.') || after_name {
            out.push(c);
            i += 1;
            continue;
        }
        // A number literal starts here: mantissa, then maybe an exponent.
        let start = i;
        while chars
            .get(i)
            .is_some_and(|d| d.is_ascii_digit() || *d == '.')
        {
            i += 1;
        }
        let mantissa_end = i;
        let mut j = i;
        if chars.get(j).is_some_and(|e| *e == 'e' || *e == 'E') {
            j += 1;
            if chars.get(j).is_some_and(|s| *s == '+' || *s == '-') {
                j += 1;
            }
            let digits = j;
            while chars.get(j).is_some_and(char::is_ascii_digit) {
                j += 1;
            }
            let ends_name = chars
                .get(j)
                .is_some_and(|n| n.is_alphanumeric() || *n == '_');
            if j > digits && !ends_name {
                let literal: String = chars.get(start..j).unwrap_or_default().iter().collect();
                if let Ok(v) = literal.parse::<f64>() {
                    if !v.is_finite() {
                        return Err(ExprError::TooLarge {
                            literal,
                            text: text.to_string(),
                        });
                    }
                    out.push_str(&format!("{v}"));
                    i = j;
                    continue;
                }
            }
        }
        out.extend(chars.get(start..mantissa_end).unwrap_or_default());
    }
    Ok(out)
}

/// Evaluates a constant expression such as `5/3`, `50/3`, `3*pi` or `1.6667`.
///
/// # Errors
/// Syntax errors, unknown names, or a non-finite value.
pub fn number(text: &str) -> Result<f64, ExprError> {
    let f = MasterFunction::with_variables(text, false)?;
    f.at(0.0).map_err(|error| ExprError::InConstant {
        text: text.to_string(),
        error: Box::new(error),
    })
}

/// The parser's message without its internal dumps: some name the Rust
/// operator structs, function addresses included, which say nothing to
/// the author of the expression.
fn plain_error(message: &str) -> String {
    // exmex reads `sinn(` as a name followed by a bracket: say what it
    // means to the author of the expression.
    if let Some(name) = message
        .split_once("left: ")
        .and_then(|(_, rest)| rest.split_once("; right: ("))
        .map(|(name, _)| name)
        .filter(|name| name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
    {
        return format!(
            "`{}` is not a function (the functions: sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, asinh, acosh, atanh, exp, ln, log, log2, log10, sqrt, cbrt, abs, signum, floor, ceil, round, trunc, fract)",
            ecam_core::excerpt::excerpt(name)
        );
    }
    let message = message.strip_prefix("wlog ").unwrap_or(message);
    match message
        .find(" Operator {")
        .or_else(|| message.find("Operator {"))
    {
        Some(at) => {
            let head = message[..at].trim_end_matches([',', ' ']);
            format!("{head} (two operators in a row)")
        }
        None => message.to_string(),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn ratios_and_constants() {
        assert!((number("5/3").unwrap() - 5.0 / 3.0).abs() < 1e-15);
        assert!((number("3*pi").unwrap() - 3.0 * std::f64::consts::PI).abs() < 1e-12);
        assert_eq!(number("1000").unwrap(), 1000.0);
        assert!(number("x").is_err());
        assert!(number("5/").is_err());
    }

    #[test]
    fn an_unknown_function_is_named() {
        // Main's wording of the parser's message (one home: `plain_error`);
        // functions the parser has but a short list might miss still parse.
        let e = MasterFunction::parse("1000*sinn(x)")
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("`sinn` is not a function"), "{e}");
        assert!(MasterFunction::parse("sqrt (x) + log10(x+1)").is_ok());
        assert!(MasterFunction::parse("cbrt(x) + trunc(x)").is_ok());
    }

    #[test]
    fn messages_quote_a_short_excerpt_of_a_long_expression() {
        // 4 000 bytes: under the length limit, so the parser's and the
        // evaluator's messages are the ones that quote it.
        let long_name = format!("x*{}", "y".repeat(3_998));
        let e = MasterFunction::parse(&long_name).err().unwrap().to_string();
        assert!(e.len() < 200, "{} bytes: {e}", e.len());
        assert!(
            e.contains("(3998 bytes)") && e.contains("(4000 bytes)"),
            "{e}"
        );
        let syntax = format!("1+{}(", "2".repeat(3_990));
        let e = MasterFunction::parse(&syntax).err().unwrap().to_string();
        assert!(e.len() < 300, "{} bytes: {e}", e.len());
        assert!(e.contains("(3993 bytes)"), "{e}");
        let big = format!("x+1e{}", "9".repeat(3_000));
        let e = number(&big).unwrap_err().to_string();
        assert!(e.len() < 300, "{} bytes: {e}", e.len());
    }

    #[test]
    fn the_manuals_sine_cam() {
        let f = MasterFunction::parse("1000*sin(2*pi*x/36000)").unwrap();
        assert!(f.at(0.0).unwrap().abs() < 1e-9);
        assert!((f.at(9000.0).unwrap() - 1000.0).abs() < 1e-9);
        assert!(MasterFunction::parse("y*2").is_err());
    }

    #[test]
    fn derivatives_of_a_sine() {
        let f = MasterFunction::parse("1000*sin(2*pi*x/36000)").unwrap();
        let k = f.kinematics(0.0, 25.0).unwrap();
        let w = std::f64::consts::TAU / 36000.0;
        let close = |got: f64, want: f64| (got - want).abs() <= 1e-5 * want.abs().max(1e-30);
        assert!(close(k.v, 1000.0 * w), "{k:?}");
        assert!(k.a.abs() < 1e-12, "{k:?}");
        assert!(close(k.j, -1000.0 * w * w * w), "{k:?}");
        let k = f.kinematics(9000.0, 25.0).unwrap();
        assert!(close(k.a, -1000.0 * w * w), "{k:?}");
    }

    #[test]
    fn derivatives_of_a_cubic() {
        let f = MasterFunction::parse("x^3").unwrap();
        let k = f.kinematics(10.0, 0.5).unwrap();
        assert!((k.v - 300.0).abs() < 1.0, "{k:?}");
        assert!((k.a - 60.0).abs() < 1e-6, "{k:?}");
        assert!((k.j - 6.0).abs() < 1e-6, "{k:?}");
    }

    #[test]
    fn scientific_notation_reads_as_a_number() {
        assert_eq!(number("1e3").unwrap(), 1000.0);
        assert_eq!(number("1.5E-3").unwrap(), 0.0015);
        assert_eq!(number("2e+2*3").unwrap(), 600.0);
        assert_eq!(number("1e308").unwrap(), 1e308);
        let f = MasterFunction::parse("1e-3*x + exp(0)").unwrap();
        assert!((f.at(1000.0).unwrap() - 2.0).abs() < 1e-12);
        // `e` alone is still Euler's number, and names are left alone.
        assert!((number("2*e").unwrap() - 2.0 * std::f64::consts::E).abs() < 1e-12);
        assert_eq!(expand_exponents("log10(x)+x2e3").unwrap(), "log10(x)+x2e3");
        let e = number("1e999").err().unwrap().to_string();
        assert!(e.contains("too large"), "{e}");
    }

    #[test]
    fn division_by_zero_is_an_error() {
        let f = MasterFunction::parse("1/x").unwrap();
        assert!(f.at(0.0).is_err());
    }
}
