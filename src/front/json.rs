//! What the command line says about runs and comparisons as JSON, for scripts: a run's final
//! line (`evolve --json`) and a comparison's summary (`compare --json`), each one object with
//! the figures the text gives, every number in full, and `null` for a number that is not one
//! (NaN: no value).

use std::path::Path;

use serde_json::{Value, json};

use super::text::{RunEnd, RunTally};
use crate::study::compare::{Arm, Report, fitness_labels};

/// `x`, or `null` when it is not finite.
fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// The object `evolve --json` prints at the end of the run `end` says:
/// `{"dir", "encoding", "fitness", "generation", "best", "best_fine": {"fitness",
/// "status"} | null, "evaluations", "simulated", "seconds", "evaluations_per_second",
/// "outside_evaluation" (the share of the time, 0 to 1), "files"}` — the final line's
/// figures.
pub fn run_json(tally: &RunTally, end: &RunEnd<'_>) -> Value {
    let (dir, fitness, encoding) = (end.dir, end.fitness, end.encoding);
    let (extension, last, wall) = (end.extension, end.last, end.wall);
    let best = format!("best.{extension}");
    let files: Vec<String> = ["run.sqlite", "fitness.svg", &best, "log.txt"]
        .iter()
        .map(|f| dir.join(f).display().to_string())
        .collect();
    json!({
        "dir": dir.display().to_string(),
        "encoding": encoding,
        "fitness": fitness,
        "generation": last.generation,
        "best": number(last.stats.best),
        "best_fine": last.stats.best_fine.as_ref().map(|f| json!({
            "fitness": number(f.fitness),
            "status": f.status,
        })),
        "evaluations": tally.evaluations,
        "simulated": tally.evaluations - tally.reused,
        "seconds": wall,
        "evaluations_per_second": tally.evaluations as f64 / wall.max(1e-9),
        "outside_evaluation": (wall - tally.evaluating).max(0.0) / wall.max(1e-9),
        "files": files,
    })
}

/// The object `compare --json` prints: the comparison in `root` (`finished` replicates of
/// `arms` in its report, `unfinished` named) as its summary gives it: `{"dir", "fitness",
/// "evaluations" (each replicate's, in walks: the most of any arm), "replicates",
/// "unfinished", "encodings" (or "conditions", each with "condition" and "encoding"): [{"encoding",
/// "walks", "replicates", "best": {"mean", "sd", "ci95"}, "mean_fine", "fine_replicates",
/// "fine_failed", "median_parts", "median_joints", "median_neurons",
/// "median_repeated", "median_symmetry", "median_description_bytes",
/// "evaluations_per_second", "simulated", "reused"}], "pairs" (of the best fitness) and
/// "fine_pairs" (of the fitness at the fine reference): [{"a", "b", "primary", "u", "p",
/// "holm_p", "a12", "a12_magnitude", "detected", "detectable_a12" (null: none is),
/// "verdict"}], "primary": [a, b] | null, "power": {"replicates", "pairs" (the secondary
/// ones: all without a primary pair), "level", "power", "detectable_a12", "method",
/// "power_at_large", "primary": {"level", "detectable_a12", "power_at_large"} | null,
/// "needed_for_large"} | null, "too_few", "files"}`.
pub fn comparison_json(
    root: &Path,
    arms: &[Arm],
    r: &Report,
    finished: usize,
    unfinished: &[String],
) -> Value {
    let conditions = r.kind == "condition";
    let summaries: Vec<Value> = r
        .arms
        .iter()
        .map(|e| {
            let mut o = json!({
                "encoding": e.encoding,
                "walks": e.walks,
                "replicates": e.replicates,
                "best": {
                    "mean": number(e.best.mean),
                    "sd": number(e.best.sd),
                    "ci95": number(e.best.ci95),
                },
                "mean_fine": number(e.mean_fine),
                "fine_replicates": e.fine_replicates,
                "fine_failed": e.fine_failed,
                "median_parts": number(e.median_parts),
                "median_joints": number(e.median_joints),
                "median_neurons": number(e.median_neurons),
                "median_repeated": number(e.median_repeated),
                "median_symmetry": number(e.median_symmetry),
                "median_description_bytes": number(e.median_description_bytes),
                "evaluations_per_second": number(e.evaluations_per_second),
                "simulated": e.simulated,
                "reused": e.reused,
            });
            if conditions {
                o["condition"] = json!(e.name);
            }
            o
        })
        .collect();
    let pairs = |pairs: &[crate::study::compare::Pair]| -> Vec<Value> {
        pairs
            .iter()
            .map(|p| {
                json!({
                    "a": p.a,
                    "b": p.b,
                    "primary": p.primary,
                    "u": number(p.test.u),
                    "p": number(p.test.p),
                    "holm_p": number(p.holm_p),
                    "a12": number(p.a12),
                    "a12_magnitude": crate::study::stats::a12_magnitude(p.a12),
                    "detected": p.detected(),
                    "detectable_a12": p.detectable.a12().map_or(Value::Null, number),
                    "verdict": p.verdict(),
                })
            })
            .collect()
    };
    let power = r.power.as_ref().map(|w| {
        let secondary = w.secondary_detectable;
        json!({
            "replicates": w.replicates,
            "pairs": w.secondary,
            "level": secondary.map_or(Value::Null, |d| json!(d.level)),
            "power": crate::study::stats::POWER,
            "detectable_a12": secondary.and_then(|d| d.a12()).map_or(Value::Null, number),
            "method": secondary.map_or(Value::Null, |d| json!(d.method.name())),
            "power_at_large": w.secondary_power.map_or(Value::Null, number),
            "primary": w.primary_detectable.map_or(Value::Null, |d| json!({
                "level": d.level,
                "detectable_a12": d.a12().map_or(Value::Null, number),
                "power_at_large": w.primary_power.map_or(Value::Null, number),
            })),
            "needed_for_large": w.needed,
        })
    });
    let files: Vec<String> = ["report.md", "summary.csv", "fitness.svg", "parts.svg"]
        .iter()
        .map(|f| root.join(f).display().to_string())
        .collect();
    let mut out = json!({
        "dir": root.display().to_string(),
        "fitness": fitness_labels(arms),
        "evaluations": r.evaluations,
        "replicates": finished,
        "unfinished": unfinished,
    });
    out[if conditions {
        "conditions"
    } else {
        "encodings"
    }] = json!(summaries);
    for (key, value) in [
        ("pairs", json!(pairs(&r.pairs))),
        ("fine_pairs", json!(pairs(&r.fine_pairs))),
        (
            "primary",
            r.power
                .as_ref()
                .and_then(|w| w.primary.clone())
                .map_or(Value::Null, |(a, b)| json!([a, b])),
        ),
        ("power", json!(power)),
        ("too_few", json!(r.too_few)),
        ("files", json!(files)),
    ] {
        out[key] = value;
    }
    out
}
