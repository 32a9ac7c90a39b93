//! Every input a fuzz target ever crashed on (`fuzz/regressions/TARGET/`), replayed through the
//! same target body on stable: each must now return without a panic. The folders also hold the
//! hand-made crashers of the hostile-input sweep (their names say what they were).

#[path = "../../../fuzz/targets.rs"]
mod targets;

use std::path::Path;

fn replay(target: &str, body: fn(&[u8])) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions").join(target);
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        let result = std::panic::catch_unwind(|| body(&data));
        assert!(result.is_ok(), "{}: the {target} target panicked on it again", path.display());
        n += 1;
    }
    n
}

#[test]
fn saved_crashers_no_longer_crash() {
    let counts: Vec<(&str, usize)> = [
        ("image", targets::image as fn(&[u8])),
        ("texture", targets::texture),
        ("obj", targets::obj),
        ("gltf", targets::gltf),
        ("cli_args", targets::cli_args),
        ("height_sets", targets::height_sets),
    ]
    .into_iter()
    .map(|(t, f)| (t, replay(t, f)))
    .collect();
    // Each folder holds at least the sweep's crashers; an empty one means the path is wrong.
    for (t, n) in &counts {
        assert!(*n > 0, "fuzz/regressions/{t} holds no inputs");
    }
}
