//! A comparison's report: each encoding's or condition's figures, the pairwise tests between
//! them with the effect they can detect, and the files that show them (`report.md`,
//! `summary.csv`, `fitness.svg`, `parts.svg`).

use std::fmt::Write as _;
use std::path::Path;

use super::CompareError;
use super::pairs::{Pair, Power, pairwise, planned_power, power_note};
use super::plan::{Arm, Manifest, walks_per_individual};
use super::replicate::{Champion, Replicate};
use crate::run::plot::{self, Band};
use crate::study::stats;

/// One encoding's or condition's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmSummary {
    /// The encoding's or condition's name.
    pub name: String,
    /// Its encoding.
    pub encoding: String,
    /// The walks each of its replicates makes ([`Arm::walks`]).
    pub walks: u64,
    /// Finished replicates.
    pub replicates: usize,
    /// The replicates' best fitness.
    pub best: stats::Summary,
    /// The mean of the replicates' final champions re-walked at the fine reference setting
    /// ([`Champion::fine_fitness`]), over those that were and whose re-walk did not fail (NaN
    /// if none): a failed re-walk scores the failure floor, which would swamp the mean.
    pub mean_fine: f64,
    /// How many replicates' champions were re-walked at the fine reference.
    pub fine_replicates: usize,
    /// How many of those re-walks failed (scored the failure floor: unstable, exploded, ...).
    pub fine_failed: usize,
    /// The champions' median parts, joints and neurons.
    pub median_parts: f64,
    /// See `median_parts`.
    pub median_joints: f64,
    /// See `median_parts`.
    pub median_neurons: f64,
    /// The champions' median share of parts in repeated sub-assemblies
    /// ([`Regularity::repeated`](crate::creature::Regularity::repeated); higher is more
    /// regular).
    pub median_repeated: f64,
    /// The champions' median share of parts with a mirror partner
    /// ([`Regularity::symmetry`](crate::creature::Regularity::symmetry); higher is more
    /// regular).
    pub median_symmetry: f64,
    /// The champions' median compressed description in bytes per part
    /// ([`Regularity::description_bytes`](crate::creature::Regularity::description_bytes);
    /// lower is more regular).
    pub median_description_bytes: f64,
    /// Evaluations per second over all its replicates.
    pub evaluations_per_second: f64,
    /// Evaluations its replicates simulated, in all.
    pub simulated: u64,
    /// Evaluations its replicates reused from an identical creature evaluated earlier in the
    /// same run, in all.
    pub reused: u64,
}

/// The fewest replicates of an encoding that statistics are given for: below it, an
/// encoding's figures have no spread (standard deviation, confidence interval) and its pairs
/// are not tested.
pub const MIN_REPLICATES_FOR_STATISTICS: usize = 2;

/// The report's numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// What is compared: "encoding" or "condition" ([`Manifest::kind`]).
    pub kind: &'static str,
    /// Per encoding or condition, in the manifest's order.
    pub arms: Vec<ArmSummary>,
    /// The tests of the best fitness between every pair of encodings with at least
    /// [`MIN_REPLICATES_FOR_STATISTICS`] replicates each, in the manifest's order.
    pub pairs: Vec<Pair>,
    /// The same pairs' tests of their champions' fitness at the fine reference
    /// ([`fine_sample`]), between those with at least [`MIN_REPLICATES_FOR_STATISTICS`]
    /// champions re-walked each.
    pub fine_pairs: Vec<Pair>,
    /// The encodings with fewer than [`MIN_REPLICATES_FOR_STATISTICS`] replicates: no
    /// statistics, and no test of their pairs.
    pub too_few: Vec<String>,
    /// The walks every replicate made (of the arm that made most, when they differ).
    pub evaluations: u64,
    /// The comparison's power as planned: the effect each pair detects with the planned
    /// replicates on every side and every pair tested, the primary pair apart; `None` with one
    /// side only.
    pub power: Option<Power>,
}

/// The values the fine-reference tests compare: the champions' fitness re-walked at the fine
/// reference, leaving out the champions not re-walked (NaN: runs that predate it). A re-walk
/// that failed (unstable, exploded: the failure floor, [`crate::task::FAILURE_FITNESS`]) keeps
/// its floor, below every fitness: it ranks lowest, tied with the other failures.
pub fn fine_sample(replicates: &[&Replicate]) -> Vec<f64> {
    replicates
        .iter()
        .map(|r| r.champion.fine_fitness)
        .filter(|f| !f.is_nan())
        .map(|f| f.max(crate::task::FAILURE_FITNESS))
        .collect()
}

/// The statistics of `replicates` (finished ones, any order) of the comparison of `arms`.
pub fn report(manifest: &Manifest, arms: &[Arm], replicates: &[Replicate]) -> Report {
    let of = |e: &str| -> Vec<&Replicate> {
        let mut v: Vec<&Replicate> = replicates.iter().filter(|r| r.name == e).collect();
        v.sort_by_key(|r| r.k);
        v
    };
    let summaries = arms
        .iter()
        .map(|arm| {
            let rs = of(&arm.name);
            let pick = |f: fn(&Champion) -> f64| {
                stats::median(&rs.iter().map(|r| f(&r.champion)).collect::<Vec<_>>())
            };
            let evaluations: u64 = rs.iter().map(|r| r.evaluations).sum();
            let reused: u64 = rs.iter().map(|r| r.reused).sum();
            let wall: f64 = rs.iter().map(|r| r.wall_seconds).sum();
            let walked: Vec<f64> = rs
                .iter()
                .map(|r| r.champion.fine_fitness)
                .filter(|f| !f.is_nan())
                .collect();
            let fine: Vec<f64> = walked
                .iter()
                .copied()
                .filter(|&f| f > crate::task::FAILURE_FITNESS)
                .collect();
            ArmSummary {
                name: arm.name.clone(),
                encoding: arm.encoding.clone(),
                walks: arm.walks(),
                replicates: rs.len(),
                best: stats::summary(&rs.iter().map(|r| r.champion.fitness).collect::<Vec<_>>()),
                mean_fine: if fine.is_empty() {
                    f64::NAN
                } else {
                    fine.iter().sum::<f64>() / fine.len() as f64
                },
                fine_replicates: walked.len(),
                fine_failed: walked.len() - fine.len(),
                median_parts: pick(|c| c.parts as f64),
                median_joints: pick(|c| c.joints as f64),
                median_neurons: pick(|c| c.neurons as f64),
                median_repeated: pick(|c| c.regularity.repeated),
                median_symmetry: pick(|c| c.regularity.symmetry),
                median_description_bytes: pick(|c| c.regularity.description_bytes),
                evaluations_per_second: if wall > 0.0 {
                    evaluations as f64 / wall
                } else {
                    f64::NAN
                },
                simulated: evaluations.saturating_sub(reused),
                reused,
            }
        })
        .collect::<Vec<ArmSummary>>();
    let too_few: Vec<String> = summaries
        .iter()
        .filter(|e| e.replicates < MIN_REPLICATES_FOR_STATISTICS)
        .map(|e| e.name.clone())
        .collect();
    let names = manifest.names();
    let pairs = pairwise(names, &too_few, &manifest.primary, |e| {
        of(e).iter().map(|r| r.champion.fitness).collect()
    });
    // An arm with too few champions re-walked has no fine-reference test.
    let mut too_few_fine = too_few.clone();
    too_few_fine.extend(
        summaries
            .iter()
            .filter(|e| e.fine_replicates < MIN_REPLICATES_FOR_STATISTICS)
            .map(|e| e.name.clone()),
    );
    let fine_pairs = pairwise(names, &too_few_fine, &manifest.primary, |e| {
        fine_sample(&of(e))
    });
    Report {
        kind: manifest.kind(),
        pairs,
        fine_pairs,
        too_few,
        evaluations: summaries.iter().map(|a| a.walks).max().unwrap_or(0),
        arms: summaries,
        power: planned_power(names.len(), manifest.replicates, &manifest.primary),
    }
}

/// Writes `text` to `path` whole or not at all ([`crate::output::write`]): a reader never sees
/// half a report.
fn write_file(path: &Path, text: &str) -> Result<(), CompareError> {
    Ok(crate::output::write(path, text)?)
}

/// A number for a table: NaN as "–".
fn num(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        "–".to_string()
    }
}

/// Writes `report.md`, `summary.csv`, `fitness.svg` and `parts.svg` into `root`.
/// `unfinished` lists the replicates not (yet) in the report.
pub fn write_report(
    root: &Path,
    manifest: &Manifest,
    arms: &[Arm],
    replicates: &[Replicate],
    unfinished: &[String],
) -> Result<Report, CompareError> {
    let r = report(manifest, arms, replicates);
    let mut md = String::new();
    let first = &arms
        .first()
        .ok_or_else(|| CompareError::Input("a comparison of nothing".into()))?
        .settings;
    let preset = |ga: &crate::evolve::ga::GaSettings| {
        serde_json::to_value(ga.preset)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    };
    if manifest.conditions.is_empty() {
        let task = first.task.task.name();
        let _ = writeln!(
            md,
            "# Comparison of {} on the {task} task\n\nFitness: {}.\n",
            manifest.encodings.join(", "),
            first.task.fitness_label()
        );
        let walks = walks_per_individual(&first.task);
        // `r.evaluations` counts walks.
        let made = if walks == 1 {
            format!("{} evaluations", r.evaluations)
        } else {
            format!(
                "{} walks, {} evaluations of {walks} walks each",
                r.evaluations,
                r.evaluations / walks
            )
        };
        let _ = writeln!(
            md,
            "{} replicate{} per encoding, seed {}; every replicate made exactly {made} \
             (budget {}{}: population {}, {} generations, elite {} not re-evaluated; preset {}).\n",
            manifest.replicates,
            if manifest.replicates == 1 { "" } else { "s" },
            manifest.seed,
            manifest.evaluations,
            if walks == 1 { "" } else { " walks" },
            first.ga.population,
            first.ga.generations,
            first.ga.survivors(),
            preset(&first.ga)
        );
    } else {
        let _ = writeln!(
            md,
            "# Comparison of the conditions {}\n\n{} replicate{} per condition, seed {} \
             (replicate k of every condition has the same seed); a budget of {} walks per \
             replicate (evaluations times walks per individual; an evaluation reused from an \
             identical creature counts as the walk it stands for), spent in whole generations: \
             every replicate of a condition made exactly its walks below (the elite is not \
             re-evaluated).\n",
            manifest.conditions.join(", "),
            manifest.replicates,
            if manifest.replicates == 1 { "" } else { "s" },
            manifest.seed,
            manifest.evaluations,
        );
        let rows = arms.iter().map(|a| {
            let g = &a.settings.ga;
            vec![
                a.name.clone(),
                a.encoding.clone(),
                a.settings.task.fitness_label(),
                g.population.to_string(),
                g.generations.to_string(),
                g.survivors().to_string(),
                preset(g),
                walks_per_individual(&a.settings.task).to_string(),
                a.walks().to_string(),
            ]
        });
        markdown_table(
            &mut md,
            &[
                "condition",
                "encoding",
                "fitness",
                "population",
                "generations",
                "elite",
                "preset",
                "walks per individual",
                "walks",
            ],
            rows,
        );
        let _ = writeln!(md);
    }
    if !unfinished.is_empty() {
        let _ = writeln!(
            md,
            "**Incomplete**: not in this report: {}.\n",
            unfinished.join(", ")
        );
    }
    let _ = writeln!(
        md,
        "Best fitness of each replicate: mean, sample standard deviation and the 95% confidence \
         interval of the mean (Student's t). Champions (each replicate's best individual): \
         median parts, joints and neurons, and three median measures of how regular their \
         bodies are (see Regularity below). \"At the fine reference\": the mean of the replicates' final \
         champions walked again with 4 physics substeps of 8 solver iterations (the stored \
         best comes from the run's own stepping, 4 substeps of 4 iterations by default; a \
         much lower value means the champions exploit it, or were lucky), over the replicates that recorded it when fewer. \
         Simulated and reused: the evaluations of all its replicates, split into those \
         simulated and those that reused the evaluation of an identical creature earlier in \
         the same run.\n"
    );
    let rows = r.arms.iter().map(|e| {
        vec![
            e.name.clone(),
            e.replicates.to_string(),
            num(e.best.mean, 4),
            fine_cell(e),
            num(e.best.sd, 4),
            format!(
                "{} to {}",
                num(e.best.mean - e.best.ci95, 4),
                num(e.best.mean + e.best.ci95, 4)
            ),
            num(e.median_parts, 1),
            num(e.median_joints, 1),
            num(e.median_neurons, 1),
            num(e.median_repeated, 2),
            num(e.median_symmetry, 2),
            num(e.median_description_bytes, 1),
            e.simulated.to_string(),
            e.reused.to_string(),
            num(e.evaluations_per_second, 1),
        ]
    });
    markdown_table(
        &mut md,
        &[
            r.kind,
            "n",
            "mean best",
            "at the fine reference",
            "sd",
            "95% CI",
            "parts",
            "joints",
            "neurons",
            "repeated",
            "mirrored",
            "bytes/part",
            "simulated",
            "reused",
            "evaluations/s",
        ],
        rows,
    );
    if !r.too_few.is_empty() {
        let _ = writeln!(md, "\n**No statistics** {}.", too_few_note(&r.too_few));
    }
    let _ = writeln!(
        md,
        "\nRegularity (of each champion's body, developed again from its genome; medians \
         above): **repeated**, the share of parts whose sub-assembly (the part with its joints \
         and children, lengths divided by its longest edge and rounded to {step}) is another \
         part's too, higher is more regular (a chain of n equal segments scores (n − 1)/n); \
         **mirrored**, the share of parts with a mirror partner of the same edges across the \
         best of the root's three planes (centres and edges within {tol} of the root's \
         longest edge), higher is more regular (the root is its own partner, so a one-part body \
         scores 1); **bytes/part**, the deflate-compressed size of the body's canonical \
         description (its tree, children sorted, lengths rounded) per part, lower is more \
         regular.",
        step = crate::creature::LENGTH_STEP,
        tol = crate::creature::MIRROR_TOLERANCE,
    );
    let primary = match manifest.primary.as_slice() {
        [a, b] => format!(
            "The primary pair, {a} against {b}, is tested alone at {}; the other (secondary) \
             pairs are Holm-corrected among themselves. ",
            stats::ALPHA
        ),
        _ => String::new(),
    };
    for (pairs, what) in [
        (&r.pairs, "the best fitness (stored)"),
        (
            &r.fine_pairs,
            "the champions' fitness at the fine reference (a champion not re-walked is left \
             out; a re-walk that failed keeps the failure floor and ranks lowest, tied with \
             any other failure, which forces the normal approximation)",
        ),
    ] {
        if pairs.is_empty() {
            continue;
        }
        let _ = writeln!(
            md,
            "\nPairwise two-sided Mann–Whitney U tests of {what} (exact distribution without \
             ties and up to {} replicates, else the normal approximation with tie and continuity \
             corrections). {primary}Holm p: the p the verdict reads (Holm-corrected over the \
             pairs it is tested with; the primary pair's own). A12 is Vargha and Delaney's \
             probability that a replicate of the first {} beats one of the second (0.5: no \
             effect); detectable: the smallest A12 the pair's test detects with probability {} \
             (see Power below).\n",
            stats::EXACT_MAX,
            r.kind,
            stats::POWER,
        );
        pair_table(&mut md, pairs);
    }
    if let Some(power) = &r.power {
        let mut note = power_note(power, r.kind);
        if !unfinished.is_empty() {
            note.push_str(
                " That is the power as planned: this report is incomplete, and each pair's own \
                 detectable effect, at the replicates it has, is in its table.",
            );
        }
        let _ = writeln!(md, "\n{note}");
    }
    let _ = writeln!(
        md,
        "\n![mean best fitness against evaluations](fitness.svg)\n\n![champions' parts](parts.svg)"
    );
    write_file(&root.join("report.md"), &md)?;

    let mut csv = format!(
        "{},replicate,seed,evaluations,best_fitness,best_fine,parts,joints,neurons,repeated,mirrored,bytes_per_part,simulated,reused,wall_seconds\n",
        r.kind
    );
    let mut sorted: Vec<&Replicate> = replicates.iter().collect();
    let position = |e: &str| manifest.names().iter().position(|x| x == e);
    sorted.sort_by_key(|r| (position(&r.name), r.k));
    for rep in sorted {
        let c = &rep.champion;
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.3}",
            rep.name,
            rep.k,
            rep.seed,
            rep.evaluations,
            c.fitness,
            c.fine_fitness,
            c.parts,
            c.joints,
            c.neurons,
            c.regularity.repeated,
            c.regularity.symmetry,
            c.regularity.description_bytes,
            rep.evaluations - rep.reused,
            rep.reused,
            rep.wall_seconds
        );
    }
    write_file(&root.join("summary.csv"), &csv)?;

    let bands: Vec<Band> = arms
        .iter()
        .map(|a| {
            let walks = walks_per_individual(&a.settings.task);
            band(&a.name, replicates, a.settings.task.fitness_floor(), walks)
        })
        .collect();
    // The task's name, or "conditions" when they do not share one.
    let task = if arms
        .iter()
        .all(|a| a.settings.task.kind() == first.task.kind())
    {
        first.task.task.name()
    } else {
        "conditions"
    };
    let title = format!("{task}: mean best fitness with 95% confidence bands");
    let y_desc = first.task.fitness_measure();
    plot::bands_svg(&root.join("fitness.svg"), &bands, &title, &y_desc)?;
    let parts: Vec<(String, Vec<f64>)> = manifest
        .names()
        .iter()
        .map(|e| {
            let mut v: Vec<(usize, f64)> = replicates
                .iter()
                .filter(|r| &r.name == e)
                .map(|r| (r.k, r.champion.parts as f64))
                .collect();
            v.sort_by_key(|x| x.0);
            (e.clone(), v.into_iter().map(|x| x.1).collect())
        })
        .collect();
    plot::strip_svg(
        &root.join("parts.svg"),
        &parts,
        "parts",
        &format!("{task}: the champions' parts (bar: median)"),
    )?;
    Ok(r)
}

/// Why `names` (encodings or conditions) have no statistics, after "no statistics": for the
/// report and the summary.
pub fn too_few_note(names: &[String]) -> String {
    format!(
        "for {}: fewer than {MIN_REPLICATES_FOR_STATISTICS} finished replicates, so no standard deviation, \
         confidence interval or pairwise test (run more with `--replicates`)",
        names.join(", ")
    )
}

/// The mean best-so-far fitness of the replicates of `name` after each generation, against
/// the walks made (evaluations times `walks` per individual), with its 95% confidence band
/// (the band is the mean where fewer than 2 replicates exist), held at or above `floor`, the
/// lowest fitness the task can score, when it has one.
fn band(name: &str, replicates: &[Replicate], floor: Option<f64>, walks: u64) -> Band {
    let rs: Vec<&Replicate> = replicates.iter().filter(|r| r.name == name).collect();
    let points = rs.first().map_or(0, |r| r.curve.len());
    let mut out = Vec::with_capacity(points);
    for g in 0..points {
        let values: Vec<f64> = rs
            .iter()
            .filter_map(|r| r.curve.get(g))
            .map(|p| p.1)
            .collect();
        let s = stats::summary(&values);
        let half = if s.ci95.is_finite() { s.ci95 } else { 0.0 };
        out.push((
            (rs[0].curve[g].0 * walks) as f64,
            s.mean,
            floor.map_or(s.mean - half, |floor| (s.mean - half).max(floor)),
            s.mean + half,
        ));
    }
    Band {
        name: name.to_string(),
        points: out,
    }
}

/// The report's "at the fine reference" cell: the champions' mean re-walked at the fine
/// reference, saying over how many replicates when not all, and how many failed.
fn fine_cell(e: &ArmSummary) -> String {
    let mean = num(e.mean_fine, 4);
    match (
        e.fine_replicates == e.replicates || e.fine_replicates == 0,
        e.fine_failed,
    ) {
        (true, 0) => mean,
        (false, 0) => format!("{mean} ({} of {})", e.fine_replicates, e.replicates),
        (_, failed) => format!(
            "{mean} ({} of {}; {failed} failed)",
            e.fine_replicates - failed,
            e.replicates
        ),
    }
}

/// Appends the table of `pairs`' tests (with a column saying which is the primary pair, when
/// one is).
fn pair_table(md: &mut String, pairs: &[Pair]) {
    let primary = pairs.iter().any(|p| p.primary);
    let rows = pairs.iter().map(|p| {
        let mut row = vec![
            p.a.clone(),
            p.b.clone(),
            num(p.test.u, 1),
            num(p.test.p, 4),
            p.test.method.name().to_string(),
            num(p.holm_p, 4),
            num(p.a12, 3),
            stats::a12_magnitude(p.a12).to_string(),
            p.detectable
                .a12()
                .map_or_else(|| "none".to_string(), |a| format!("{a:.2}")),
            p.verdict(),
        ];
        if primary {
            row.insert(2, if p.primary { "primary" } else { "secondary" }.into());
        }
        row
    });
    let mut header = vec![
        "a",
        "b",
        "U",
        "p",
        "method",
        "Holm p",
        "A12",
        "effect",
        "detectable",
        "verdict",
    ];
    if primary {
        header.insert(2, "test");
    }
    markdown_table(md, &header, rows);
}

/// Appends a Markdown table: its header, the separator line, one line per row.
fn markdown_table(md: &mut String, header: &[&str], rows: impl Iterator<Item = Vec<String>>) {
    let _ = writeln!(md, "| {} |", header.join(" | "));
    let _ = writeln!(md, "|{}", "---|".repeat(header.len()));
    for row in rows {
        let _ = writeln!(md, "| {} |", row.join(" | "));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::compare::chaumont_ga as ga;
    use crate::study::compare::{Shared, encoding_arms};
    use crate::task::TaskSpec;

    fn replicate(name: &str, k: usize, best: f64, parts: u32) -> Replicate {
        Replicate {
            name: name.into(),
            k,
            seed: k as u64,
            curve: vec![(6, best / 2.0), (11, best)],
            evaluations: 11,
            reused: 1,
            wall_seconds: 2.0,
            champion: Champion {
                fitness: best,
                fine_fitness: best / 4.0,
                parts,
                joints: parts.saturating_sub(1),
                neurons: 2 * parts,
                regularity: crate::creature::Regularity {
                    repeated: 0.5,
                    symmetry: 1.0,
                    description_bytes: 20.0,
                },
            },
        }
    }

    #[test]
    fn the_report_by_hand() {
        let manifest = Manifest {
            encodings: vec!["a".into(), "b".into(), "c".into()],
            conditions: vec![],
            replicates: 3,
            evaluations: 11,
            seed: 1,
            primary: vec![],
        };
        let shared = Shared {
            ga: ga(6, 2),
            task: TaskSpec::new(crate::task::TaskKind::Walker),
        };
        // Replicate 1 of c was not re-walked at the fine reference (an old run).
        let mut unverified = replicate("c", 1, 1.5, 1);
        unverified.champion.fine_fitness = f64::NAN;
        // b's third champion did not come to rest at the fine reference: the failure floor.
        let mut failed = replicate("b", 3, 6.0, 2);
        failed.champion.fine_fitness = crate::task::FAILURE_FITNESS;
        let reps = vec![
            replicate("a", 1, 1.0, 3),
            replicate("a", 2, 2.0, 5),
            replicate("a", 3, 3.0, 9),
            replicate("b", 1, 4.0, 1),
            replicate("b", 2, 5.0, 1),
            failed,
            unverified,
            replicate("c", 2, 2.5, 1),
            replicate("c", 3, 3.5, 2),
        ];
        let r = report(&manifest, &encoding_arms(&manifest, &shared), &reps);
        assert_eq!(r.evaluations, 11);
        let a = &r.arms[0];
        assert_eq!(a.replicates, 3);
        assert_eq!(a.best.mean, 2.0);
        assert_eq!(a.best.sd, 1.0);
        // The fine reference values 1/4, 2/4, 3/4: mean 0.5.
        assert_eq!((a.mean_fine, a.fine_replicates), (0.5, 3));
        // c's over its two verified replicates: (2.5 + 3.5) / 4 / 2.
        let c = &r.arms[2];
        assert_eq!((c.mean_fine, c.fine_replicates), (0.75, 2));
        // b's over the two re-walks that did not fail: (4 + 5) / 4 / 2; one failed.
        let b = &r.arms[1];
        assert_eq!(
            (b.mean_fine, b.fine_replicates, b.fine_failed),
            (1.125, 3, 1)
        );
        assert_eq!((a.fine_failed, c.fine_failed), (0, 0));
        assert_eq!(a.median_parts, 5.0);
        assert_eq!(a.median_joints, 4.0);
        assert_eq!(a.median_neurons, 10.0);
        // 33 evaluations in 6 s.
        assert_eq!(a.evaluations_per_second, 5.5);
        // Of which one per replicate reused.
        assert_eq!((a.simulated, a.reused), (30, 3));
        // a against b: every b beats every a: U = 0, exact p = 2/C(6, 3) = 0.1, A12 = 0.
        let ab = &r.pairs[0];
        assert_eq!((ab.a.as_str(), ab.b.as_str()), ("a", "b"));
        assert_eq!(ab.test.u, 0.0);
        assert!((ab.test.p - 0.1).abs() < 1e-12);
        assert_eq!(ab.a12, 0.0);
        // a against c: a's 1, 2, 3 against 1.5, 2.5, 3.5: U = 0 + 1 + 2 = 3, A12 = 3/9.
        let ac = &r.pairs[1];
        assert_eq!(ac.test.u, 3.0);
        assert!((ac.a12 - 1.0 / 3.0).abs() < 1e-12);
        // b against c: U = 9, p = 0.1. Holm over p = (0.1, p_ac, 0.1): p_ac = 0.7 (U = 3 of
        // 9: P(U ≤ 3) = 7/20 = 0.35, twice 0.7); sorted 0.1·3, 0.1·2 → 0.3, 0.3; 0.7.
        assert!((ac.test.p - 0.7).abs() < 1e-12, "{}", ac.test.p);
        assert!((r.pairs[0].holm_p - 0.3).abs() < 1e-12);
        assert!((r.pairs[2].holm_p - 0.3).abs() < 1e-12);
        assert!((r.pairs[1].holm_p - 0.7).abs() < 1e-12);
        // Three replicates a side cannot reach p ≤ 0.05/3: nothing is detectable, and each
        // pair says so rather than "no difference".
        let power = r.power.clone().unwrap();
        let d = power.secondary_detectable.unwrap();
        assert_eq!((d.distance, d.m, d.level), (None, 3, 0.05 / 3.0));
        assert_eq!(power.primary, None);
        assert!(!ab.detected());
        assert_eq!(
            ab.verdict(),
            "not detected at this power (none is detectable with 3 and 3 replicates)"
        );
        assert!(power_note(&power, r.kind).contains("each pair is tested at 0.05 / 3 = 0.0167"));
        // The fine reference: a's 0.25, 0.5, 0.75 against b's 1, 1.25 and the failure floor,
        // which ranks lowest: U of a = 3 (each of a's beats the failure), A12 = 3/9; the tie-free
        // exact p = 2 · P(U ≤ 3) = 0.7. c has two re-walked champions: tested on those.
        let fine_ab = &r.fine_pairs[0];
        assert_eq!(fine_ab.test.u, 3.0);
        assert!((fine_ab.test.p - 0.7).abs() < 1e-12);
        assert_eq!(r.fine_pairs.len(), 3);
        assert_eq!(r.fine_pairs[1].detectable.n, 2);
        // The regularity medians.
        assert_eq!((a.median_repeated, a.median_symmetry), (0.5, 1.0));
        // The band: the mean of the best so far, 1, 2, 3 → 2 ± t(2)·1/√3.
        let b = band("a", &reps, None, 1);
        assert_eq!(b.points.len(), 2);
        assert_eq!(b.points[1].0, 11.0);
        assert_eq!(b.points[1].1, 2.0);
        let half = stats::t_quantile_975(2) / 3f64.sqrt();
        assert!((b.points[1].3 - 2.0 - half).abs() < 1e-12);
        // 2 − 2.48 is below 0: a fitness that cannot be negative has its band held at 0.
        assert!(b.points[1].2 < 0.0);
        let held = band("a", &reps, Some(0.0), 1);
        assert_eq!(held.points[1].2, 0.0);
        assert_eq!(held.points[1].3, b.points[1].3);
    }
}
