//! One writer per output folder: [`OutputLock`] holds an advisory file lock (`flock`) on
//! `DIR/.lock` for as long as a job writes into `DIR`. A second job on the same folder is
//! refused with a message naming the first (its pid and command line); a killed job's lock is
//! released by the operating system, so a resume never has to clean anything up.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::error::{DataError, Result};

/// Name of the lock file inside an output folder (a dot-file: readers skip it).
pub const LOCK_FILE: &str = ".lock";

/// A held lock on an output folder; released on drop (or when the process dies).
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
    _file: File,
}

impl OutputLock {
    /// Lock `dir` (created if missing) for `job` (e.g. `"evaluate"`), or fail naming the job
    /// that holds it.
    pub fn acquire(dir: &Path, job: &str) -> Result<Self> {
        check_is_folder(dir)?;
        std::fs::create_dir_all(dir).map_err(|e| DataError::io(dir, e))?;
        let path = dir.join(LOCK_FILE);
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| DataError::io(&path, e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let mut holder = String::new();
                let _ = file.read_to_string(&mut holder);
                let holder = holder.trim();
                return Err(DataError::invalid(
                    "out",
                    dir.display(),
                    format!(
                        "another job is writing into this folder ({}); wait for it to finish or \
                         choose another folder",
                        if holder.is_empty() {
                            "holder unknown"
                        } else {
                            holder
                        }
                    ),
                ));
            }
            Err(TryLockError::Error(e)) => return Err(DataError::io(&path, e)),
        }
        let args: Vec<String> = std::env::args().collect();
        let who = format!(
            "{job}, pid {}: {}",
            std::process::id(),
            args.join(" ").chars().take(300).collect::<String>()
        );
        file.set_len(0)
            .and_then(|_| file.seek(SeekFrom::Start(0)))
            .and_then(|_| file.write_all(who.as_bytes()))
            .map_err(|e| DataError::io(&path, e))?;
        Ok(OutputLock { path, _file: file })
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// `--out` names a folder (made if missing): a file there is refused in words, not with the
/// operating system's "File exists".
pub fn check_is_folder(dir: &Path) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if !m.is_dir() => Err(DataError::invalid(
            "out",
            dir.display(),
            "is a file, not a folder; name a folder (it is made if missing)",
        )),
        _ => Ok(()),
    }
}

/// Refuse to write a job's results into a dataset folder (one with `scenes/` or a
/// `<task>/<split>/<split>.json.gz`): its files would mix with the dataset's.
pub fn refuse_dataset_folder(dir: &Path) -> Result<()> {
    let holds_split = crate::episode::Task::ALL.iter().any(|&t| {
        crate::episode::Split::ALL
            .iter()
            .any(|&s| crate::dataset::split_path(dir, t, s).is_file())
    });
    if dir.join("scenes").is_dir() || holds_split {
        return Err(DataError::invalid(
            "out",
            dir.display(),
            "is a dataset folder (it holds scenes/ or split files); write results into a \
             folder of their own",
        ));
    }
    Ok(())
}

/// Written beside `summary.json` by `score`: marks the folder as score's own, so a later
/// score may replace its files.
pub const SCORE_FILE: &str = "score.json";

/// Files of an evaluation's run folder: a score written among them would mix two runs.
const EVALUATION_FILES: [&str; 3] = ["run.json", "progress.jsonl", "trajectories.jsonl"];

/// Refuse an `out` that `score` must not write into: a file, a dataset folder, an evaluation's
/// run (finished or running; `force` does not change that), or a `summary.json` that no score
/// wrote (no [`SCORE_FILE`] beside it) unless `force`.
pub fn check_score_folder(out: &Path, force: bool) -> Result<()> {
    check_is_folder(out)?;
    refuse_dataset_folder(out)?;
    let refuse = |why: String| Err(DataError::invalid("out", out.display(), why));
    if let Some(f) = EVALUATION_FILES.iter().find(|f| out.join(f).exists()) {
        return refuse(format!(
            "holds an evaluation's run ({f}); score into a folder of its own"
        ));
    }
    if !force && out.join("summary.json").exists() && !out.join(SCORE_FILE).exists() {
        return refuse(
            "holds a summary.json that score did not write; choose another folder, or \
             --force (Python: force=True) to overwrite it"
                .into(),
        );
    }
    Ok(())
}

/// Write [`SCORE_FILE`] into `out`: what was scored.
pub fn write_score_file(
    out: &Path,
    trajectories: &Path,
    dataset: &Path,
    task: crate::episode::Task,
    split: crate::episode::Split,
) -> Result<()> {
    let marker = serde_json::json!({
        "trajectories": trajectories.display().to_string(),
        "dataset": dataset.display().to_string(),
        "task": task.name(),
        "split": split.name(),
    });
    crate::dataset::write_atomic(&out.join(SCORE_FILE), format!("{marker:#}\n").as_bytes())
}
