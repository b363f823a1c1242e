//! The two `[limits]` keys every genome shares on the creature it develops into:
//! `max_neurons` (the brain's neurons, sensors and actuators included, as the run store's
//! `neurons` column counts them) and `max_chain` (the parts of the body's longest sequence
//! joined end to end, Hornby & Pollack's "bars in a row"). For each of the four genomes, a creature whose
//! neurons and chain are counted by hand is invalid one below each count and valid at it;
//! the keys' ranges are checked; absent, they change no stored configuration, no draw of the
//! operators and no run; set, a run is the same on any thread count and resumed.

use std::path::Path;

use ontogeny::creature::{Creature, Face, JointKind, NeuronFunction};
use ontogeny::encoding::graph::{Effector, Input, NeuronGene, Source};
use ontogeny::encoding::{
    CheckedLimits, ContinuousGenome, ContinuousLimits, DirectGenome, DirectLimits, Genome,
    GraphGenome, GraphLimits, LSystemGenome, LSystemLimits, Rng,
};
use ontogeny::evolve::habitats::develop_in_habitats;
use ontogeny::run::store::RunStore;
use ontogeny::task::{TaskKind, TaskSpec};
use rand::SeedableRng;

use crate::genome_graph::{node, straight};
use crate::util::{
    assert_the_same_on_any_thread_count_and_resumed, evolve, operators_fingerprint, scratch_dir,
};

/// The creature `genome` develops into for a walker under `limits`, as evolution develops it.
fn developed<G: Genome>(genome: &G, limits: &G::Limits) -> Creature {
    develop_in_habitats(genome, limits, 0, &TaskSpec::new(TaskKind::Walker))
        .expect("develops")
        .remove(0)
}

/// The messages of a creature's error-level problems.
fn errors(c: &Creature) -> Vec<String> {
    c.problems
        .iter()
        .filter(|p| p.severity == ontogeny::creature::Severity::Error)
        .map(|p| p.message.clone())
        .collect()
}

/// Asserts that `genome`, whose creature has `neurons` neurons and a longest chain of `chain`
/// parts (counted by hand) and is valid without the keys, is valid with each key at its
/// count and invalid one below it, with the message that names the key. `limits(n, c)` are
/// the encoding's default limits with `max_neurons = n` and `max_chain = c`.
fn held_to_both_keys<G: Genome>(
    genome: &G,
    limits: impl Fn(Option<usize>, Option<usize>) -> G::Limits,
    neurons: usize,
    chain: usize,
) {
    let free = developed(genome, &limits(None, None));
    assert_eq!(
        (free.neuron_count(), free.longest_chain()),
        (neurons, chain),
        "{}",
        G::NAME
    );
    assert!(free.is_valid(), "{}: {:?}", G::NAME, free.problems);
    let at = developed(genome, &limits(Some(neurons), Some(chain)));
    assert_eq!(at, free, "{}", G::NAME);
    let fewer = developed(genome, &limits(Some(neurons - 1), None));
    assert!(!fewer.is_valid(), "{}", G::NAME);
    assert_eq!(
        errors(&fewer),
        [format!(
            "{neurons} neurons, more than limits.max_neurons = {}",
            neurons - 1
        )],
        "{}",
        G::NAME
    );
    let shorter = developed(genome, &limits(None, Some(chain - 1)));
    assert!(!shorter.is_valid(), "{}", G::NAME);
    assert_eq!(
        errors(&shorter),
        [format!(
            "a chain of {chain} parts in a row, more than limits.max_chain = {}",
            chain - 1
        )],
        "{}",
        G::NAME
    );
}

/// An L-system genome of one production `P0` rewritten once into `successor`.
fn one_step(successor: &str) -> String {
    format!("derivation length: 1\naxiom: P0(0, 0)\n\nP0(n0, n1) --> {successor}\n")
}

/// The successor of the hand-counted L-system genome: three parts in a row, the second
/// hinged and the third twisting, each joint driven by an output neuron, and a touch sensor.
/// Neurons: the brain's first oscillator, two outputs and the touch sensor, 4. Chain: 3.
const ROW: &str = "forward(1) revolute2 forward(1) output(1) twist90 forward(1) output(1) touch";

#[test]
fn an_lsystem_creature_is_held_to_max_neurons_and_max_chain() {
    let g = LSystemGenome::from_lsys(&one_step(ROW), &LSystemLimits::default()).unwrap();
    let limits = |max_neurons, max_chain| LSystemLimits {
        max_neurons,
        max_chain,
        ..LSystemLimits::default()
    };
    held_to_both_keys(&g, limits, 4, 3);
}

#[test]
fn a_direct_creature_is_held_to_max_neurons_and_max_chain() {
    // A T: the root carries a hinged leg to each side (each driven by an output neuron) and a
    // row of two parts ahead. The longest chain runs from a leg through the root along the
    // row ahead: 4 parts. Neurons: the oscillator and two outputs, 3.
    let text = "axiom: forward(1) [ left(1) revolute2 forward(1) output(1) ] \
                [ right(1) revolute2 forward(1) output(1) ] forward(1) forward(1)\n";
    let g = DirectGenome::from_lsys(text, &DirectLimits::default()).unwrap();
    let limits = |max_neurons, max_chain| DirectLimits {
        max_neurons,
        max_chain,
        ..DirectLimits::default()
    };
    held_to_both_keys(&g, limits, 3, 4);
}

#[test]
fn an_lsystem_continuous_creature_is_held_to_max_neurons_and_max_chain() {
    // The hand-written walker: two body segments, a pair of legs on each (hip, then knee),
    // 10 parts. The longest chain runs from a knee of the first segment's legs through its
    // hip, both segments, and a hip and knee of the second's: 6 parts. Neurons: the
    // oscillator and an output for each of the 4 hips and 4 knees, 9.
    let text = std::fs::read_to_string("examples/continuous-walker.lsys").unwrap();
    let g = ContinuousGenome::from_lsys(&text, &ContinuousLimits::default()).unwrap();
    let limits = |max_neurons, max_chain| ContinuousLimits {
        max_neurons,
        max_chain,
        ..ContinuousLimits::default()
    };
    assert_eq!(developed(&g, &limits(None, None)).parts.len(), 10);
    held_to_both_keys(&g, limits, 9, 6);
}

#[test]
fn a_graph_creature_is_held_to_max_neurons_and_max_chain() {
    // A root, then a hinged limb that recurs on its front face three times: 4 parts in a
    // row. Each copy of the limb has its own local neuron, which reads its joint's angle (a
    // sensor neuron of that part) and drives the joint; one global neuron besides. Neurons:
    // 3 × (1 local + 1 angle sensor) + 1 global, 7.
    let mut root = node([1.0, 0.5, 0.5], JointKind::Rigid, 1);
    root.connections.push(straight(1, Face::Front, 1.0));
    let mut limb = node([0.5, 0.2, 0.2], JointKind::Revolute, 3);
    limb.connections.push(straight(1, Face::Front, 0.8));
    let gene = |inputs, effector| NeuronGene {
        function: NeuronFunction::Sum,
        params: vec![],
        bias: 0.0,
        inputs,
        effector,
    };
    limb.neurons.push(gene(
        vec![Input {
            source: Source::Angle { dof: 0 },
            weight: 1.0,
        }],
        Some(Effector::Joint { dof: 0 }),
    ));
    let g = GraphGenome {
        nodes: vec![root, limb],
        neurons: vec![gene(vec![], None)],
        projectile: None,
    };
    let limits = |max_neurons, max_chain| GraphLimits {
        max_neurons,
        max_chain,
        ..GraphLimits::default()
    };
    assert_eq!(developed(&g, &limits(None, None)).parts.len(), 4);
    held_to_both_keys(&g, limits, 7, 4);
}

#[test]
fn the_keys_have_ranges_in_every_encoding_and_are_written_only_when_set() {
    fn check<L: CheckedLimits + serde::Serialize + serde::de::DeserializeOwned + PartialEq>(
        name: &str,
        set: impl Fn(Option<usize>, Option<usize>) -> L,
    ) {
        let toml_of = |l: &L| toml::to_string(l).unwrap();
        let unset = toml_of(&set(None, None));
        assert!(
            !unset.contains("max_neurons") && !unset.contains("max_chain"),
            "{name}: {unset}"
        );
        let both = set(Some(40), Some(8));
        let text = toml_of(&both);
        assert!(
            text.contains("max_neurons = 40\n") && text.contains("max_chain = 8\n"),
            "{name}: {text}"
        );
        assert!(toml::from_str::<L>(&text).unwrap() == both, "{name}");
        for (limits, error) in [
            (set(Some(1), Some(1)), None),
            (set(Some(10_000), Some(1_000)), None),
            (
                set(Some(0), None),
                Some("[limits] max_neurons must be 1 to 10000, not 0"),
            ),
            (
                set(Some(10_001), None),
                Some("[limits] max_neurons must be 1 to 10000, not 10001"),
            ),
            (
                set(None, Some(0)),
                Some("[limits] max_chain must be 1 to 1000, not 0"),
            ),
            (
                set(None, Some(1_001)),
                Some("[limits] max_chain must be 1 to 1000, not 1001"),
            ),
        ] {
            assert_eq!(
                limits
                    .check_ranges()
                    .err()
                    .map(|e| e.to_string())
                    .as_deref(),
                error,
                "{name}"
            );
        }
    }
    check("lsystem", |max_neurons, max_chain| LSystemLimits {
        max_neurons,
        max_chain,
        ..LSystemLimits::default()
    });
    check("lsystem-continuous", |max_neurons, max_chain| {
        ContinuousLimits {
            max_neurons,
            max_chain,
            ..ContinuousLimits::default()
        }
    });
    check("direct", |max_neurons, max_chain| DirectLimits {
        max_neurons,
        max_chain,
        ..DirectLimits::default()
    });
    check("graph", |max_neurons, max_chain| GraphLimits {
        max_neurons,
        max_chain,
        ..GraphLimits::default()
    });
}

/// Genomes of `G` drawn and mutated from seeds 0 to 9 under `limits`, as text.
fn drawn<G: Genome>(limits: &G::Limits) -> Vec<String> {
    let mut out = Vec::new();
    for seed in 0..10 {
        let mut r = Rng::seed_from_u64(seed);
        let mut g = G::random(limits, &mut r);
        for _ in 0..10 {
            g = g.mutate(limits, 0.3, &mut r);
            out.push(g.to_text());
        }
    }
    out
}

#[test]
fn the_keys_add_no_draw_to_any_genomes_operators() {
    // The fingerprint pinned before the keys existed (`genome_lsystem_repeat`): the
    // operators draw the same with them set.
    let lsystem = LSystemLimits {
        max_neurons: Some(3),
        max_chain: Some(2),
        ..LSystemLimits::default()
    };
    assert_eq!(
        operators_fingerprint::<LSystemGenome>(&lsystem),
        "f2d30153db4574827ef54bd535a1688a75ec4565a6c90df0f77fb8492e96337a"
    );
    assert_eq!(
        drawn::<ContinuousGenome>(&ContinuousLimits {
            max_neurons: Some(3),
            max_chain: Some(2),
            ..ContinuousLimits::default()
        }),
        drawn::<ContinuousGenome>(&ContinuousLimits::default())
    );
    assert_eq!(
        drawn::<DirectGenome>(&DirectLimits {
            max_neurons: Some(3),
            max_chain: Some(2),
            ..DirectLimits::default()
        }),
        drawn::<DirectGenome>(&DirectLimits::default())
    );
    assert_eq!(
        drawn::<GraphGenome>(&GraphLimits {
            max_neurons: Some(3),
            max_chain: Some(2),
            ..GraphLimits::default()
        }),
        drawn::<GraphGenome>(&GraphLimits::default())
    );
}

/// A run of `pop` walkers for 2 s from the hand-counted L-system genome (`--init`), one
/// generation, under the `[limits]` lines `limits`; its individuals' (neurons, status).
fn seeded_run(dir: &Path, name: &str, limits: &str) -> Vec<(u32, String)> {
    let seed = dir.join("row.lsys");
    std::fs::write(&seed, one_step(ROW)).unwrap();
    let config = dir.join(format!("{name}.toml"));
    std::fs::write(
        &config,
        format!(
            "encoding = \"lsystem\"\nseed = 3\ninit = \"{}\"\n[ga]\npopulation = 4\n\
             generations = 1\n[task]\ntask = \"walker\"\n[task.walker]\nseconds = 2\n\
             [limits]\n{limits}",
            seed.display()
        ),
    )
    .unwrap();
    let out = dir.join(name);
    evolve(&config, &out, &[]);
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    store
        .individuals(0)
        .unwrap()
        .into_iter()
        .map(|i| (i.neurons, i.status))
        .collect()
}

#[test]
fn a_newborn_past_max_neurons_is_stored_invalid_with_the_neurons_the_store_counts() {
    let dir = scratch_dir("limits-common-seeded");
    // Individual 0 is the seed itself: 4 neurons by hand, in the store's column too.
    let free = seeded_run(&dir, "free", "");
    assert_eq!(free[0].0, 4);
    assert_ne!(free[0].1, "invalid");
    let at = seeded_run(&dir, "at", "max_neurons = 4\nmax_chain = 3\n");
    assert_eq!(at[0], free[0]);
    let fewer = seeded_run(&dir, "fewer", "max_neurons = 3\n");
    assert_eq!(fewer[0], (4, "invalid".to_string()));
    let shorter = seeded_run(&dir, "shorter", "max_chain = 2\n");
    assert_eq!(shorter[0], (4, "invalid".to_string()));
    // Every individual of a run is held to them: none past the limit is valid.
    for (neurons, status) in &fewer {
        assert!(*neurons <= 3 || status == "invalid", "{neurons} {status}");
    }
}

#[test]
fn a_run_with_the_keys_is_the_same_on_any_thread_count_and_resumed() {
    let dir = scratch_dir("limits-common-threads");
    let config = dir.join("limits.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem\"\nseed = 5\n[ga]\npopulation = 10\ngenerations = 3\n\
         [task]\ntask = \"walker\"\n[task.walker]\nseconds = 2\n\
         [limits]\nmax_parts = 12\nmax_chain = 3\nmax_neurons = 3\n",
    )
    .unwrap();
    assert_the_same_on_any_thread_count_and_resumed(&config, &dir, "2", "3");
    let stored = std::fs::read_to_string(dir.join("one/config.toml")).unwrap();
    assert!(
        stored.contains("max_chain = 3\n") && stored.contains("max_neurons = 3\n"),
        "{stored}"
    );
}

#[test]
fn the_example_runs_and_keeps_its_keys() {
    let dir = scratch_dir("limits-common-example");
    let out = dir.join("run");
    evolve(
        Path::new("examples/evolve-hornby-pollack-limits.toml"),
        &out,
        &["--gens", "1", "--pop", "6", "--seconds", "2"],
    );
    let stored = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(
        stored.contains("max_chain = 6\n") && stored.contains("max_neurons = 30\n"),
        "{stored}"
    );
}

#[test]
fn a_straight_row_of_bars_with_side_nubs_is_still_a_row_of_its_length() {
    // Hornby & Pollack bound "sequence[s] of more than N bars in a row that [are] not part of
    // a cycle", to keep creatures physically plausible. A straight row of 11 parts (11 m)
    // with a short nub hung off each of the 9 inner ones is a sequence of 11 bars in a row
    // however many nubs hang off it: a nub adds no support. Its longest path runs from one end
    // of the row to the other (11 parts), or from the first inner part's nub to the far end
    // (also 11).
    let text = format!(
        "axiom: forward(1){} forward(1)\n",
        " forward(1) [ left(1) forward(0.3) ]".repeat(9)
    );
    let g = DirectGenome::from_lsys(&text, &DirectLimits::default()).unwrap();
    let c = developed(&g, &DirectLimits::default());
    assert_eq!(c.parts.len(), 20);
    assert_eq!(c.longest_chain(), 11);
}
