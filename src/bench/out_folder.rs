//! A bench's output folder without stale files: each run lists the files it
//! wrote in `.sweeplab-bench` (a manifest), and the next run into the same folder
//! first removes exactly those, so a plot of a strategy left out this time does
//! not linger beside the new tables. Files the bench did not write are never
//! touched.
//!
//! A bench saves its rows as it measures them ([`OutFolder::save_rows`]), so an
//! interrupted run keeps what it measured. The folder is created by the first
//! file written into it, and a run that ends by an error before writing
//! anything removes the folder it would have created: no empty folder is left
//! behind.

use crate::bench::error::BenchError;
use crate::bench::rows::BenchTable;
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
    /// Whether the folder existed before the run (else the run may remove it
    /// again, when it wrote nothing).
    existed: bool,
}

impl OutFolder {
    /// Removes the files the previous run listed. `folder` need not exist yet:
    /// the first file written creates it.
    pub fn prepare(folder: &Path) -> Result<OutFolder, OutFolderError> {
        let err = |source| OutFolderError { folder: folder.to_path_buf(), source };
        if folder.exists() && !folder.is_dir() {
            return Err(err(std::io::Error::other("exists and is not a folder")));
        }
        if !folder.exists() {
            return Ok(OutFolder { folder: folder.to_path_buf(), before: HashMap::new(), existed: false });
        }
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
        Ok(OutFolder { folder: folder.to_path_buf(), before, existed: true })
    }

    pub fn path(&self) -> &Path {
        &self.folder
    }

    /// Writes `table` as `<stem>.csv` and `<stem>.json`, whole, replacing the
    /// previous save: a bench calls it after each row, so the files always hold
    /// every row measured so far.
    pub fn save_rows(&self, stem: &str, table: &BenchTable) -> Result<(), BenchError> {
        table.write_csv(self.folder.join(format!("{stem}.csv")))?;
        table.write_json(self.folder.join(format!("{stem}.json")))
    }

    /// Lists the files written since [`OutFolder::prepare`] (new, or changed)
    /// in the manifest.
    pub fn finish(self) -> Result<Vec<String>, OutFolderError> {
        let err = |source| OutFolderError { folder: self.folder.clone(), source };
        if !self.folder.exists() {
            return Ok(Vec::new());
        }
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

impl Drop for OutFolder {
    /// A folder this run would have created but left empty (it ended by an
    /// error before its first row) is removed; `remove_dir` refuses a folder
    /// that holds anything.
    fn drop(&mut self) {
        if !self.existed {
            let _ = std::fs::remove_dir(&self.folder);
        }
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

    fn fresh(name: &str) -> PathBuf {
        let folder = std::env::temp_dir().join(format!("sweeplab-out-folder-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        folder
    }

    #[test]
    fn a_run_that_writes_nothing_leaves_no_folder() {
        let folder = fresh("empty");
        let out = OutFolder::prepare(&folder).unwrap();
        assert!(!folder.exists(), "prepare created the folder before anything was written");
        drop(out); // the run ended by an error
        assert!(!folder.exists());
        assert_eq!(OutFolder::prepare(&folder).unwrap().finish().unwrap(), Vec::<String>::new());
        assert!(!folder.exists());
        // A folder that was there already stays, empty or not.
        std::fs::create_dir_all(&folder).unwrap();
        drop(OutFolder::prepare(&folder).unwrap());
        assert!(folder.exists());
        std::fs::remove_dir_all(&folder).unwrap();
        // A file where the folder should be is refused, not written into.
        std::fs::write(&folder, "x").unwrap();
        assert!(OutFolder::prepare(&folder).is_err());
        std::fs::remove_file(&folder).unwrap();
    }

    #[test]
    fn rows_saved_as_they_come_survive_an_interrupted_run() {
        let folder = fresh("partial");
        let out = OutFolder::prepare(&folder).unwrap();
        let mut table = BenchTable::new();
        for size in [64, 128] {
            table.push(crate::bench::rows::BenchRow::new().with("size", size).with("gpu_ms", 1.5));
            out.save_rows("runs", &table).unwrap();
        }
        drop(out); // interrupted: no finish, no final report
        let kept = BenchTable::read_json(folder.join("runs.json")).unwrap();
        assert_eq!(kept, table);
        let csv = std::fs::read_to_string(folder.join("runs.csv")).unwrap();
        assert_eq!(csv.lines().count(), 3, "{csv}");
        assert!(folder.exists(), "a folder holding rows was removed");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
