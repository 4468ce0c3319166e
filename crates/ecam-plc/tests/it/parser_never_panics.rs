//! Random text never panics the IL parser (it returns a program or an error).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use proptest::prelude::*;

const WORDS: &[&str] = &[
    "LD",
    "LDI",
    "LDP",
    "AND",
    "OR",
    "ANB",
    "ORB",
    "MPS",
    "MRD",
    "MPP",
    "OUT",
    "SET",
    "RST",
    "PLS",
    "MOV",
    "DMOVP",
    "DEMOV",
    "ZRST",
    "ADD",
    "DSUB",
    "CMP",
    "DPLSY",
    "DECAM",
    "ECAMTBX",
    "END",
    "X0",
    "X377",
    "Y400",
    "M8511",
    "D8511",
    "D65536",
    "C231",
    "K-99999999999",
    "K5",
    "HFFFFFFFFF",
    "E1e39",
    "E1.5",
    "Z0",
    "V7",
    "D10Z0",
    "K4M0Z1",
    "X0V0",
    "T0Z0",
    "C255Z1",
    "K2Y0",
    "D0Z0.1",
    ";",
    ",",
    "\n",
    " ",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(600)))]

    #[test]
    fn arbitrary_text(text in "\\PC{0,200}") {
        let _ = ecam_plc::Program::parse(&text, "fuzz.il");
    }

    #[test]
    fn plausible_tokens(tokens in proptest::collection::vec(proptest::sample::select(WORDS), 0..60)) {
        let text = tokens.join(" ");
        if let Err(err) = ecam_plc::Program::parse(&text, "fuzz.il") {
            prop_assert!(err.to_string().starts_with("fuzz.il:"));
        }
    }

    #[test]
    fn parsed_programs_run(tokens in proptest::collection::vec(proptest::sample::select(WORDS), 0..40)) {
        let text = tokens.join(" ");
        if let Ok(program) = ecam_plc::Program::parse(&text, "fuzz.il") {
            if let Ok(mut plc) = ecam_plc::Plc::new(program) {
                for _ in 0..3 {
                    plc.scan();
                    plc.hardware_tick(100);
                }
            }
        }
    }
}
