//! Plasticity: `runs plasticity` walks each champion again in each habitat (the figures a
//! fresh `eval` and the run's store give), groups habitats into cues by their chemical array,
//! tells a body that depends on the cue from one that does not, and refuses bad input.

use std::path::{Path, PathBuf};

use crate::util::{ontogeny, ontogeny_command, refused, scratch_dir, stdout, succeeded};

use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome};
use ontogeny::evolve::habitats::develop_in_habitats;
use ontogeny::run::config::read_task_config;
use ontogeny::study::plasticity::{Norm, cues_of, reaction_norm};

/// The shipped plastic genome's text: a limb forks where chemical 0 is above 0.5.
fn plastic_text() -> String {
    std::fs::read_to_string("examples/plastic-genome.lsys").unwrap()
}

/// The reaction norm of the genome `text` under the habitats of the shipped config `config`.
fn norm_of(text: &str, config: &str) -> (Vec<ontogeny::study::plasticity::CueMorph>, Option<Norm>) {
    let limits = ContinuousLimits::default();
    let genome = ContinuousGenome::read_text(text, &limits).unwrap();
    let task = read_task_config(Path::new(config)).unwrap();
    let creatures = develop_in_habitats(&genome, &limits, 0, &task).unwrap();
    reaction_norm(&task, &creatures)
}

#[test]
fn a_genome_that_reads_the_cue_grows_two_morphs_and_one_that_does_not_grows_one() {
    let (cues, norm) = norm_of(&plastic_text(), "examples/plasticity-plastic.toml");
    // Cue 0 (flat): straight limbs, each a part and its growing tip: 5 parts, 4 hinges, 5
    // neurons. Cue 1 (steps): each limb forks into two rigid tips of 0.3 m: 7 parts, 2 hinges
    // and 4 rigid joints, 3 neurons.
    let counts: Vec<(usize, usize, usize)> = cues
        .iter()
        .map(|c| (c.parts, c.joints, c.neurons))
        .collect();
    assert_eq!(counts, [(5, 4, 5), (7, 6, 3)]);
    assert_eq!(cues[0].habitats, ["flat"]);
    assert_eq!(cues[1].habitats, ["steps"]);
    // Parts 0.25 m thick and wide: lengths 0.5 + 2 × (0.5 + 0.5) = 2.5 m against
    // 0.5 + 2 × (0.5 + 0.3 + 0.3) = 2.7 m, volumes 0.15625 and 0.16875 m³.
    assert!((cues[0].volume - 0.15625).abs() < 1e-12, "{cues:?}");
    assert!((cues[1].volume - 0.16875).abs() < 1e-12, "{cues:?}");
    // The turtle turns about the vertical only: both morphs lie flat, as high as a part is
    // thick.
    assert!((cues[0].height - 0.25).abs() < 1e-12, "{cues:?}");
    assert!((cues[1].height - 0.25).abs() < 1e-12, "{cues:?}");
    let norm = norm.unwrap();
    assert!(norm.depends_on_cue);
    assert_eq!(norm.parts_change, 2.0);
    assert_eq!(norm.joints_change, 2.0);
    assert_eq!(norm.neurons_change, 2.0);
    assert!((norm.volume_change - 0.08).abs() < 1e-12, "{norm:?}");
    // The parts of the same id: two 0.5 m tips against two 0.3 m forks, 0.2 m shorter each.
    assert!((norm.size_change - 0.4).abs() < 1e-12, "{norm:?}");

    // Without its reads (the rule that branches on the cue, and the reads before the
    // maturing tokens), the same body under both cues.
    let text = plastic_text();
    let deaf: String = text
        .lines()
        .filter(|l| !l.starts_with("?E(1, 0, c) < mforward(x)") && *l != "environment: 0")
        .map(|l| l.replace("?E(1, 0, 0) ", ""))
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(deaf, text);
    let (cues, norm) = norm_of(&deaf, "examples/plasticity-plastic.toml");
    assert_eq!(cues[0].parts, cues[1].parts);
    assert_eq!(norm, Some(Norm::default()));
}

#[test]
fn the_random_cue_s_four_habitats_are_two_cues_and_its_norm_is_between_the_values() {
    let task = read_task_config(Path::new("examples/plasticity-random-cue.toml")).unwrap();
    assert_eq!(
        cues_of(&task),
        [(Some(vec![0.0]), vec![0, 2]), (Some(vec![1.0]), vec![1, 3])]
    );
    let (cues, norm) = norm_of(&plastic_text(), "examples/plasticity-random-cue.toml");
    assert_eq!(cues.len(), 2);
    assert_eq!(cues[0].habitats, ["flat-0", "steps-0"]);
    assert_eq!(cues[1].habitats, ["flat-1", "steps-1"]);
    assert_eq!(norm.unwrap().parts_change, 2.0);
}

/// `examples/plasticity-NAME.toml` cut down for a test: a population of 6, walks of 1 s.
fn small_config(dir: &Path, name: &str) -> PathBuf {
    let text = std::fs::read_to_string(format!("examples/plasticity-{name}.toml"))
        .unwrap()
        .replace("population = 40", "population = 6")
        .replace("seconds = 10", "seconds = 1");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A comparison of the conditions plastic and random-cue, 2 replicates each, 2 generations.
fn tiny_comparison(name: &str) -> PathBuf {
    let dir = scratch_dir(name);
    let out = dir.join("cmp");
    let mut command = ontogeny_command();
    command.arg("compare");
    for condition in ["fixed", "random-cue"] {
        let config = small_config(&dir, condition);
        command
            .arg("--condition")
            .arg(format!("{condition}={}", config.display()));
    }
    // Walks per individual: 2 habitats × 2 trials (fixed), 4 × 1 (random-cue); 2
    // generations of 6 individuals, the second without its elite.
    let o = command
        .args([
            "--replicates",
            "2",
            "--evaluations",
            "44",
            "--seed",
            "1",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&o);
    out
}

fn plasticity(dir: &Path, flags: &[&str]) -> String {
    let o = ontogeny_command()
        .args(["runs", "plasticity"])
        .arg(dir)
        .args(flags)
        .output()
        .unwrap();
    succeeded(&o)
}

#[test]
fn each_champion_s_fitness_per_habitat_is_a_fresh_eval_s_and_the_stored_one() {
    let cmp = tiny_comparison("plasticity-comparison");
    let json: serde_json::Value = serde_json::from_str(&plasticity(&cmp, &["--json"])).unwrap();
    let conditions = json["conditions"].as_array().unwrap();
    let names: Vec<&str> = conditions
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["fixed", "random-cue"]);
    for condition in conditions {
        let champions = condition["champions"].as_array().unwrap();
        let runs: Vec<&str> = champions
            .iter()
            .map(|c| c["run"].as_str().unwrap())
            .collect();
        assert_eq!(runs, ["rep-1", "rep-2"]);
        for champion in champions {
            let best = Path::new(champion["dir"].as_str().unwrap()).join("best.lsys");
            for habitat in champion["habitats"].as_array().unwrap() {
                let name = habitat["name"].as_str().unwrap();
                let eval: serde_json::Value = serde_json::from_str(&stdout(&ontogeny(&[
                    "eval",
                    best.to_str().unwrap(),
                    "--habitat",
                    name,
                    "--json",
                ])))
                .unwrap();
                assert_eq!(habitat["fitness"], eval["fitness"], "{name}: {champion}");
                assert_eq!(habitat["stored"], habitat["fitness"], "{name}: {champion}");
            }
            // The mean of the habitats' means is the fitness the run stored (equal trials in
            // every habitat).
            let habitats = champion["habitats"].as_array().unwrap();
            let mean = habitats
                .iter()
                .map(|h| h["fitness"].as_f64().unwrap())
                .sum::<f64>()
                / habitats.len() as f64;
            let stored = champion["fitness"].as_f64().unwrap();
            assert!((mean - stored).abs() < 1e-12, "{champion}");
        }
    }
    // The fixed condition's genomes read nothing: no body depends on the cue.
    let fixed = &conditions[0];
    for champion in fixed["champions"].as_array().unwrap() {
        assert_eq!(champion["norm"]["depends_on_cue"], false, "{champion}");
        assert_eq!(champion["norm"]["size_change"], 0.0, "{champion}");
    }
    assert_eq!(fixed["summary"]["share_depending"], 0.0);
    assert_eq!(fixed["summary"]["with_norm"], 2);
    // The random cue's four habitats are two cues: [0] and [1].
    let random = &conditions[1]["champions"][0];
    assert_eq!(
        random["cues"][0]["habitats"],
        serde_json::json!(["flat-0", "steps-0"])
    );
    assert_eq!(
        random["cues"][1]["habitats"],
        serde_json::json!(["flat-1", "steps-1"])
    );

    // The table: a line for the directory, then per condition a blank line, its cues, a
    // header, a row per champion and the summary.
    let table = plasticity(&cmp, &[]);
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(
        lines[0],
        format!(
            "{}: plasticity of 4 champion(s) in 2 condition(s); a cue is a distinct array, its morph the body grown in it",
            cmp.display()
        )
    );
    assert_eq!(
        lines[2],
        "condition fixed: 2 champion(s); cues [0] (flat), [1] (steps)"
    );
    assert!(lines[3].starts_with("run "), "{table}");
    assert!(lines[4].starts_with("rep-1 "), "{table}");
    assert!(lines[5].starts_with("rep-2 "), "{table}");
    assert!(
        lines[6].contains("the body depends on the cue in 0 of 2 champion(s) (0%)"),
        "{table}"
    );
    assert_eq!(
        lines[8],
        "condition random-cue: 2 champion(s); cues [0] (flat-0, steps-0), [1] (flat-1, steps-1)"
    );
    assert_eq!(lines.len(), 13, "{table}");
    // The CSV: its header, then a row per champion and habitat (2 × 2 + 2 × 4).
    let csv = plasticity(&cmp, &["--csv"]);
    assert_eq!(
        csv.lines().next().unwrap(),
        ontogeny::study::plasticity::CSV_COLUMNS
    );
    assert_eq!(csv.lines().count(), 1 + 4 + 8);
    // One run, or the runs of one folder: the same champion, its condition the folder's.
    let one: serde_json::Value =
        serde_json::from_str(&plasticity(&cmp.join("fixed").join("rep-2"), &["--json"])).unwrap();
    assert_eq!(one["conditions"][0]["name"], "fixed");
    assert_eq!(
        one["conditions"][0]["champions"][0],
        conditions[0]["champions"][1]
    );
    let folder: serde_json::Value =
        serde_json::from_str(&plasticity(&cmp.join("fixed"), &["--json"])).unwrap();
    assert_eq!(
        folder["conditions"][0]["champions"],
        conditions[0]["champions"]
    );
}

#[test]
fn bad_input_is_refused_with_what_is_wrong() {
    let dir = scratch_dir("plasticity-refused");
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    refused(
        &ontogeny(&["runs", "plasticity", empty.to_str().unwrap()]),
        "empty holds no run (no run.sqlite in it or under it) and is no comparison (no compare.toml)",
    );
    refused(
        &ontogeny(&["runs", "plasticity", dir.join("absent").to_str().unwrap()]),
        "absent: cannot read it",
    );
    // A store that is no database: refused, naming it, and left as it was.
    let broken = dir.join("runs").join("broken");
    std::fs::create_dir_all(&broken).unwrap();
    std::fs::write(
        broken.join("run.sqlite"),
        "not a database, but long enough to look like one at all",
    )
    .unwrap();
    let said = refused(
        &ontogeny(&["runs", "plasticity", dir.join("runs").to_str().unwrap()]),
        "run.sqlite",
    );
    assert!(said.contains("broken"), "{said}");
    assert_eq!(
        std::fs::read_to_string(broken.join("run.sqlite")).unwrap(),
        "not a database, but long enough to look like one at all"
    );
}
