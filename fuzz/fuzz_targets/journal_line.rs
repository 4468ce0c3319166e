#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| ecam_serve::fuzz::journal_line(data));
