//! The files a command reads and writes, checked together before any work: an output that is
//! also an input (the same file, however it is spelled: canonical paths, and on Unix the same
//! inode) is refused always; an output that exists is refused unless `--force` was given; an
//! output that cannot be written (a directory, a missing parent, no permission) fails early.
//!
//! Two commands regenerate files by a documented convention instead, the data they are made
//! from being kept: `figures` (the SVGs its configs name, in `--out`) and a study's `--config`
//! (the figure its `output` names in figures/ and the data next to it). Those outputs
//! ([`Files::regenerated`]) may replace an existing file without `--force`, but never an input.

use anyhow::{Result, bail};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// `--force`, set once by `main`.
static FORCE: OnceLock<bool> = OnceLock::new();

/// Records the global `--force` flag (called once, before any command runs).
pub fn set_force(force: bool) {
    let _ = FORCE.set(force);
}

fn force() -> bool {
    FORCE.get().copied().unwrap_or(false)
}

/// What may happen to an existing output file.
#[derive(Clone, Copy, PartialEq)]
enum Existing {
    /// Replaced only with `--force`.
    NeedsForce,
    /// Replaced by convention (the command regenerates it).
    Regenerated,
}

/// The inputs and outputs of one command (flag, path).
#[derive(Default)]
pub struct Files {
    inputs: Vec<(String, PathBuf)>,
    outputs: Vec<(String, PathBuf, Existing)>,
}

impl Files {
    /// No files yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// A file the command reads (given by `flag`).
    pub fn input(mut self, flag: &str, path: impl AsRef<Path>) -> Self {
        self.inputs
            .push((flag.to_string(), path.as_ref().to_path_buf()));
        self
    }

    /// A file the command writes (given by `flag`): an existing one needs `--force`.
    pub fn output(mut self, flag: &str, path: impl AsRef<Path>) -> Self {
        self.outputs.push((
            flag.to_string(),
            path.as_ref().to_path_buf(),
            Existing::NeedsForce,
        ));
        self
    }

    /// A file the command regenerates by its documented convention (module docs).
    pub fn regenerated(mut self, flag: &str, path: impl AsRef<Path>) -> Self {
        self.outputs.push((
            flag.to_string(),
            path.as_ref().to_path_buf(),
            Existing::Regenerated,
        ));
        self
    }

    /// Checks every output against the inputs, the other outputs, `--force` and the file
    /// system (module docs); the first problem is the error, naming the flag and the file.
    pub fn check(&self) -> Result<()> {
        for (i, (flag, path, existing)) in self.outputs.iter().enumerate() {
            let shown = path.display();
            if path.is_dir() {
                bail!("{flag}: {shown} is a directory, not a file");
            }
            if let Some((iflag, _)) = self.inputs.iter().find(|(_, p)| same_file(p, path)) {
                bail!(
                    "{flag}: {shown} is also an input of this command ({iflag}); writing it would destroy it: choose another file"
                );
            }
            if let Some((oflag, ..)) = self.outputs[..i].iter().find(|o| same_file(&o.1, path)) {
                bail!("{flag}: {shown} is also written as {oflag}: choose another file");
            }
            if *existing == Existing::NeedsForce && path.exists() && !force() {
                bail!("{flag}: {shown} exists; add --force to overwrite it");
            }
            writable(flag, path)?;
        }
        Ok(())
    }
}

/// Fails when `path` cannot be written: a missing parent directory or no permission. A file
/// created only for the check is removed again.
fn writable(flag: &str, path: &Path) -> Result<()> {
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|e| anyhow::anyhow!("{flag}: cannot write {}: {e}", path.display()))?;
    if !existed {
        let _ = std::fs::remove_file(path);
    }
    Ok(())
}

/// The path as the file system resolves it: canonical if it exists, else its parent's
/// canonical path joined with its name (a file about to be created), else as given.
fn resolved(p: &Path) -> PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let parent = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    match (parent.canonicalize(), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => p.to_path_buf(),
    }
}

/// Whether `a` and `b` name the same file (the same resolved path, or on Unix the same device
/// and inode: a hard link).
fn same_file(a: &Path, b: &Path) -> bool {
    if resolved(a) == resolved(b) {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_file_sees_through_spellings() {
        let dir = std::env::temp_dir().join(format!("sphstab-files-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let f = dir.join("a.json");
        std::fs::write(&f, "{}").unwrap();
        assert!(same_file(&f, &dir.join("sub/../a.json")));
        assert!(same_file(&dir.join("new.svg"), &dir.join("sub/../new.svg")));
        assert!(!same_file(&f, &dir.join("b.json")));
        let e = Files::new()
            .input("<FILES>", &f)
            .output("--out", dir.join("sub/../a.json"))
            .check()
            .unwrap_err();
        assert!(e.to_string().contains("also an input"), "{e}");
        let e = Files::new().output("--out", &f).check().unwrap_err();
        assert!(e.to_string().contains("--force"), "{e}");
        assert!(Files::new().regenerated("figures", &f).check().is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
