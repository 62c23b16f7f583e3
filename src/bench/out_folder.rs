//! A bench's output folder without stale files: each run lists the files it
//! wrote in `.sweeplab-bench` (a manifest), and the next run into the same folder
//! first removes exactly those, so a plot of a strategy left out this time does
//! not linger beside the new tables. Files the bench did not write are never
//! touched.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

const MANIFEST: &str = ".sweeplab-bench";

#[derive(Debug, thiserror::Error)]
#[error("bench output folder {}: {source}", .folder.display())]
pub struct OutFolderError {
    pub folder: PathBuf,
    #[source]
    pub source: std::io::Error,
}

/// An output folder being written by one run.
pub struct OutFolder {
    folder: PathBuf,
    /// The files there before the run, with their modification times.
    before: HashMap<String, SystemTime>,
}

impl OutFolder {
    /// Creates `folder` if needed and removes the files the previous run listed.
    pub fn prepare(folder: &Path) -> Result<OutFolder, OutFolderError> {
        let err = |source| OutFolderError { folder: folder.to_path_buf(), source };
        std::fs::create_dir_all(folder).map_err(err)?;
        let manifest = folder.join(MANIFEST);
        if let Ok(listed) = std::fs::read_to_string(&manifest) {
            for name in listed.lines().filter(|n| is_plain_name(n)) {
                match std::fs::remove_file(folder.join(name)) {
                    Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(err(e)),
                    _ => {}
                }
            }
            std::fs::remove_file(&manifest).map_err(err)?;
        }
        let before = files(folder).map_err(err)?;
        Ok(OutFolder { folder: folder.to_path_buf(), before })
    }

    pub fn path(&self) -> &Path {
        &self.folder
    }

    /// Lists the files written since [`OutFolder::prepare`] (new, or changed)
    /// in the manifest.
    pub fn finish(self) -> Result<Vec<String>, OutFolderError> {
        let err = |source| OutFolderError { folder: self.folder.clone(), source };
        let mut written: Vec<String> = files(&self.folder)
            .map_err(err)?
            .into_iter()
            .filter(|(name, modified)| self.before.get(name) != Some(modified))
            .map(|(name, _)| name)
            .collect();
        written.sort();
        std::fs::write(self.folder.join(MANIFEST), written.join("\n")).map_err(err)?;
        Ok(written)
    }
}

/// The plain files of `folder` (the manifest aside) with their modification times.
fn files(folder: &Path) -> std::io::Result<HashMap<String, SystemTime>> {
    let mut out = HashMap::new();
    for entry in std::fs::read_dir(folder)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if entry.file_type()?.is_file() && name != MANIFEST {
            out.insert(name, entry.metadata()?.modified()?);
        }
    }
    Ok(out)
}

/// A file name in the folder itself (a manifest never reaches outside it).
fn is_plain_name(name: &str) -> bool {
    !name.is_empty() && name != MANIFEST && !name.contains('/') && !name.contains('\\') && name != ".." && name != "."
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_run_removes_what_the_first_wrote_and_nothing_else() {
        let folder = std::env::temp_dir().join(format!("sweeplab-out-folder-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("notes.txt"), "the user's").unwrap();
        let first = OutFolder::prepare(&folder).unwrap();
        std::fs::write(folder.join("a.csv"), "1").unwrap();
        std::fs::write(folder.join("lines_racy.png"), "1").unwrap();
        let listed = first.finish().unwrap();
        assert!(listed.contains(&"a.csv".to_string()) && listed.contains(&"lines_racy.png".to_string()));
        let second = OutFolder::prepare(&folder).unwrap();
        assert!(!folder.join("lines_racy.png").exists(), "stale file of the first run kept");
        assert!(folder.join("notes.txt").exists(), "a file the bench did not write was removed");
        std::fs::write(folder.join("a.csv"), "2").unwrap();
        assert_eq!(second.finish().unwrap(), vec!["a.csv".to_string()]);
        // A manifest naming a path outside the folder removes nothing there.
        std::fs::write(folder.join(MANIFEST), "../escape.txt\n/etc/passwd").unwrap();
        let outside = folder.parent().unwrap().join("escape.txt");
        std::fs::write(&outside, "x").unwrap();
        OutFolder::prepare(&folder).unwrap();
        assert!(outside.exists());
        std::fs::remove_file(outside).unwrap();
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
