//! Canalization: a genome that reads no environment is never changed by noise in its array,
//! one that reads a slot near its threshold is; `runs canalization` measures a run's best
//! individuals, the same for a seed on any number of threads, and refuses bad input.

use std::path::{Path, PathBuf};

use crate::util::{ontogeny, ontogeny_command, refused, scratch_dir, stdout, succeeded};

use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome, Rng};
use ontogeny::environment::Environment;
use ontogeny::study::canalization::{Measurement, Settings, generations_measured, measure};
use rand::SeedableRng;

/// The shipped plastic genome: a limb forks where chemical 0 is above 0.5.
fn plastic_example() -> ContinuousGenome {
    let text = std::fs::read_to_string("examples/plastic-genome.lsys").unwrap();
    ContinuousGenome::read_text(&text, &ContinuousLimits::default()).unwrap()
}

fn settings(samples: usize, noise: f64) -> Settings {
    Settings {
        samples,
        noise,
        mutation_rate: 0.1,
        seed: 7,
    }
}

fn measured(genome: &ContinuousGenome, array: f64, noise: f64) -> Measurement {
    measure(
        genome,
        &ContinuousLimits::default(),
        0,
        &[Environment::new(vec![array])],
        &settings(40, noise),
    )
}

#[test]
fn a_genome_without_environment_reads_is_never_changed_by_noise_in_its_array() {
    let limits = ContinuousLimits::default();
    let genome = ContinuousGenome::random(&limits, &mut Rng::seed_from_u64(3));
    assert!(genome.environment().is_empty());
    let m = measured(&genome, 0.5, 0.05);
    assert_eq!(m.arrays_developed, 1);
    assert_eq!(m.noise.changed, Some(0.0));
    assert_eq!(m.noise.failed, Some(0.0));
    assert_eq!(m.noise.mean_parts_change, Some(0.0));
    assert_eq!(m.noise.mean_volume_change, Some(0.0));
}

#[test]
fn a_read_on_a_threshold_near_its_value_changes_the_body_under_noise() {
    let genome = plastic_example();
    // At 0.5 the limbs grow straight; a sample above 0.5 forks both limbs: 7 parts, not 5.
    let near = measured(&genome, 0.5, 0.05);
    let changed = near.noise.changed.unwrap();
    assert!(changed > 0.2 && changed < 0.8, "{near:?}");
    assert_eq!(near.noise.failed, Some(0.0));
    // Every changed sample gained the 2 parts of the forks.
    assert_eq!(near.noise.mean_parts_change, Some(2.0 * changed));
    // Far from the threshold, or without noise, nothing changes.
    assert_eq!(measured(&genome, 0.0, 0.05).noise.changed, Some(0.0));
    assert_eq!(measured(&genome, 0.5, 0.0).noise.changed, Some(0.0));
}

#[test]
fn mutants_shares_are_fractions_and_a_rate_of_0_changes_nothing() {
    let genome = plastic_example();
    let m = measured(&genome, 0.0, 0.05);
    for share in [m.mutation.changed, m.mutation.failed] {
        let share = share.unwrap();
        assert!((0.0..=1.0).contains(&share), "{m:?}");
    }
    assert!(m.mutation.changed.unwrap() >= m.mutation.failed.unwrap());
    // Rate 0 makes mutants identical to the genome: nothing changes.
    let unchanged = measure(
        &genome,
        &ContinuousLimits::default(),
        0,
        &[Environment::new(vec![0.0])],
        &Settings {
            mutation_rate: 0.0,
            ..settings(10, 0.05)
        },
    );
    assert_eq!(unchanged.mutation.changed, Some(0.0));
}

#[test]
fn a_sample_past_the_runs_max_chain_counts_as_failed_as_the_run_would_call_it_invalid() {
    // The hand-written walker (`examples/continuous-walker.lsys`): 10 parts whose longest
    // chain is 3 (a body segment, a hip and its knee; `genome_limits_common`). Under
    // `max_chain = 2` the run calls every creature it develops into invalid, so every noisy
    // sample of its array (it reads none: each is the same body) fails.
    let text = std::fs::read_to_string("examples/continuous-walker.lsys").unwrap();
    let limits = ContinuousLimits {
        max_chain: Some(2),
        ..ContinuousLimits::default()
    };
    let genome = ContinuousGenome::from_lsys(&text, &limits).unwrap();
    let m = measure(
        &genome,
        &limits,
        0,
        &[Environment::new(vec![0.5])],
        &Settings {
            mutation_rate: 0.0,
            ..settings(4, 0.05)
        },
    );
    assert_eq!(m.noise.failed, Some(1.0), "{m:?}");
    assert_eq!(m.mutation.failed, Some(1.0), "{m:?}");
}

#[test]
fn every_k_th_generation_is_measured_and_the_last() {
    assert_eq!(generations_measured(5, 2), [0, 2, 4, 5]);
    assert_eq!(generations_measured(4, 2), [0, 2, 4]);
    assert_eq!(generations_measured(2, 1), [0, 1, 2]);
    assert_eq!(generations_measured(0, 3), [0]);
}

/// A config of `lsystem-continuous` walkers in two habitats that differ in chemical 0,
/// genomes that may read it with chance `reads`: a population of 6, 3 generations of short
/// walks.
fn config(dir: &Path, reads: &str) -> PathBuf {
    let path = dir.join("canalization.toml");
    std::fs::write(
        &path,
        format!(
            "encoding = \"lsystem-continuous\"\nseed = 3\n\n\
             [ga]\npopulation = 6\ngenerations = 3\nenvironment_reads = {reads}\n\n\
             [task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n\
             [[task.habitats]]\nname = \"poor\"\nenvironment = [0]\n\n\
             [[task.habitats]]\nname = \"rich\"\nenvironment = [1]\n"
        ),
    )
    .unwrap();
    path
}

/// A tiny run of `config(reads)` in `dir/run`.
fn tiny_run(dir: &Path, reads: &str) -> PathBuf {
    let run = dir.join("run");
    let o = ontogeny_command()
        .arg("evolve")
        .arg("--config")
        .arg(config(dir, reads))
        .arg("--out")
        .arg(&run)
        .output()
        .unwrap();
    succeeded(&o);
    run
}

fn canalization(run: &Path, extra: &[&str], threads: &str) -> String {
    let o = ontogeny_command()
        .args(["runs", "canalization"])
        .arg(run)
        .args(extra)
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .unwrap();
    succeeded(&o)
}

#[test]
fn a_plastic_run_s_best_individuals_are_measured_generation_by_generation() {
    let dir = scratch_dir("canalization-plastic");
    let run = tiny_run(&dir, "0.5");
    let run_arg = run.to_str().unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&canalization(&run, &["--samples", "8", "--json"], "2")).unwrap();
    assert_eq!(json["samples"], 8);
    assert_eq!(json["noise"], 0.05);
    // The run's own mutation rate (the default preset's).
    assert_eq!(json["mutation_rate"], 0.1);
    let rows = json["generations"].as_array().unwrap();
    let generations: Vec<u64> = rows
        .iter()
        .map(|r| r["generation"].as_u64().unwrap())
        .collect();
    assert_eq!(generations, [0, 1, 2]);
    for row in rows {
        assert_eq!(row["arrays_developed"], 2, "{row}");
        for kind in ["noise", "mutation"] {
            for share in ["changed", "failed"] {
                let v = row[kind][share].as_f64().unwrap();
                assert!((0.0..=1.0).contains(&v), "{kind} {share}: {row}");
            }
            for mean in ["mean_parts_change", "mean_volume_change"] {
                assert!(
                    row[kind][mean].as_f64().unwrap() >= 0.0,
                    "{kind} {mean}: {row}"
                );
            }
        }
    }
    // The best fitness is the run's own, as `runs show --json` gives it.
    let shown: serde_json::Value =
        serde_json::from_str(&stdout(&ontogeny(&["runs", "show", run_arg, "--json"]))).unwrap();
    assert_eq!(rows[2]["best"], shown["generations"][2]["best"]);
    // The table: the settings, two header lines, a row per generation measured.
    let table = canalization(
        &run,
        &["--samples", "4", "--every", "2", "--rate", "0.3"],
        "1",
    );
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(
        lines[0],
        format!(
            "{run_arg}: canalization of each generation's best; 4 sample(s) per array, \
             2 array(s); noise ±0.05 on every slot; mutation rate 0.3; seed 0"
        )
    );
    assert!(lines[2].trim_start().starts_with("gen"), "{table}");
    assert_eq!(lines.len(), 5, "{table}");
    assert!(lines[3].trim_start().starts_with("0 "), "{table}");
    assert!(lines[4].trim_start().starts_with("2 "), "{table}");
    // The CSV: its header, then a row per generation.
    let csv = canalization(&run, &["--samples", "4", "--csv"], "1");
    assert_eq!(
        csv.lines().next().unwrap(),
        ontogeny::study::canalization::CSV_COLUMNS
    );
    assert_eq!(csv.lines().count(), 4);
}

#[test]
fn the_same_seed_gives_the_same_figures_on_any_number_of_threads() {
    let dir = scratch_dir("canalization-threads");
    let run = tiny_run(&dir, "0.5");
    let flags = ["--samples", "6", "--seed", "11", "--csv"];
    let one = canalization(&run, &flags, "1");
    assert_eq!(one, canalization(&run, &flags, "2"));
    assert_eq!(one, canalization(&run, &flags, "3"));
}

#[test]
fn a_run_whose_genomes_read_nothing_shows_no_change_under_noise() {
    let dir = scratch_dir("canalization-fixed");
    let run = tiny_run(&dir, "0");
    let csv = canalization(&run, &["--samples", "10", "--csv"], "2");
    for row in csv.lines().skip(1) {
        let cells: Vec<&str> = row.split(',').collect();
        // noise: changed, failed, mean |Δparts|, mean |ΔV|/V, all exactly 0.
        assert_eq!(cells[3..7], ["0", "0", "0", "0"], "{csv}");
    }
}

#[test]
fn bad_input_is_refused_with_what_is_wrong() {
    let dir = scratch_dir("canalization-refused");
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let empty = empty.to_str().unwrap();
    refused(
        &ontogeny(&["runs", "canalization", empty]),
        "holds no run (no run.sqlite with a run in it)",
    );
    let run = tiny_run(&dir, "0.5");
    let run = run.to_str().unwrap();
    let refuse = |flags: &[&str], message: &str| {
        let mut args = vec!["runs", "canalization", run];
        args.extend_from_slice(flags);
        refused(&ontogeny(&args), message);
    };
    refuse(&["--samples", "0"], "--samples must be at least 1, not 0");
    refuse(
        &["--noise=-0.1"],
        "--noise must be a finite number of 0 or more, not -0.1",
    );
    refuse(
        &["--noise", "NaN"],
        "--noise must be a finite number of 0 or more, not NaN",
    );
    refuse(
        &["--rate", "1.5"],
        "--rate must be between 0 and 1, not 1.5",
    );
    refuse(&["--every", "0"], "--every must be at least 1, not 0");
}
