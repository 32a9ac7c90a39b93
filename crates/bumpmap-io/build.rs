//! Links the C++ runtime that Intel's ISPC texture compressor (`intel_tex_2`, under
//! `image_dds`) needs: its prebuilt kernels are C++ objects, and rustc links through `cc`,
//! which does not add the C++ standard library on its own.
fn main() {
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.contains("apple") || target.contains("freebsd") {
        println!("cargo:rustc-link-lib=c++");
    } else if target.contains("linux") {
        println!("cargo:rustc-link-lib=stdc++");
    }
}
