#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| ecam_mc::fuzz::mc_script(data));
