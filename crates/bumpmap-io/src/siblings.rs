//! Files found by name beside a file the user gave: a PNG chain's `NAME.mipK.png` levels, a
//! heights file's `NAME.minmax.EXT`, a horizon map's `NAME.dirs4-7.EXT`. The user named only the
//! first, so the others are read under the rule a glTF's URIs are: from the named file's own
//! folder only. A link there is followed when it leads to a file in that same folder; one that
//! leads anywhere else, or an entry that is not a regular file (a folder, a FIFO that would
//! block), is an error naming it, never read.
//!
//! What this module does not do: read the files (each reader does), or decide which names a
//! format's siblings have (the readers and writers of each format do, through
//! [`level_path`] and their own).

use std::path::{Path, PathBuf};

use crate::error::IoError;
use crate::image_file::level_path;

/// `file`, found by name beside `named`, when there is an entry by that name: `Ok(None)` when
/// there is none, the file to read when it is a regular file in `named`'s folder (or a link to
/// one there), an error naming it otherwise.
pub fn beside(named: &Path, file: &Path) -> Result<Option<PathBuf>, IoError> {
    let folder = named.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    in_folder(folder, file, &format!("the folder of {}", named.display()))
}

/// `file`, an entry of `folder` found by listing it or by name (`place` says which folder, in
/// words): `Ok(None)` when there is no such entry, the file to read when it is a regular file
/// or a link to one in `folder`, an error naming it otherwise.
pub fn in_folder(folder: &Path, file: &Path, place: &str) -> Result<Option<PathBuf>, IoError> {
    let Ok(meta) = std::fs::symlink_metadata(file) else { return Ok(None) };
    let refused = |reason: String| IoError::Texture { path: file.to_path_buf(), reason };
    if meta.file_type().is_symlink() {
        let real_folder =
            std::fs::canonicalize(folder).map_err(|source| IoError::Read { path: folder.to_path_buf(), source })?;
        let target =
            std::fs::canonicalize(file).map_err(|source| IoError::Read { path: file.to_path_buf(), source })?;
        if target.parent() != Some(real_folder.as_path()) {
            return Err(refused(format!(
                "is a link to {}, outside {place}: a file found by name rather than given is read only from \
                 there (give the file itself, or copy it there)",
                target.display()
            )));
        }
        if !target.is_file() {
            return Err(refused(format!("leads to {}, which is not a regular file", target.display())));
        }
        return Ok(Some(file.to_path_buf()));
    }
    if !meta.is_file() {
        return Err(refused(format!(
            "is not a regular file, but is found by name in {place} and would be read as one"
        )));
    }
    Ok(Some(file.to_path_buf()))
}

/// Level `k` of the PNG chain whose level 0 is `path` (`full` its size), when its
/// `NAME.mipK.png` is there ([`beside`]), with its size read from its header and checked
/// against `want` **before** anything decodes it: a small map beside a huge file is refused
/// naming the file, never decoded into memory it does not need.
pub fn png_level(
    path: &Path,
    k: usize,
    full: (usize, usize),
    want: (usize, usize),
) -> Result<Option<PathBuf>, IoError> {
    let Some(file) = beside(path, &level_path(path, k))? else { return Ok(None) };
    let declared = crate::texture_read::declared_size(&file)?;
    if declared != want {
        return Err(IoError::Texture {
            path: file,
            reason: format!(
                "is {}x{}, but as level {k} of a {}x{} map it must be {}x{}",
                declared.0, declared.1, full.0, full.1, want.0, want.1
            ),
        });
    }
    Ok(Some(file))
}

/// The `NAME.mip1.png`, `NAME.mip2.png`, … beside the PNG `path`, as many as follow one another
/// (each passed by [`beside`]); level 0 (`path` itself) is not among them. A reader may stop
/// earlier (at 1×1); these are every file it may read.
pub fn png_levels(path: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut files = Vec::new();
    for k in 1.. {
        match beside(path, &level_path(path, k))? {
            Some(file) => files.push(file),
            None => break,
        }
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_out_of_the_folder_is_refused_and_one_inside_is_followed() {
        let root = std::env::temp_dir().join(format!("bumpmap-siblings-{}", std::process::id()));
        let (here, elsewhere) = (root.join("here"), root.join("elsewhere"));
        std::fs::create_dir_all(&here).unwrap();
        std::fs::create_dir_all(&elsewhere).unwrap();
        let named = here.join("r.png");
        std::fs::write(&named, b"x").unwrap();
        std::fs::write(here.join("r.mip1.png"), b"x").unwrap();
        std::fs::write(here.join("copy.png"), b"x").unwrap();
        std::fs::write(elsewhere.join("secret.png"), b"x").unwrap();
        std::os::unix::fs::symlink(here.join("copy.png"), here.join("r.mip2.png")).unwrap();
        assert_eq!(png_levels(&named).unwrap(), [here.join("r.mip1.png"), here.join("r.mip2.png")]);
        std::os::unix::fs::symlink(elsewhere.join("secret.png"), here.join("r.mip3.png")).unwrap();
        let e = png_levels(&named).unwrap_err().to_string();
        assert!(e.contains("r.mip3.png: is a link to") && e.contains("outside the folder of"), "{e}");
        assert!(in_folder(&here, &here.join("r.mip3.png"), "here").is_err());
        assert_eq!(in_folder(&here, &here.join("r.mip2.png"), "here").unwrap(), Some(here.join("r.mip2.png")));
        std::fs::create_dir(here.join("q.mip1.png")).unwrap();
        let e = png_levels(&here.join("q.png")).unwrap_err().to_string();
        assert!(e.contains("q.mip1.png: is not a regular file"), "{e}");
        assert_eq!(png_levels(&elsewhere.join("secret.png")).unwrap(), Vec::<PathBuf>::new());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
