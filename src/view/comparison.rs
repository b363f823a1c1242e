//! A comparison's page (`ontogeny view COMPARISON_DIR`): its report as `compare` wrote it
//! (`report.md`, and the plots `fitness.svg` and `parts.svg`), and its replicates, each with how
//! far it got and its best, read from its run's store without changing it.

use std::path::Path;

use serde_json::{Value, json};

use super::{ViewError, finite};
use crate::run::store::RunStore;
use crate::study::compare::{self, replicate_dir};

/// The plots a comparison's page shows, by file name, as the server serves them
/// (`/plot/NAME`).
pub const COMPARISON_PLOTS: [&str; 2] = ["fitness.svg", "parts.svg"];

/// Whether `dir` is a comparison directory (it holds `compare.toml`).
pub fn is_comparison(dir: &Path) -> bool {
    dir.join("compare.toml").is_file()
}

/// Reads the comparison in `dir` into the page's data: `{"kind": "comparison", "file",
/// "encodings", "conditions" (one of them empty), "evaluations" (each replicate's budget),
/// "replicates" (per encoding or condition),
/// "fitness" (the task and what its fitness measures), "report" (`report.md`'s text, or null
/// before the first report), "plots" (those of [`COMPARISON_PLOTS`] written), "runs": [{"encoding",
/// "name" (the encoding's or condition's), "k", "dir", "generations" (stored), "best", "best_fine"} (null figures for a replicate not
/// started)]}`.
pub fn comparison_data(dir: &Path) -> Result<Value, ViewError> {
    let (manifest, arms) = compare::open(dir).map_err(|e| ViewError::BadFile(e.to_string()))?;
    let report = match std::fs::read_to_string(dir.join("report.md")) {
        Ok(text) => Value::String(text),
        Err(_) => Value::Null,
    };
    let plots: Vec<&str> = COMPARISON_PLOTS
        .into_iter()
        .filter(|p| dir.join(p).is_file())
        .collect();
    let mut runs = Vec::new();
    for k in 1..=manifest.replicates {
        for arm in &arms {
            let run = replicate_dir(dir, &arm.name, k);
            let mut row = json!({
                "encoding": arm.encoding,
                "name": arm.name,
                "k": k,
                "dir": run.display().to_string(),
                "generations": 0,
                "best": null,
                "best_fine": null,
            });
            if let Ok(store) = RunStore::open_read_only(&run.join("run.sqlite"))
                && let Ok(generations) = store.generations()
                && let Some(last) = generations.last()
            {
                row["generations"] = json!(generations.len());
                row["best"] = finite(last.best);
                row["best_fine"] = last
                    .best_fine
                    .as_ref()
                    .map_or(Value::Null, |f| finite(f.fitness));
            }
            runs.push(row);
        }
    }
    Ok(json!({
        "kind": "comparison",
        "file": dir.display().to_string(),
        "encodings": manifest.encodings,
        "conditions": manifest.conditions,
        "evaluations": manifest.evaluations,
        "replicates": manifest.replicates,
        "fitness": compare::fitness_labels(&arms),
        "report": report,
        "plots": plots,
        "runs": runs,
    }))
}
