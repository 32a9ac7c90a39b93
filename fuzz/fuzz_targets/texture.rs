//! Normal-map files (DDS, KTX2, images) decoded with their levels and imported (see targets.rs).
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::texture(data));
