//! Hostile input, round four (issue #57): what the fourth sweep found short, one test per class.

mod common;

use std::path::Path;
use std::process::Output;

use common::{limited, listing, ok, png_header_only, scratch, stderr};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Exit 1, `expect` in the message, no abort or panic, and `dir` as it was.
fn refused(o: &Output, dir: &Path, before: &[String], expect: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(expect), "message must say '{expect}': {err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation of"), "{err}");
    assert_eq!(listing(dir), before, "nothing may be written");
}

/// Every heights or horizon file — named by an option, or found by name beside one — is sized
/// from its header and refused before its texels are decoded. The 16384² files here are headers
/// alone: decoding one would fail on its missing body, or ask for gigabytes, and the 1 GiB
/// limit turns either into another message than the size's.
#[test]
fn heights_and_horizon_files_are_sized_from_their_headers_before_they_are_decoded() {
    let dir = scratch("hostile4_sized");
    let at = |name: &str| dir.join(name);
    ok(&[
        "normalmap",
        "bricks@64",
        "-o",
        s(&at("n.png")),
        "--mips",
        "--height-out",
        s(&at("h.png")),
        "--horizon-out",
        s(&at("hz.png")),
    ]);
    let huge = png_header_only(16384, 16384);
    std::fs::write(at("big.png"), &huge).unwrap();
    let render = |args: &[&str]| {
        let (out, normal) = (at("out.png"), at("n.png"));
        let mut all = vec!["render", "--scene", "wall", "--size", "32", "--normal-map", s(&normal), "-o", s(&out)];
        all.extend(args);
        limited(1024, &all)
    };
    let before = listing(&dir);
    let big = at("big.png");
    let o = render(&["--technique", "pom", "--height-map", s(&big)]);
    refused(&o, &dir, &before, "big.png: is 16384x16384, but the normal map is 64x64");
    let o = render(&["--technique", "horizon", "--horizon-map", s(&big)]);
    refused(&o, &dir, &before, "big.png: is 16384x16384, but the normal map is 64x64");
    // Found by name: the bounds beside the heights, the second half beside the horizons.
    for (beside, named, technique, flag) in [
        ("h.minmax.png", "h.png", "height-exact", "--height-map"),
        ("hz.dirs4-7.png", "hz.png", "horizon", "--horizon-map"),
    ] {
        let kept = std::fs::read(at(beside)).unwrap();
        std::fs::write(at(beside), &huge).unwrap();
        let before = listing(&dir);
        let o = render(&["--technique", technique, flag, s(&at(named))]);
        refused(&o, &dir, &before, &format!("{beside}: is 16384x16384, but "));
        assert!(stderr(&o).contains("64x64"), "{}", stderr(&o));
        std::fs::write(at(beside), kept).unwrap();
    }
    // Restored, the set draws.
    let o = render(&["--technique", "height-exact", "--height-map", s(&at("h.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Bounds of the wrong format beside heights are refused, naming the file and what it holds,
/// never read as bounds: a normal map (8-bit RGBA), or gray heights (blue not 0).
#[test]
fn bounds_of_another_format_are_refused_not_read_as_bounds() {
    let dir = scratch("hostile4_bounds");
    let at = |name: &str| dir.join(name);
    ok(&["normalmap", "bricks@64", "-o", s(&at("n.png")), "--bits", "16", "--height-out", s(&at("h.png"))]);
    ok(&["normalmap", "bricks@64", "-o", s(&at("n8.png"))]);
    let kept = std::fs::read(at("h.minmax.png")).unwrap();
    for (stand_in, says) in [
        ("n8.png", "h.minmax.png: holds R8G8B8A8_UNORM, not min–max bounds"),
        ("h.png", "h.minmax.png: is not min–max bounds: its texel (0, 0) has blue"),
    ] {
        std::fs::copy(at(stand_in), at("h.minmax.png")).unwrap();
        let before = listing(&dir);
        let (out, normal, heights) = (at("out.png"), at("n.png"), at("h.png"));
        let o = limited(
            2048,
            &["render", "--scene", "wall", "--size", "32", "--technique", "height-exact", "--normal-map", s(&normal)]
                .into_iter()
                .chain(["--height-map", s(&heights), "-o", s(&out)])
                .collect::<Vec<_>>(),
        );
        refused(&o, &dir, &before, says);
    }
    std::fs::write(at("h.minmax.png"), kept).unwrap();
}
