//! Image decoding as height fields and as RGBA8 textures (see targets.rs).
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::image(data));
