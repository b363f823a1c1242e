//! Plastic `lsystem` genomes (Hornby & Pollack's): productions that read the chemical array
//! and branch on the value read, the operators that make and remove them, the promise that
//! without them nothing changes, and `genome show --habitats`.

use crate::util::{
    assert_bad_input, genome_file, grown_low_and_high, offspring_whose_body_depends_on_the_cue,
    ontogeny, operators_fingerprint, scratch_dir, succeeded, tiny_run,
};

use ontogeny::creature::phenotype_differences;
use ontogeny::encoding::{Genome, LSystemGenome, LSystemLimits, Rng};
use ontogeny::environment::Environment;
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

#[test]
fn without_environment_reads_the_operators_draw_what_they_drew_before_reads_existed() {
    // The fingerprint of the operators as they were before genomes could read their
    // environment: the default must reproduce it to the bit.
    assert_eq!(
        operators_fingerprint::<LSystemGenome>(&LSystemLimits::default()),
        "f2d30153db4574827ef54bd535a1688a75ec4565a6c90df0f77fb8492e96337a"
    );
}

/// The shipped plastic lsystem genome, read with the default limits.
fn plastic_example() -> LSystemGenome {
    genome_file("examples/plastic-lsystem.lsys")
}

#[test]
fn the_plastic_example_grows_a_tail_where_its_cue_is_low_and_two_legs_where_it_is_high() {
    let limits = LSystemLimits::default();
    let g = plastic_example();
    assert_eq!(g.productions[0].read, Some(0));
    assert_eq!(g.productions[1].read, None);
    let (low, high) = grown_low_and_high(&g, &limits);
    assert_eq!((low.parts.len(), low.joints.len()), (5, 4));
    assert_eq!((high.parts.len(), high.joints.len()), (7, 6));
    let d = phenotype_differences(&low, &high);
    assert_eq!(
        (d.parts, d.joints, d.neurons, d.links),
        ((5, 7), (4, 6), (4, 5), (4, 5))
    );
    assert!(!d.is_same());
}

#[test]
fn a_plastic_genome_prints_its_reads_and_reads_back_equal() {
    let g = plastic_example();
    let text = g.to_text();
    assert_eq!(
        text.lines().skip(1).collect::<Vec<_>>(),
        [
            "derivation length: 4",
            "environment: 0",
            "axiom: ?E(1, 0, 0) P0(2, 0)",
            "",
            "?E(1, 0, c) < P0(n0, n1) : c > 0.5 --> forward(0.5) [ left(1) revolute2 \
             forward(0.4) output(1) P1(n0 - 1, n1) ] [ right(1) revolute2 forward(0.4) \
             output(1) P1(n0 - 1, n1) ]",
            "?E(1, 0, c) < P0(n0, n1) --> forward(0.5) revolute1 forward(0.5) output(1) P1(n0, n1)",
            "P1(n0, n1) : n0 > 0 --> revolute2 forward(0.3) output(1) P1(n0 - 1, n1)",
            "P1(n0, n1) --> forward(0.2)",
        ]
    );
    assert_eq!(
        LSystemGenome::read_text(&text, &LSystemLimits::default()).unwrap(),
        g
    );
    // The JSON a run stores reads back equal too.
    let json = serde_json::to_string(&g).unwrap();
    assert_eq!(serde_json::from_str::<LSystemGenome>(&json).unwrap(), g);
}

#[test]
fn reads_that_the_genome_cannot_hold_are_refused_with_where() {
    let limits = LSystemLimits::default();
    let refused = |body: &str| {
        let text = format!("derivation length: 2\nenvironment: 0 1\naxiom: P0(1)\n{body}");
        LSystemGenome::read_text(&text, &limits).unwrap_err().0
    };
    assert_eq!(
        refused("?E(1, 0, c) < P0(x) : c > 0.5 --> forward(1)\n"),
        "this file does not fit the lsystem genome: line 3, column 8: P0 reads slot 0: write \
         ?E(1, 0, 0) right before every call of it"
    );
    assert_eq!(
        refused("P0(x) --> ?E(1, 1, 0) forward(1)\n"),
        "this file does not fit the lsystem genome: line 4, column 11: a read ?E(1, SLOT, 0) \
         stands right before a call of a production, not before 'forward'"
    );
    assert_eq!(
        refused("P0(x) --> ?E(0, 1, 0) P0(x)\n"),
        "this file does not fit the lsystem genome: line 4, column 11: a genome's read of the \
         environment is written ?E(1, SLOT, 0), right before a call of a production"
    );
    assert_eq!(
        refused("P0(x) --> forward(1) ?E(1, 1, 0) P0(x)\n"),
        "this file does not fit the lsystem genome: line 4, column 34: a read ?E(1, SLOT, 0) \
         stands before a call of P0, whose rules read nothing"
    );
    let two_parameters = "derivation length: 2\nenvironment: 0 1\naxiom: P0(1, 1)\n\
                          P0(x, y) --> forward(1) chem(2)\n";
    assert_eq!(
        LSystemGenome::read_text(two_parameters, &limits)
            .unwrap_err()
            .0,
        "this file does not fit the lsystem genome: a successor of P0 has chem without a slot \
         of the environment, 0 to 1, as its argument"
    );
}

#[test]
fn with_environment_reads_every_offspring_fits_reads_back_and_develops_in_any_array() {
    let limits = LSystemLimits {
        environment_reads: 0.5,
        ..LSystemLimits::default()
    };
    let (mut genomes, mut reading, mut neurons) = (0, 0, 0);
    let differ =
        offspring_whose_body_depends_on_the_cue(&limits, 0..60, |seed, a: &LSystemGenome, text| {
            genomes += 1;
            a.check(&limits)
                .unwrap_or_else(|e| panic!("seed {seed}: {e}\n{text}"));
            assert_eq!(a.environment, vec![0.0], "seed {seed}");
            reading += usize::from(a.productions.iter().any(|p| p.read.is_some()));
            neurons += usize::from(text.contains("chem(") || text.contains("secrete("));
        });
    assert_eq!(genomes, 480);
    assert!(reading > 300, "{reading}");
    assert!(neurons > 100, "{neurons}");
    assert!(differ > 30, "{differ}");
}

#[test]
fn without_environment_reads_no_genome_reads_or_has_an_environment() {
    let limits = LSystemLimits::default();
    for seed in 0..40 {
        let mut r = rng(seed);
        let mut a = LSystemGenome::random(&limits, &mut r);
        let b = LSystemGenome::random(&limits, &mut r);
        for _ in 0..5 {
            a = a.mutate(&limits, 0.5, &mut r);
            a = a.crossover(&b, &limits, &mut r).unwrap();
            assert!(a.environment.is_empty(), "seed {seed}");
            assert!(a.productions.iter().all(|p| p.read.is_none()));
            let text = a.to_text();
            assert!(!text.contains("?E") && !text.contains("chem("), "{text}");
            // A genome without an array grows the same creature in any.
            assert_eq!(
                a.develop_in(&limits, 0, &Environment::new(vec![1.0, 2.0])),
                a.develop(&limits, 0)
            );
        }
    }
}

#[test]
fn genome_show_lists_which_production_reads_which_slot_and_what_its_rules_test() {
    let shown = succeeded(&ontogeny(&[
        "genome",
        "show",
        "examples/plastic-lsystem.lsys",
    ]));
    assert!(
        shown.contains(
            "environment reads:\n  P0 reads slot 0 (1 read(s) written): where c is the value \
             read, c > 0.5 --> forward(0.5) [ left(1) revolute2 forward(0.4) output(1) \
             P1(n0 - 1, n1) ] [ right(1) revolute2 forward(0.4) output(1) P1(n0 - 1, n1) ]\n\
             develops into 5 parts"
        ),
        "{shown}"
    );
    let plain = succeeded(&ontogeny(&[
        "genome",
        "show",
        "examples/hornby-walker.lsys",
    ]));
    assert!(!plain.contains("environment reads"), "{plain}");
}

#[test]
fn genome_show_habitats_tells_a_plastic_body_from_one_that_is_the_same_everywhere() {
    let shown = succeeded(&ontogeny(&[
        "genome",
        "show",
        "--habitats",
        "examples/habitats.toml",
        "examples/plastic-lsystem.lsys",
    ]));
    assert_eq!(
        shown.lines().collect::<Vec<_>>(),
        [
            "examples/plastic-lsystem.lsys: lsystem genome, developed in 2 habitat(s)",
            "habitat poor (environment 0): develops into 5 parts, 4 joints (3 revolute, 1 \
             rigid), 4 neurons, 4 links; valid",
            "habitat rich (environment 1): develops into 7 parts, 6 joints (4 revolute, 2 \
             rigid), 5 neurons, 5 links; valid",
            "poor -> rich: parts 5 -> 7, joints 4 -> 6, neurons 4 -> 5, links 4 -> 5, volume \
             0.1125 -> 0.14375 m³, 3 part(s) of the same id resized (by up to 0.2 m), 4 \
             part(s) of the same id placed elsewhere, 2 joint(s) of the same id of another kind",
            "the body depends on the habitat",
        ]
    );
    let plain = succeeded(&ontogeny(&[
        "genome",
        "show",
        "--habitats",
        "examples/habitats.toml",
        "examples/hornby-walker.lsys",
    ]));
    assert_eq!(
        plain.lines().skip(3).collect::<Vec<_>>(),
        [
            "poor -> rich: the same body and brain",
            "the same body in every habitat"
        ]
    );
    let json: serde_json::Value = serde_json::from_str(&succeeded(&ontogeny(&[
        "genome",
        "show",
        "--habitats",
        "examples/habitats.toml",
        "examples/plastic-lsystem.lsys",
        "--json",
    ])))
    .unwrap();
    assert_eq!(json["encoding"], "lsystem");
    assert_eq!(json["habitats"][0]["name"], "poor");
    assert_eq!(json["habitats"][1]["environment"], serde_json::json!([1.0]));
    assert_eq!(json["habitats"][1]["creature"]["parts"], 7);
    assert_eq!(json["differences"][0]["from"], "poor");
    assert_eq!(json["differences"][0]["parts"], serde_json::json!([5, 7]));
    assert_eq!(json["differences"][0]["same"], false);
    assert_eq!(json["depends_on_habitat"], true);
    assert_eq!(json["verdict"], "the body depends on the habitat");
}

#[test]
fn genome_show_habitats_refuses_bad_configs_and_arrays_that_do_not_fit() {
    let dir = scratch_dir("plastic-lsystem-habitats");
    let genome = "examples/plastic-lsystem.lsys";
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[task.habitats]]\nname = \"a\"\nenvironment = \"x\"\n",
    )
    .unwrap();
    let said = assert_bad_input(
        &[
            "genome",
            "show",
            "--habitats",
            bad.to_str().unwrap(),
            genome,
        ],
        "[[task.habitats]] environment must be a list in brackets, [a, b, ...], not \"x\"",
    );
    assert!(said.contains("bad.toml:3:15"), "{said}");
    let two = dir.join("two.toml");
    std::fs::write(
        &two,
        "[[task.habitats]]\nname = \"a\"\nenvironment = [0.0, 1.0]\n",
    )
    .unwrap();
    assert_bad_input(
        &[
            "genome",
            "show",
            "--habitats",
            two.to_str().unwrap(),
            genome,
        ],
        "examples/plastic-lsystem.lsys: habitat a's environment has 2 slot(s); the genome \
         develops in an environment of 1",
    );
    assert_bad_input(
        &[
            "genome",
            "show",
            "--habitats",
            "examples/evolve-walker.toml",
            genome,
        ],
        "examples/evolve-walker.toml: it has no [[task.habitats]] to develop the genome in",
    );
    let broken = dir.join("broken.lsys");
    std::fs::write(
        &broken,
        "derivation length: 1\naxiom: P0\nP0 --> forward(1) [\n",
    )
    .unwrap();
    assert_bad_input(
        &[
            "genome",
            "show",
            "--habitats",
            "examples/habitats.toml",
            broken.to_str().unwrap(),
        ],
        "line 3, column 8: the successor's brackets are not balanced",
    );
    assert_bad_input(
        &[
            "genome",
            "show",
            "--habitats",
            dir.join("missing.toml").to_str().unwrap(),
            genome,
        ],
        "missing.toml",
    );
}

#[test]
fn an_lsystem_run_with_environment_reads_evolves_genomes_that_read() {
    let dir = scratch_dir("plastic-lsystem-run");
    let config = dir.join("plastic.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem\"\n[ga]\nenvironment_reads = 0.5\n",
    )
    .unwrap();
    let run = dir.join("run");
    tiny_run("lsystem", &run, &["--config", config.to_str().unwrap()]);
    let best = std::fs::read_to_string(run.join("best.lsys")).unwrap();
    assert!(best.contains("environment: 0\n"), "{best}");
}
