//! Helpers shared by the CLI tests: run the binary, make scratch folders, craft image files.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Output;

pub fn bumpmap(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap")).args(args).output().expect("run bumpmap")
}

/// `bumpmap ARGS…` under an address-space limit of `limit_mib` (`ulimit -v`) and a 60 s timeout.
/// Two worker threads and two malloc arenas whatever the machine: each thread's arena reserves
/// 64 MiB of address space, so the limits the tests choose mean the same on every machine.
pub fn limited(limit_mib: u64, args: &[&str]) -> Output {
    limited_threads(limit_mib, 2, args)
}

/// [`limited`] with `threads` worker threads: one makes the order of allocations, and so the
/// outcome at a given limit, the same on every run.
pub fn limited_threads(limit_mib: u64, threads: usize, args: &[&str]) -> Output {
    let script = format!("ulimit -v {}; exec timeout 60 \"$0\" \"$@\"", limit_mib * 1024);
    std::process::Command::new("sh")
        .env("RAYON_NUM_THREADS", threads.to_string())
        .env("MALLOC_ARENA_MAX", "2")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_bumpmap"))
        .args(args)
        .output()
        .unwrap()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh, empty folder under the target directory, named after the test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names of the files in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

/// Writes an 8-bit greyscale PNG.
pub fn write_gray_png(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> u8) {
    image::GrayImage::from_fn(w, h, |x, y| image::Luma([f(x, y)])).save(path).unwrap();
}

/// CRC-32 (PNG chunks, zlib's polynomial).
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A PNG whose IHDR claims `w`×`h` 8-bit greyscale, with no pixel data behind it.
pub fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut out = vec![0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A];
    let mut chunk = |kind: &[u8; 4], data: &[u8]| {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let mut body = kind.to_vec();
        body.extend_from_slice(data);
        out.extend_from_slice(&body);
        out.extend_from_slice(&crc32(&body).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    chunk(b"IHDR", &ihdr);
    // An empty zlib stream: enough for a decoder to report the header's size.
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    out
}

/// Runs `bumpmap ARGS…` expecting exit status 1, a message that names `input` and contains
/// `expect`, no panic, and no file added to or removed from `dir`.
pub fn fails_cleanly(dir: &Path, args: &[&str], input: &Path, expect: &str) {
    let before = listing(dir);
    let o = bumpmap(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(&input.display().to_string()), "message must name the file: {err}");
    assert!(err.contains(expect), "message must say '{expect}': {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(listing(dir), before, "no partial or stray output");
}

/// A PNG file's RGB as an RGBA8 image (alpha 255).
pub fn read_png(path: &Path) -> bumpmap_math::Rgba8Image {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgb8();
    let (w, h) = (img.width() as usize, img.height() as usize);
    bumpmap_math::Rgba8Image::new(w, h, img.pixels().map(|p| [p[0], p[1], p[2], 255]).collect())
}

/// Runs `bumpmap ARGS…`, expecting success; returns stderr.
pub fn ok(args: &[&str]) -> String {
    let o = bumpmap(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stderr(&o)
}

/// Whether a GPU test should run: an adapter answered, or CI (`CI` set) demands one. `o` is the
/// output of a `--backend gpu` command.
pub fn gpu_ran(o: &Output) -> bool {
    if !o.status.success() && stderr(o).contains("no GPU adapter") && std::env::var_os("CI").is_none() {
        eprintln!("SKIPPED (no GPU adapter): {}", stderr(o));
        return false;
    }
    true
}
