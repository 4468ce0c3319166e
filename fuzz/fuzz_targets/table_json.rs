#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| ecam_core::fuzz::table_json(data));
