//! A bench's output folder, shared by every bench so that each keeps its
//! results the same way:
//!
//! - **A run never overwrites another run's results.** Without a folder named
//!   (`--out-dir`), each run writes a new one under the bench's default
//!   (`bench-sync/2026-12-05_10-31-02`). A folder named that already holds
//!   files is refused, unless the user passes `--force`: then the files the
//!   previous run listed in its manifest (`.sweeplab-bench`) are removed first
//!   (so a plot of a strategy left out this time does not linger beside the new
//!   tables), and files the bench did not write are never touched.
//! - **A stopped run keeps what it measured, named as partial.** The folder holds
//!   a `PARTIAL` file from the start of the run to its end: a run stopped by
//!   Ctrl-C, or by an error ([`OutFolder::watch`] writes the error into it),
//!   or a run that its time budget cut short ([`OutFolder::finish_partial`])
//!   leaves it there, beside the rows saved as they were measured
//!   ([`OutFolder::save_rows`], whose JSON and CSV say `partial` in their run
//!   header until the final report replaces them).
//! - A run that ends by an error before it measured anything removes the
//!   folders it created: no empty folder is left behind.

use crate::bench::error::BenchError;
use crate::bench::rows::BenchTable;
use crate::bench::run_info::utc_now_iso8601;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

const MANIFEST: &str = ".sweeplab-bench";
/// The marker of a run that has not finished (see the module's description).
pub const PARTIAL: &str = "PARTIAL";

/// What a partial table's run header says (JSON `run.partial`, CSV `# partial:`).
pub const PARTIAL_ROWS: &str = "the rows measured so far; the run has not finished (or was stopped)";

#[derive(Debug, thiserror::Error)]
pub enum OutFolderError {
    #[error("bench output folder {}: {source}", .folder.display())]
    Io {
        folder: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(
        "--out-dir {}: already holds {} ({}); name a new folder, or pass --force to replace \
         what the previous bench run wrote there",
        .folder.display(), crate::plural::count(*.count as u64, "file", "files"), .some.join(", ")
    )]
    NotEmpty { folder: PathBuf, count: usize, some: Vec<String> },
}

/// Where a run writes.
#[derive(Clone, Copy, Debug)]
pub enum OutTarget<'a> {
    /// The folder the user named; `force` allows one that holds files.
    Named { folder: &'a Path, force: bool },
    /// A new folder under `base`, named by the date and time (UTC) of the run.
    NewUnder(&'a Path),
}

/// An output folder being written by one run.
pub struct OutFolder {
    folder: PathBuf,
    /// The files there before the run, with their modification times.
    before: HashMap<String, SystemTime>,
    /// The folders this run created (the run folder last), removed again when
    /// it ends by an error before writing anything.
    created: Vec<PathBuf>,
    finished: bool,
}

impl OutFolder {
    /// Chooses and creates the folder, refuses one that holds files (unless
    /// forced: then the files the previous run listed are removed), and marks
    /// the run [`PARTIAL`] until it finishes.
    pub fn prepare(target: OutTarget) -> Result<OutFolder, OutFolderError> {
        let folder = match target {
            OutTarget::Named { folder, .. } => folder.to_path_buf(),
            OutTarget::NewUnder(base) => new_run_folder(base),
        };
        let err = |source| OutFolderError::Io { folder: folder.clone(), source };
        if folder.exists() && !folder.is_dir() {
            return Err(err(std::io::Error::other("exists and is not a folder")));
        }
        let mut created = Vec::new();
        if folder.exists() {
            let force = matches!(target, OutTarget::Named { force: true, .. });
            // The manifest alone is no result (its files are gone).
            let mut held: Vec<String> = entries(&folder).map_err(err)?.into_iter().filter(|n| n != MANIFEST).collect();
            if !held.is_empty() && !force {
                held.sort();
                let count = held.len();
                held.truncate(4);
                return Err(OutFolderError::NotEmpty { folder, count, some: held });
            }
            remove_listed(&folder).map_err(err)?;
        } else {
            // Each missing folder on the way, outermost first.
            let missing: Vec<&Path> =
                folder.ancestors().take_while(|p| !p.as_os_str().is_empty() && !p.exists()).collect();
            created = missing.into_iter().rev().map(Path::to_path_buf).collect();
            std::fs::create_dir_all(&folder).map_err(err)?;
        }
        let before = files(&folder).map_err(err)?;
        let out = OutFolder { folder, before, created, finished: false };
        out.mark_partial("it has not finished: it is still running, or it was stopped (Ctrl-C)")?;
        Ok(out)
    }

    pub fn path(&self) -> &Path {
        &self.folder
    }

    /// Writes `table` as `<stem>.csv` and `<stem>.json`, whole, replacing the
    /// previous save, with `partial` in their run header: a bench calls it after
    /// each row, so the files always hold every row measured so far (the final
    /// report writes the same files without the mark).
    pub fn save_rows(&self, stem: &str, table: &BenchTable) -> Result<(), BenchError> {
        let mut partial = table.clone();
        if let Some(run) = &mut partial.run {
            run.partial = Some(PARTIAL_ROWS.to_string());
        }
        partial.write_csv(self.folder.join(format!("{stem}.csv")))?;
        partial.write_json(self.folder.join(format!("{stem}.json")))
    }

    /// Passes `result` on; an error is written into the [`PARTIAL`] marker, so
    /// the folder says why its files are partial.
    pub fn watch<T, E: std::fmt::Display>(&self, result: Result<T, E>) -> Result<T, E> {
        if let Err(e) = &result {
            let _ = self.mark_partial(&format!("it was stopped by an error: {e}"));
        }
        result
    }

    /// Whether the run has written anything yet (its marker aside).
    pub fn holds_results(&self) -> bool {
        files(&self.folder).is_ok_and(|f| f.keys().any(|n| n != PARTIAL))
    }

    /// The run ended as planned: the marker goes, and the files written since
    /// [`OutFolder::prepare`] (new, or changed) are listed in the manifest.
    pub fn finish(mut self) -> Result<Vec<String>, OutFolderError> {
        self.finished = true;
        match std::fs::remove_file(self.folder.join(PARTIAL)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(self.io_error(e)),
            _ => {}
        }
        self.list_written()
    }

    /// The run ended, but measured less than it planned (`why`, e.g. its time
    /// budget left configurations out): the marker stays and says so.
    pub fn finish_partial(mut self, why: &str) -> Result<Vec<String>, OutFolderError> {
        self.finished = true;
        self.mark_partial(&format!("it measured less than planned: {why}"))?;
        self.list_written()
    }

    fn list_written(&self) -> Result<Vec<String>, OutFolderError> {
        let mut written: Vec<String> = files(&self.folder)
            .map_err(|e| self.io_error(e))?
            .into_iter()
            .filter(|(name, modified)| name != PARTIAL && self.before.get(name) != Some(modified))
            .map(|(name, _)| name)
            .collect();
        written.sort();
        std::fs::write(self.folder.join(MANIFEST), written.join("\n")).map_err(|e| self.io_error(e))?;
        Ok(written)
    }

    fn mark_partial(&self, why: &str) -> Result<(), OutFolderError> {
        let text = format!(
            "This bench run is partial: {why}.\nThe files here hold what it measured until then.\n\
             command: {}\nmarked: {}\n",
            std::env::args().collect::<Vec<_>>().join(" "),
            utc_now_iso8601()
        );
        std::fs::write(self.folder.join(PARTIAL), text).map_err(|e| self.io_error(e))
    }

    fn io_error(&self, source: std::io::Error) -> OutFolderError {
        OutFolderError::Io { folder: self.folder.clone(), source }
    }
}

impl Drop for OutFolder {
    /// A run that ended by an error before its first file (the marker aside)
    /// removes the marker and the folders it created; `remove_dir` refuses a
    /// folder that holds anything.
    fn drop(&mut self) {
        if self.finished {
            return;
        }
        if !self.holds_results() && self.folder.is_dir() {
            let _ = std::fs::remove_file(self.folder.join(PARTIAL));
            for folder in self.created.iter().rev() {
                let _ = std::fs::remove_dir(folder);
            }
        }
    }
}

/// `base/<date>_<time>` (UTC) of now, with `-2`, `-3`, ... where one of that
/// second exists already.
fn new_run_folder(base: &Path) -> PathBuf {
    // "2026-12-05T10:31:02Z" -> "2026-12-05_10-31-02": sorts by time, and no ':'.
    let stamp = utc_now_iso8601().trim_end_matches('Z').replace('T', "_").replace(':', "-");
    let first = base.join(&stamp);
    if !first.exists() {
        return first;
    }
    (2..).map(|n| base.join(format!("{stamp}-{n}"))).find(|p| !p.exists()).unwrap_or(first)
}

/// The names of everything in `folder`.
fn entries(folder: &Path) -> std::io::Result<Vec<String>> {
    std::fs::read_dir(folder)?.map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned())).collect()
}

/// Removes the files the previous run listed in its manifest, its marker and
/// the manifest.
fn remove_listed(folder: &Path) -> std::io::Result<()> {
    let manifest = folder.join(MANIFEST);
    let listed = std::fs::read_to_string(&manifest).unwrap_or_default();
    let names = listed.lines().filter(|n| is_plain_name(n)).chain([PARTIAL, MANIFEST]);
    for name in names {
        match std::fs::remove_file(folder.join(name)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e),
            _ => {}
        }
    }
    Ok(())
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

    fn fresh(name: &str) -> PathBuf {
        let folder = std::env::temp_dir().join(format!("sweeplab-out-folder-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        folder
    }

    fn named(folder: &Path, force: bool) -> Result<OutFolder, OutFolderError> {
        OutFolder::prepare(OutTarget::Named { folder, force })
    }

    #[test]
    fn a_folder_that_holds_files_is_refused_without_force() {
        let folder = fresh("refused");
        let first = named(&folder, false).unwrap();
        std::fs::write(folder.join("sync.json"), "1").unwrap();
        first.finish().unwrap();
        let e = named(&folder, false).err().expect("a second run into the same folder is refused");
        let text = e.to_string();
        assert!(text.contains("already holds 1 file (sync.json)") && text.contains("--force"), "{text}");
        assert_eq!(std::fs::read_to_string(folder.join("sync.json")).unwrap(), "1", "the first run's file was touched");
        // An empty folder is taken as it is.
        let empty = fresh("refused-empty");
        std::fs::create_dir_all(&empty).unwrap();
        named(&empty, false).unwrap().finish().unwrap();
        std::fs::remove_dir_all(&folder).unwrap();
        std::fs::remove_dir_all(&empty).unwrap();
    }

    #[test]
    fn forced_a_second_run_removes_what_the_first_wrote_and_nothing_else() {
        let folder = fresh("forced");
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("notes.txt"), "the user's").unwrap();
        let first = named(&folder, true).unwrap();
        std::fs::write(folder.join("a.csv"), "1").unwrap();
        std::fs::write(folder.join("lines_racy.png"), "1").unwrap();
        let listed = first.finish().unwrap();
        assert_eq!(listed, ["a.csv", "lines_racy.png"], "the marker is not a result");
        let second = named(&folder, true).unwrap();
        assert!(!folder.join("lines_racy.png").exists(), "stale file of the first run kept");
        assert!(folder.join("notes.txt").exists(), "a file the bench did not write was removed");
        std::fs::write(folder.join("a.csv"), "2").unwrap();
        assert_eq!(second.finish().unwrap(), vec!["a.csv".to_string()]);
        // A manifest naming a path outside the folder removes nothing there.
        let outside = folder.parent().unwrap().join(format!("escape-{}.txt", std::process::id()));
        let escape = format!("../{}\n/etc/passwd", outside.file_name().unwrap().to_string_lossy());
        std::fs::write(folder.join(MANIFEST), escape).unwrap();
        std::fs::write(&outside, "x").unwrap();
        named(&folder, true).unwrap().finish().unwrap();
        assert!(outside.exists());
        std::fs::remove_file(outside).unwrap();
        std::fs::remove_dir_all(&folder).unwrap();
    }

    #[test]
    fn without_a_named_folder_every_run_writes_a_new_one() {
        let base = fresh("new-runs");
        let first = OutFolder::prepare(OutTarget::NewUnder(&base)).unwrap();
        let second = OutFolder::prepare(OutTarget::NewUnder(&base)).unwrap();
        assert_ne!(first.path(), second.path());
        for out in [&first, &second] {
            assert_eq!(out.path().parent(), Some(base.as_path()));
            let name = out.path().file_name().unwrap().to_string_lossy().into_owned();
            assert!(name.starts_with("20") && !name.contains(':'), "{name}");
            std::fs::write(out.path().join("a.csv"), "1").unwrap();
        }
        first.finish().unwrap();
        second.finish().unwrap();
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn a_run_that_writes_nothing_leaves_no_folder() {
        let base = fresh("empty");
        let folder = base.join("deeper").join("run");
        let out = named(&folder, false).unwrap();
        assert!(folder.join(PARTIAL).is_file(), "the run is marked partial from its start");
        drop(out); // the run ended by an error
        assert!(!base.exists(), "the folders the run created are gone");
        // A folder that was there already stays.
        std::fs::create_dir_all(&folder).unwrap();
        drop(named(&folder, false).unwrap());
        assert!(folder.exists() && !folder.join(PARTIAL).exists());
        std::fs::remove_dir_all(&base).unwrap();
        // A file where the folder should be is refused, not written into.
        std::fs::write(&base, "x").unwrap();
        assert!(named(&base, true).is_err());
        std::fs::remove_file(&base).unwrap();
    }

    #[test]
    fn rows_saved_as_they_come_survive_a_stopped_run_named_as_partial() {
        let folder = fresh("partial");
        let out = named(&folder, false).unwrap();
        let mut table = BenchTable::with_run(crate::bench::RunInfo::host());
        for size in [64, 128] {
            table.push(crate::bench::rows::BenchRow::new().with("size", size).with("gpu_ms", 1.5));
            out.save_rows("runs", &table).unwrap();
        }
        let failed: Result<(), String> = out.watch(Err("device lost".to_string()));
        assert!(failed.is_err());
        drop(out); // stopped: no finish, no final report
        let kept = BenchTable::read_json(folder.join("runs.json")).unwrap();
        assert_eq!(kept.rows, table.rows);
        assert_eq!(kept.run.and_then(|r| r.partial).as_deref(), Some(PARTIAL_ROWS));
        let csv = std::fs::read_to_string(folder.join("runs.csv")).unwrap();
        assert!(csv.contains("# partial: "), "{csv}");
        let marker = std::fs::read_to_string(folder.join(PARTIAL)).unwrap();
        assert!(marker.contains("stopped by an error: device lost"), "{marker}");
        std::fs::remove_dir_all(&folder).unwrap();
    }

    #[test]
    fn a_finished_run_drops_the_marker_and_a_cut_one_says_why() {
        let folder = fresh("finished");
        let out = named(&folder, false).unwrap();
        std::fs::write(folder.join("a.csv"), "1").unwrap();
        out.finish().unwrap();
        assert!(!folder.join(PARTIAL).exists());
        let cut = named(&folder, true).unwrap();
        std::fs::write(folder.join("a.csv"), "2").unwrap();
        cut.finish_partial("--max-minutes 3 left out line widths 2, 8").unwrap();
        let marker = std::fs::read_to_string(folder.join(PARTIAL)).unwrap();
        assert!(marker.contains("measured less than planned: --max-minutes 3"), "{marker}");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
