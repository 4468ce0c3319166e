#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| ecam_design::fuzz::generator_toml(data));
