#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| ecam_plc::fuzz::il_program(data));
