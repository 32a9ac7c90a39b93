//! Write-then-rename, and the rule that an output never replaces an input.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::IoError;

/// A set of output files written all or nothing: each file goes to a hidden temporary file
/// beside its destination; [`FileSet::commit`] renames them all into place once every one was
/// written. Until then no destination is touched, and a set dropped uncommitted (an error on
/// the way) removes its temporary files. Every destination is checked against the inputs and
/// against the set's other files before its bytes are written. Missing destination folders
/// are created, and removed again if the set is dropped uncommitted (when still empty).
///
/// If a rename still fails after others succeeded (the folder vanished, a disk error), the
/// files renamed so far are put back as they were: each existing destination is kept under a
/// second name (a hard link, or a copy where links are not possible) until the whole set is in
/// place. What it cannot promise is the same after a power cut or a `kill -9` mid-commit.
pub struct FileSet {
    inputs: Vec<PathBuf>,
    staged: Vec<(PathBuf, PathBuf)>,
    /// Folders this set created, outermost first.
    created: Vec<PathBuf>,
}

/// Every live set's temporary files and the folders it created, for [`abandon_all`]: what a
/// signal handler removes before the process ends. A set's commit holds the lock while it
/// renames, so a signal finds each set either wholly in place or wholly staged.
static LIVE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn forget(paths: &[&Path]) {
    live().retain(|p| !paths.contains(&p.as_path()));
}

/// Folders a command fills before putting them in place whole ([`StagedFolder`]): removed with
/// everything in them by [`abandon_all`].
static SCRATCH: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn scratch() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    SCRATCH.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A folder of outputs written all or nothing: filled under a hidden name beside its
/// destination, then put in place by [`StagedFolder::commit`] (an existing destination folder
/// is replaced whole); dropped uncommitted (an error, or [`abandon_all`] on a signal), it is
/// removed with everything in it, and so are the folders made to hold it.
pub struct StagedFolder {
    staging: PathBuf,
    destination: PathBuf,
    /// Ancestors of the destination this made, outermost first.
    created: Vec<PathBuf>,
}

impl StagedFolder {
    /// A fresh staging folder for `destination`, which must not be a file.
    pub fn new(destination: &Path) -> Result<Self, IoError> {
        let err = |source| IoError::Write { path: destination.to_path_buf(), source };
        if destination.exists() && !destination.is_dir() {
            return Err(err(std::io::Error::other("is a file; a folder of outputs cannot replace it")));
        }
        let parent = destination.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let name = destination.file_name().ok_or_else(|| err(std::io::Error::other("not a folder name")))?;
        let mut created: Vec<PathBuf> = parent
            .ancestors()
            .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
            .map(Path::to_path_buf)
            .collect();
        created.reverse();
        let staging = parent.join(format!(".{}.{}.staging", name.to_string_lossy(), std::process::id()));
        let _ = std::fs::remove_dir_all(&staging);
        scratch().push(staging.clone());
        live().extend(created.iter().cloned());
        // Made before the folders are: a failure drops it, which takes away what was made.
        let staged = Self { staging, destination: destination.to_path_buf(), created };
        std::fs::create_dir_all(&staged.staging).map_err(err)?;
        Ok(staged)
    }

    /// Where to write the outputs.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Puts the folder in place: the destination's old folder, if any, is replaced whole.
    pub fn commit(mut self) -> Result<PathBuf, IoError> {
        // Locks in the order abandon_all takes them: the sets', then the folders'.
        let mut live = live();
        let err = |source| IoError::Write { path: self.destination.clone(), source };
        let old = self.staging.with_extension("old");
        let had_old = self.destination.exists();
        if had_old {
            std::fs::rename(&self.destination, &old).map_err(err)?;
        }
        if let Err(e) = std::fs::rename(&self.staging, &self.destination) {
            if had_old {
                let _ = std::fs::rename(&old, &self.destination);
            }
            return Err(err(e));
        }
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        scratch().retain(|p| *p != self.staging);
        let created = std::mem::take(&mut self.created);
        live.retain(|p| !created.contains(p));
        Ok(self.destination.clone())
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        let mut live = live();
        let mut scratch = scratch();
        if let Some(i) = scratch.iter().position(|p| *p == self.staging) {
            let _ = std::fs::remove_dir_all(&self.staging);
            scratch.remove(i);
        }
        for dir in self.created.iter().rev() {
            let _ = std::fs::remove_dir(dir);
        }
        live.retain(|p| !self.created.contains(p));
    }
}

/// Removes every uncommitted set's temporary files, and the folders those sets created when
/// they are empty, and every [`StagedFolder`] not yet in place: for a signal handler (Ctrl-C,
/// SIGTERM) to call before exiting, so an interrupted command leaves nothing behind. Waits for
/// a commit in progress to finish. Sets staged afterwards are not affected; the caller is
/// expected to exit.
pub fn abandon_all() {
    let mut paths = live();
    for dir in scratch().drain(..) {
        let _ = std::fs::remove_dir_all(dir);
    }
    // Files first, then folders innermost first (they were registered outermost first).
    for p in paths.iter().filter(|p| !p.is_dir()) {
        let _ = std::fs::remove_file(p);
    }
    for p in paths.iter().rev().filter(|p| p.is_dir()) {
        let _ = std::fs::remove_dir(p);
    }
    paths.clear();
    // Held until the process exits: no commit may start after the abandonment.
    std::mem::forget(paths);
}

impl FileSet {
    /// A set whose files must not replace any of `inputs`.
    pub fn new(inputs: &[&Path]) -> Self {
        Self { inputs: inputs.iter().map(|p| p.to_path_buf()).collect(), staged: Vec::new(), created: Vec::new() }
    }

    /// Writes `path`'s bytes through `fill` into its temporary file. Refuses a path that names
    /// an input or a file already in the set.
    pub fn write(
        &mut self,
        path: &Path,
        fill: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
    ) -> Result<(), IoError> {
        let inputs: Vec<&Path> = self.inputs.iter().map(PathBuf::as_path).collect();
        ensure_not_input(path, &inputs)?;
        let staged: Vec<&Path> = self.staged.iter().map(|(p, _)| p.as_path()).collect();
        if staged.contains(&path) || ensure_not_input(path, &staged).is_err() {
            return Err(IoError::SameOutput { path: path.to_path_buf() });
        }
        let err = |source| IoError::Write { path: path.to_path_buf(), source };
        if path.is_dir() {
            return Err(err(std::io::Error::other("is a folder; a file cannot replace it")));
        }
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let name = path.file_name().ok_or_else(|| err(std::io::Error::other("not a file name")))?;
        // Unique in the process: threads writing the same path stage into files of their own.
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let tmp = dir.join(format!(".{}.{}.{n}.tmp", name.to_string_lossy(), std::process::id()));
        // Folders made and the temporary file created under one lock, which a set dropped on
        // another thread also takes to remove the folders it made: it cannot take away a
        // folder between another set's making sure of it and its first file there.
        let file = {
            let mut live = live();
            self.create_folders(dir, &mut live).map_err(err)?;
            live.push(tmp.clone());
            File::create(&tmp)
        };
        let result = (|| {
            let mut w = BufWriter::new(file?);
            fill(&mut w)?;
            w.flush()?;
            w.into_inner().map_err(|e| e.into_error())?.sync_all()
        })();
        match result {
            Ok(()) => {
                self.staged.push((path.to_path_buf(), tmp));
                Ok(())
            }
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                forget(&[&tmp]);
                Err(err(e))
            }
        }
    }

    /// Creates `dir` and its missing ancestors, remembering which were new (in `live` too).
    fn create_folders(&mut self, dir: &Path, live: &mut Vec<PathBuf>) -> std::io::Result<()> {
        let mut missing: Vec<PathBuf> =
            dir.ancestors().take_while(|d| !d.as_os_str().is_empty() && !d.exists()).map(Path::to_path_buf).collect();
        if missing.is_empty() {
            return Ok(());
        }
        std::fs::create_dir_all(dir)?;
        missing.reverse();
        live.extend(missing.iter().cloned());
        self.created.extend(missing);
        Ok(())
    }

    /// Renames every file into place; returns their paths in the order they were written.
    pub fn commit(mut self) -> Result<Vec<PathBuf>, IoError> {
        // No signal handler removes anything while the set is renamed into place.
        let mut live = live();
        let mine: Vec<PathBuf> =
            self.staged.iter().map(|(_, t)| t.clone()).chain(self.created.iter().cloned()).collect();
        live.retain(|p| !mine.contains(p));
        // A destination that became a folder since it was staged would fail its rename halfway
        // through the set: refuse the set before the first rename instead (dropping it removes
        // its temporary files and the folders it made).
        if let Some((path, _)) = self.staged.iter().find(|(p, _)| p.is_dir()) {
            return Err(IoError::Write {
                path: path.clone(),
                source: std::io::Error::other("is a folder; a file cannot replace it"),
            });
        }
        // Two runs writing the same set at once: their renames must not interleave (a chain
        // mixing levels of both). Each destination folder is locked while this set renames into
        // it, in one order, so one run's set lands whole after the other's.
        let mut folders: Vec<PathBuf> = self
            .staged
            .iter()
            .map(|(p, _)| p.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new(".")).to_path_buf())
            .collect();
        folders.sort();
        folders.dedup();
        let _locks: Vec<File> =
            folders.iter().filter_map(|d| File::open(d).ok()).filter(|f| f.lock().is_ok()).collect();
        // What each destination held before, to put back if a later rename fails.
        let mut backups: Vec<Option<PathBuf>> = Vec::with_capacity(self.staged.len());
        for (path, tmp) in &self.staged {
            if !path.exists() {
                backups.push(None);
                continue;
            }
            let backup = tmp.with_extension("old");
            let _ = std::fs::remove_file(&backup);
            let kept = std::fs::hard_link(path, &backup).or_else(|_| std::fs::copy(path, &backup).map(|_| ()));
            if let Err(source) = kept {
                remove_backups(&backups);
                return Err(IoError::Write { path: path.clone(), source });
            }
            backups.push(Some(backup));
        }
        let staged = std::mem::take(&mut self.staged);
        let mut done = Vec::with_capacity(staged.len());
        for (i, (path, tmp)) in staged.iter().enumerate() {
            if let Err(source) = std::fs::rename(tmp, path) {
                for (_, t) in &staged[i..] {
                    let _ = std::fs::remove_file(t);
                }
                // Back as it was: old files restored, new ones removed, made folders emptied.
                for (p, backup) in done.iter().zip(&backups) {
                    match backup {
                        Some(b) => {
                            let _ = std::fs::rename(b, p);
                        }
                        None => {
                            let _ = std::fs::remove_file(p);
                        }
                    }
                }
                remove_backups(&backups);
                return Err(IoError::Write { path: path.clone(), source });
            }
            done.push(path.clone());
        }
        remove_backups(&backups);
        // The folders now hold the set's files.
        self.created.clear();
        Ok(done)
    }
}

fn remove_backups(backups: &[Option<PathBuf>]) {
    for b in backups.iter().flatten() {
        let _ = std::fs::remove_file(b);
    }
}

impl Drop for FileSet {
    fn drop(&mut self) {
        let mut live = live();
        for (_, tmp) in &self.staged {
            let _ = std::fs::remove_file(tmp);
        }
        // Innermost first; a folder something else wrote into meanwhile is not empty and stays.
        for dir in self.created.iter().rev() {
            let _ = std::fs::remove_dir(dir);
        }
        let mine: Vec<&Path> =
            self.staged.iter().map(|(_, t)| t.as_path()).chain(self.created.iter().map(PathBuf::as_path)).collect();
        live.retain(|p| !mine.contains(&p.as_path()));
    }
}

/// Writes one file atomically (a [`FileSet`] of one, with no inputs to protect).
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    set.write(path, fill)?;
    set.commit().map(|_| ())
}

/// Refuses an output path that names the same file as any input (also through links or
/// `..`), so a typo cannot destroy the data being processed.
pub fn ensure_not_input(output: &Path, inputs: &[&Path]) -> Result<(), IoError> {
    let out = resolved(output);
    for input in inputs {
        if out.is_some() && std::fs::canonicalize(input).ok() == out {
            return Err(IoError::SameAsInput { path: output.to_path_buf() });
        }
    }
    Ok(())
}

/// The file `path` will name once its missing folders are made: its deepest existing ancestor
/// canonicalized, then the rest of the path taken lexically (`missing/../a.png` is `./a.png`,
/// because `missing` will exist by the time it is written). `None` when no ancestor resolves.
pub fn resolved(path: &Path) -> Option<PathBuf> {
    for ancestor in path.ancestors() {
        let base = if ancestor.as_os_str().is_empty() { Path::new(".") } else { ancestor };
        let Ok(mut out) = std::fs::canonicalize(base) else { continue };
        for part in path.strip_prefix(ancestor).ok()?.components() {
            match part {
                std::path::Component::ParentDir => {
                    out.pop();
                }
                std::path::Component::Normal(name) => out.push(name),
                _ => {}
            }
        }
        return Some(out);
    }
    None
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

    #[test]
    fn a_set_is_written_all_or_nothing_and_never_over_an_input() {
        let dir = std::env::temp_dir().join(format!("bumpmap-fileset-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let input = dir.join("in.png");
        std::fs::write(&input, b"input").unwrap();
        // The third file names the input: nothing of the set may appear.
        let mut set = FileSet::new(&[&input]);
        set.write(&dir.join("a"), |w| w.write_all(b"a")).unwrap();
        set.write(&dir.join("b"), |w| w.write_all(b"b")).unwrap();
        assert!(matches!(set.write(&input, |w| w.write_all(b"x")), Err(IoError::SameAsInput { .. })));
        drop(set);
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, ["in.png"], "no file of an unfinished set, no temporary file");
        assert_eq!(std::fs::read(&input).unwrap(), b"input");
        // The same output twice is refused; a good set lands whole.
        let mut set = FileSet::new(&[&input]);
        set.write(&dir.join("a"), |w| w.write_all(b"a")).unwrap();
        assert!(set.write(&dir.join("./a"), |w| w.write_all(b"again")).is_err());
        set.write(&dir.join("b"), |w| w.write_all(b"b")).unwrap();
        assert_eq!(set.commit().unwrap().len(), 2);
        assert_eq!(std::fs::read(dir.join("a")).unwrap(), b"a");
        // Missing folders are made for the set, and taken away again with an unfinished one.
        let mut set = FileSet::new(&[&input]);
        set.write(&dir.join("new/deeper/c"), |w| w.write_all(b"c")).unwrap();
        assert!(dir.join("new/deeper").is_dir());
        drop(set);
        assert!(!dir.join("new").exists(), "an unfinished set leaves no folder it made");
        let mut set = FileSet::new(&[&input]);
        set.write(&dir.join("new/deeper/c"), |w| w.write_all(b"c")).unwrap();
        set.commit().unwrap();
        assert_eq!(std::fs::read(dir.join("new/deeper/c")).unwrap(), b"c");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_destination_that_is_a_folder_fails_the_set_before_any_rename() {
        let dir = std::env::temp_dir().join(format!("bumpmap-fileset-folder-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("c")).unwrap();
        // Found when staged…
        let mut set = FileSet::new(&[]);
        set.write(&dir.join("a"), |w| w.write_all(b"a")).unwrap();
        assert!(matches!(set.write(&dir.join("c"), |w| w.write_all(b"c")), Err(IoError::Write { .. })));
        drop(set);
        // …and when it became a folder after it was staged: nothing is renamed.
        let mut set = FileSet::new(&[]);
        set.write(&dir.join("a"), |w| w.write_all(b"a")).unwrap();
        set.write(&dir.join("b"), |w| w.write_all(b"b")).unwrap();
        std::fs::create_dir(dir.join("b")).unwrap();
        let err = set.commit().unwrap_err();
        assert!(err.to_string().contains("is a folder"), "{err}");
        let mut names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        names.sort();
        assert_eq!(names, ["b", "c"], "neither a nor a temporary file");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_rename_that_fails_midway_puts_back_what_was_there() {
        let dir = std::env::temp_dir().join(format!("bumpmap-fileset-restore-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("a"), b"old a").unwrap();
        let mut set = FileSet::new(&[]);
        set.write(&dir.join("a"), |w| w.write_all(b"new a")).unwrap();
        set.write(&dir.join("sub/b"), |w| w.write_all(b"new b")).unwrap();
        set.write(&dir.join("c"), |w| w.write_all(b"new c")).unwrap();
        // The last temporary file vanishes: its rename fails after the others succeeded.
        std::fs::remove_file(&set.staged[2].1).unwrap();
        let err = set.commit().unwrap_err();
        assert!(err.to_string().contains(&dir.join("c").display().to_string()), "{err}");
        assert_eq!(std::fs::read(dir.join("a")).unwrap(), b"old a");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, ["a"], "no new file, no folder made for one, no backup");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_output_reached_through_a_folder_yet_to_be_made_is_still_checked() {
        let dir = std::env::temp_dir().join(format!("bumpmap-resolved-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let input = dir.join("h.png");
        std::fs::write(&input, b"heights").unwrap();
        let sneaky = dir.join("missing/deeper/../../h.png");
        assert!(matches!(ensure_not_input(&sneaky, &[&input]), Err(IoError::SameAsInput { .. })));
        assert!(ensure_not_input(&dir.join("missing/h.png"), &[&input]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
