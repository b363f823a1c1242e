//! Plastic `lsystem-continuous` genomes: environment reads that make development depend on
//! the chemical array, the operators that make and remove them, and the promise that without
//! them nothing changes.

use crate::util::{
    genome_file, grow_creature_json, grown_low_and_high, offspring_whose_body_depends_on_the_cue,
    ontogeny, ontogeny_command, operators_fingerprint, refused, scratch_dir, succeeded, tiny_run,
};

use ontogeny::creature::phenotype_differences;
use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome, Rng};
use ontogeny::environment::Environment;
use ontogeny::number::format_number;
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

#[test]
fn without_environment_reads_the_operators_draw_what_they_drew_before_reads_existed() {
    // The fingerprint of the operators as they were before genomes could read their
    // environment: the default must reproduce it to the bit.
    assert_eq!(
        operators_fingerprint::<ContinuousGenome>(&ContinuousLimits::default()),
        "8c6812bf4e08c68c7f27a45735c41399cca998f94d7e3d1e5888f692c0b96e60"
    );
}

/// The shipped plastic genome, read with the default limits.
fn plastic_example() -> ContinuousGenome {
    genome_file("examples/plastic-genome.lsys")
}

#[test]
fn the_plastic_example_grows_5_parts_where_its_cue_is_low_and_7_where_it_is_high() {
    let limits = ContinuousLimits::default();
    let (low, high) = grown_low_and_high(&plastic_example(), &limits);
    // Low: the root and two limbs of two driven segments each. High: each limb's first
    // segment forks into two short rigid segments.
    assert_eq!((low.parts.len(), low.joints.len()), (5, 4));
    assert_eq!((high.parts.len(), high.joints.len()), (7, 6));
    let d = phenotype_differences(&low, &high);
    assert_eq!(
        (d.parts, d.joints, d.neurons, d.links),
        ((5, 7), (4, 6), (5, 3), (5, 3))
    );
    // The first segment of each limb keeps its length; what follows it differs.
    assert_eq!(d.resized, 2);
    assert_eq!(format_number(d.largest_resize), "0.2");
    // Two 0.5 m tips against two 0.3 m forks: 0.4 m summed.
    assert_eq!(format_number(d.summed_resize), "0.4");
    // The second limb and the tip of each limb stand elsewhere once the first limb forks.
    assert_eq!(d.moved, 3);
    // The joints after those first segments are rigid where the limbs fork.
    assert_eq!(d.joints_of_another_kind, 2);
    assert!(!d.is_same());
    assert_eq!(
        d.to_string(),
        format!(
            "parts 5 -> 7, joints 4 -> 6, neurons 5 -> 3, links 5 -> 3, volume {} -> {} m³, \
             2 part(s) of the same id resized (by up to 0.2 m), 3 part(s) of the same id placed \
             elsewhere, 2 joint(s) of the same id of another kind",
            format_number(d.volume.0),
            format_number(d.volume.1)
        )
    );
    // The same creature twice differs in nothing.
    let same = phenotype_differences(&low, &low);
    assert!(same.is_same());
    assert_eq!(same.to_string(), "the same body and brain");
}

#[test]
fn a_plastic_genome_develops_as_its_printed_file_grows_with_the_same_env() {
    let g = plastic_example();
    assert_eq!(
        ContinuousGenome::read_text(&g.to_text(), &ContinuousLimits::default()).unwrap(),
        g
    );
    let dir = scratch_dir("plastic-cli");
    let file = dir.join("genome.lsys");
    std::fs::write(&file, g.to_text()).unwrap();
    for (value, parts) in [("0", 5), ("1", 7)] {
        let out = dir.join(format!("grow-{value}"));
        let json = grow_creature_json(&file, &out, &["--env", &format!("0={value}")]);
        assert_eq!(
            json["parts"].as_array().unwrap().len(),
            parts,
            "--env 0={value}"
        );
    }
}

#[test]
fn genome_show_lists_which_symbol_reads_which_slot_and_what_its_rule_branches_on() {
    let shown = succeeded(&ontogeny(&[
        "genome",
        "show",
        "examples/plastic-genome.lsys",
    ]));
    assert!(
        shown.contains(
            "environment reads:\n  mforward reads slot 0 (3 read(s) written): on maturing, \
             where the value read is above 0.5, it becomes forward(x) output(1) [ left(0.5) \
             forward(0.3) ] right(0.5) forward(0.3); elsewhere forward(x) output(1) revolute1 \
             ?E(1, 0, 0) mforward(0)\n"
        ),
        "{shown}"
    );
    assert!(
        shown
            .ends_with("develops into 5 parts, 4 joints (4 revolute), 5 neurons, 5 links; valid\n"),
        "{shown}"
    );
}

#[test]
fn reads_where_the_genome_does_not_write_them_are_refused_with_where() {
    let limits = ContinuousLimits::default();
    let text = std::fs::read_to_string("examples/plastic-genome.lsys").unwrap();
    // The axiom's second read left out.
    let missing = text.replacen(
        "right(1) revolute2 ?E(1, 0, 0) mforward(0)",
        "right(1) revolute2 mforward(0)",
        1,
    );
    assert_ne!(missing, text);
    let e = ContinuousGenome::from_lsys(&missing, &limits).unwrap_err();
    assert_eq!(
        e.0,
        "this file does not fit the lsystem-continuous genome: in the axiom: a plastic rule's \
         read ?E(1, SLOT, 0) stands right before each of its maturing tokens, and no read \
         stands anywhere else"
    );
    // A write is not a read.
    let write = text.replacen("?E(1, 0, 0) mforward(0)", "?E(0, 0, 1) mforward(0)", 1);
    let e = ContinuousGenome::from_lsys(&write, &limits).unwrap_err();
    assert!(
        e.0.ends_with(
            "in the axiom: a genome's environment read is written ?E(1, SLOT, 0), right before \
             a maturing token"
        ),
        "{e}"
    );
    // A slot past the environment's end.
    let far = text.replace("?E(1, 0, ", "?E(1, 2, ");
    let e = ContinuousGenome::from_lsys(&far, &limits).unwrap_err();
    assert!(
        e.0.contains("?E's index 2 is outside the environment of 1 slot(s)"),
        "{e}"
    );
    // chem and secrete need an environment.
    let e =
        ContinuousGenome::from_lsys("time: 4\naxiom: forward(0.5) chem(0)\n", &limits).unwrap_err();
    assert!(
        e.0.ends_with(
            "the axiom: chem needs an environment ('environment:'), and the genome has none"
        ),
        "{e}"
    );
}

#[test]
fn with_environment_reads_every_offspring_fits_reads_back_and_develops_in_any_array() {
    let limits = ContinuousLimits {
        environment_reads: 0.5,
        ..ContinuousLimits::default()
    };
    let (mut genomes, mut plastic, mut neurons) = (0, 0, 0);
    let differ = offspring_whose_body_depends_on_the_cue(
        &limits,
        0..100,
        |seed, a: &ContinuousGenome, text| {
            genomes += 1;
            a.check_limits(&limits)
                .unwrap_or_else(|e| panic!("seed {seed}: {e}\n{text}"));
            plastic += usize::from(text.contains("?E(1, "));
            neurons += usize::from(text.contains("chem(") || text.contains("secrete("));
            assert_eq!(a.environment.len(), 1, "seed {seed}");
        },
    );
    assert_eq!(genomes, 800);
    // Without reads allowed, a genome has no environment and grows the same creature in
    // any array.
    let plain = ContinuousGenome::random(&ContinuousLimits::default(), &mut rng(3));
    assert!(plain.environment.is_empty());
    assert_eq!(
        plain.develop_in(&limits, 0, &Environment::new(vec![1.0, 2.0])),
        plain.develop(&limits, 0)
    );
    // Reads and neurons are made (and kept) often, and many bodies depend on the array.
    assert!(plastic > 400, "{plastic}");
    assert!(neurons > 200, "{neurons}");
    assert!(differ > 100, "{differ}");
}

#[test]
fn an_evolve_config_with_environment_reads_runs_and_keeps_the_key() {
    let dir = scratch_dir("plastic-run");
    let config = dir.join("plastic.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem-continuous\"\n[ga]\nenvironment_reads = 0.5\n",
    )
    .unwrap();
    let run = dir.join("run");
    tiny_run(
        "lsystem-continuous",
        &run,
        &["--config", config.to_str().unwrap()],
    );
    let stored = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(stored.contains("environment_reads = 0.5\n"), "{stored}");
    // Without the key nothing is written: a run's config.toml stays as it was.
    let plain = dir.join("plain");
    tiny_run("lsystem-continuous", &plain, &[]);
    let stored = std::fs::read_to_string(plain.join("config.toml")).unwrap();
    assert!(!stored.contains("environment_reads"), "{stored}");
    // A chance outside [0, 1] is refused.
    std::fs::write(
        &config,
        "encoding = \"lsystem-continuous\"\n[ga]\nenvironment_reads = 1.5\n",
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("refused"))
        .output()
        .unwrap();
    refused(&o, "environment_reads must be between 0 and 1");
    assert!(!dir.join("refused").exists());
}
