//! Heights and horizon sets found by name beside the file named (see targets.rs): a value or an
//! error, never a panic, an abort or memory past the limit.
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::height_sets(data));
