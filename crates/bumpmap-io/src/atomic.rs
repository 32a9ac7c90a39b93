//! Write-then-rename, and the rule that an output never replaces an input.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::IoError;

/// Writes `path` through `fill`: the bytes go to a hidden temporary file beside it, which is
/// renamed over `path` only once `fill` and the flush succeeded. On any error the temporary file
/// is removed and `path` is untouched.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<(), IoError> {
    let err = |source| IoError::Write { path: path.to_path_buf(), source };
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().ok_or_else(|| err(std::io::Error::other("not a file name")))?;
    let tmp = dir.join(format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id()));
    let result = (|| {
        let mut w = BufWriter::new(File::create(&tmp)?);
        fill(&mut w)?;
        w.flush()?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(err)
}

/// Refuses an output path that names the same file as any input (also through links or
/// `..`), so a typo cannot destroy the data being processed.
pub fn ensure_not_input(output: &Path, inputs: &[&Path]) -> Result<(), IoError> {
    let canon = |p: &Path| -> Option<PathBuf> { std::fs::canonicalize(p).ok() };
    let out = canon(output).or_else(|| {
        // The output may not exist yet: compare its canonical folder plus file name.
        let parent = output.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        Some(canon(parent)?.join(output.file_name()?))
    });
    for input in inputs {
        if out.is_some() && canon(input) == out {
            return Err(IoError::SameAsInput { path: output.to_path_buf() });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_nothing_behind() {
        let dir = std::env::temp_dir().join(format!("bumpmap-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("out.bin");
        std::fs::write(&target, b"old").unwrap();
        let r = write_atomic(&target, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "no temporary file may remain");
        write_atomic(&target, |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert!(matches!(ensure_not_input(&dir.join("./out.bin"), &[&target]), Err(IoError::SameAsInput { .. })));
        assert!(ensure_not_input(&dir.join("other.bin"), &[&target]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
