//! The runs and comparisons under a directory (`ontogeny runs list`), found by their files
//! (a run directory holds `run.sqlite`, a comparison directory `compare.toml`), one line
//! each: path, kind, encoding(s), task, progress and best. One that cannot be read is listed
//! with its error; the listing goes on. Read-only: nothing is opened for writing.

use std::path::{Path, PathBuf};

use super::compare;
use crate::run::store::RunStore;

/// What a listed directory is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A run directory (`run.sqlite`).
    Run,
    /// A comparison directory (`compare.toml`), whose replicates are runs listed after it.
    Comparison,
}

impl Kind {
    /// Its name in the listing.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Run => "run",
            Kind::Comparison => "comparison",
        }
    }
}

/// One run or comparison found.
#[derive(Clone, Debug, PartialEq)]
pub struct Listed {
    /// Its directory.
    pub path: PathBuf,
    /// What it is.
    pub kind: Kind,
    /// The rest of its line (encoding(s), task, progress, best), or why it cannot be read.
    pub summary: Result<String, String>,
}

impl Listed {
    /// Its line: `PATH  KIND  SUMMARY`, or `PATH  KIND  error: WHY`.
    pub fn line(&self) -> String {
        let rest = match &self.summary {
            Ok(s) => s.clone(),
            Err(e) => format!("error: {e}"),
        };
        format!("{}  {}  {rest}", self.path.display(), self.kind.name())
    }
}

/// Every run and comparison in `root` and under it (symbolic links are not followed), in
/// path order. Err only when `root` itself cannot be read; a directory below it that
/// cannot be read is skipped.
pub fn list(root: &Path) -> std::io::Result<Vec<Listed>> {
    std::fs::read_dir(root)?;
    let mut found = Vec::new();
    visit(root, &mut found);
    Ok(found)
}

fn visit(dir: &Path, found: &mut Vec<Listed>) {
    if dir.join("compare.toml").is_file() {
        found.push(Listed {
            path: dir.to_path_buf(),
            kind: Kind::Comparison,
            summary: comparison_summary(dir),
        });
    }
    if dir.join("run.sqlite").is_file() {
        found.push(Listed {
            path: dir.to_path_buf(),
            kind: Kind::Run,
            summary: run_summary(dir).map_err(|e| e.to_string()),
        });
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut subdirectories: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| e.path())
        .collect();
    subdirectories.sort();
    for sub in subdirectories {
        visit(&sub, found);
    }
}

/// A run's encoding, task, generations done of those planned, and the last generation's best.
fn run_summary(dir: &Path) -> Result<String, crate::run::store::StoreError> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite"))?;
    let run = store.run()?;
    let task = run
        .task_spec()
        .map_or_else(|| run.task.clone(), |spec| spec.fitness_label());
    let planned = run
        .planned_generations()
        .map_or_else(|| "?".to_string(), |n| n.to_string());
    let generations = store.generations()?;
    let best = generations
        .last()
        .map_or_else(|| "none yet".to_string(), |g| format!("{:.6}", g.best));
    Ok(format!(
        "{}  {task}  {}/{planned} generations  best {best}",
        run.encoding,
        generations.len()
    ))
}

/// A comparison's encodings, task, replicates finished of those planned, and the best
/// champion of its finished replicates.
fn comparison_summary(dir: &Path) -> Result<String, String> {
    let (manifest, arms) = compare::open(dir).map_err(|e| e.to_string())?;
    let (finished, _) = compare::gather(dir, &manifest, &arms).map_err(|e| e.to_string())?;
    let best = finished
        .iter()
        .max_by(|a, b| a.champion.fitness.total_cmp(&b.champion.fitness))
        .map_or_else(
            || "none yet".to_string(),
            |r| format!("{:.6} ({} rep-{})", r.champion.fitness, r.name, r.k),
        );
    Ok(format!(
        "{}  {}  {}/{} replicates finished  best {best}",
        manifest.names().join(","),
        compare::fitness_labels(&arms),
        finished.len(),
        manifest.replicates * manifest.names().len()
    ))
}
