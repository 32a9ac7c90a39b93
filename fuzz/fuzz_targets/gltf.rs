//! glTF JSON and GLB bytes to a mesh (see targets.rs).
#![no_main]

#[path = "../targets.rs"]
mod targets;

libfuzzer_sys::fuzz_target!(|data: &[u8]| targets::gltf(data));
