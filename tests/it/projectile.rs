//! The thrower's projectile as Chaumont et al. let it evolve (4.1, 4.3): a gene of every
//! genome when `[task.catapult] evolve_projectile` is set, kept within its range by mutation
//! and whole by crossover, carried by the genomes' texts, and thrown by the catapult at
//! exactly its size and mass; and the aim task without the target sensor (4.3).

use std::path::Path;

use rand::SeedableRng;

use crate::util::{evolve, ontogeny_ok, scratch_dir, stdout};
use ontogeny::creature::{
    Actuator, Brain, Creature, Link, Neuron, NeuronFunction, PROJECTILE_EDGE, Role, Sensor,
};
use ontogeny::encoding::{
    ContinuousGenome, ContinuousLimits, DirectGenome, DirectLimits, Genome, GraphGenome,
    GraphLimits, LSystemGenome, LSystemLimits, Rng,
};
use ontogeny::run::store::RunStore;
use ontogeny::sim::{SimOptions, World};
use ontogeny::task::{self, CatapultOptions, Status};

const START: [f64; 3] = [0.2, 0.2, 0.2];

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// The first genome of seeds 0, 1, ... that develops.
fn developing<G: Genome>(limits: &G::Limits) -> (G, Creature) {
    (0..100)
        .find_map(|seed| {
            let g = G::random(limits, &mut rng(seed));
            g.develop(limits, 0).ok().map(|c| (g, c))
        })
        .expect("a random genome that develops")
}

/// `g` mutated at `rate` until its projectile differs from `g`'s.
fn with_another_projectile<G: Genome>(g: &G, limits: &G::Limits, seed: u64) -> G {
    let mut r = rng(seed);
    let mut m = g.clone();
    for _ in 0..200 {
        m = m.mutate(limits, 0.5, &mut r);
        if m.projectile() != g.projectile() {
            return m;
        }
    }
    panic!("200 mutants at rate 0.5 kept the projectile");
}

/// What every encoding owes its projectile genes: newborns carry the start, development gives
/// it to the creature, mutation keeps every edge in range and follows the seed, crossover and
/// grafting keep the first parent's projectile whole, the text carries it; and a run that does
/// not evolve the projectile has genomes, creatures and texts without one.
fn the_projectile_is_a_gene_of<G: Genome + PartialEq>(plain: G::Limits) {
    let name = G::NAME;
    // Not evolving: nothing carries a projectile.
    let (g, c) = developing::<G>(&plain);
    assert_eq!((g.projectile(), c.projectile), (None, None), "{name}");
    assert!(!g.to_text().contains("projectile"), "{name}");
    let m = g.mutate(&plain, 1.0, &mut rng(2));
    assert_eq!(m.projectile(), None, "{name}");

    let mut limits = plain;
    G::evolve_projectile(&mut limits, START);
    let (a, c) = developing::<G>(&limits);
    assert_eq!(
        a.projectile(),
        Some(START),
        "{name}: a newborn starts from the start"
    );
    assert_eq!(c.projectile, Some(START), "{name}: its creature throws it");

    // Mutation: in range, changing, and the same from the same seed.
    let (lo, hi) = PROJECTILE_EDGE;
    let chain = |seed| {
        let mut r = rng(seed);
        let mut m = a.clone();
        let mut seen = Vec::new();
        for _ in 0..100 {
            m = m.mutate(&limits, 0.3, &mut r);
            seen.push(m.projectile().expect("a mutant keeps its projectile"));
        }
        seen
    };
    let seen = chain(7);
    assert_eq!(
        seen,
        chain(7),
        "{name}: the same seed, the same projectiles"
    );
    assert!(
        seen.iter().flatten().all(|e| (lo..=hi).contains(e)),
        "{name}: {seen:?}"
    );
    let distinct: std::collections::BTreeSet<String> =
        seen.iter().map(|p| format!("{p:?}")).collect();
    assert!(distinct.len() > 10, "{name}: {distinct:?}");

    // Crossover and grafting: the first parent's projectile, whole.
    let b = with_another_projectile(&a, &limits, 9);
    let (pa, pb) = (a.projectile(), b.projectile());
    assert_ne!(pa, pb);
    for seed in 0..10 {
        if let Some(child) = a.crossover(&b, &limits, &mut rng(seed)) {
            assert_eq!(child.projectile(), pa, "{name}: crossover, seed {seed}");
        }
        if let Some(child) = b.crossover(&a, &limits, &mut rng(seed)) {
            assert_eq!(child.projectile(), pb, "{name}: crossover, seed {seed}");
        }
        if let Some(child) = a.graft(&b, &limits, &mut rng(seed)) {
            assert_eq!(child.projectile(), pa, "{name}: graft, seed {seed}");
        }
    }

    // The text carries it and reads back.
    let read = G::read_text(&b.to_text(), &limits).unwrap();
    assert_eq!(read.projectile(), pb, "{name}");
    assert!(read == b, "{name}: the genome reads back whole");
}

#[test]
fn every_encoding_carries_mutates_crosses_and_writes_its_projectile() {
    the_projectile_is_a_gene_of::<LSystemGenome>(LSystemLimits::default());
    the_projectile_is_a_gene_of::<ContinuousGenome>(ContinuousLimits::default());
    the_projectile_is_a_gene_of::<DirectGenome>(DirectLimits::default());
    let mut graph = GraphLimits::default();
    GraphGenome::adapt_limits(&mut graph, ontogeny::encoding::Purpose::Throwing);
    the_projectile_is_a_gene_of::<GraphGenome>(graph);
}

#[test]
fn a_genome_text_written_before_projectiles_evolved_reads_as_before() {
    for path in [
        "docs/evolve/walker-best.lsys",
        "docs/evolve/chaumont-seed1-best.lsys",
    ] {
        let text = std::fs::read_to_string(path).unwrap();
        let g: LSystemGenome = crate::util::genome_file(path);
        assert_eq!(g.projectile, None, "{path}");
        assert!(!g.to_text().contains("projectile"), "{path}");
        // Read back from its own text, as before: the same genome, the same creature.
        let again = LSystemGenome::read_text(&g.to_text(), &LSystemLimits::default()).unwrap();
        assert_eq!(again, g);
        assert!(
            text.ends_with(&g.to_text()),
            "{path}: the text is written as it was"
        );
    }
    let g: DirectGenome = crate::util::genome_file("docs/evolve/direct-best.lsys");
    assert_eq!(g.projectile, None);
    let g: GraphGenome = crate::util::genome_file("docs/evolve/graph-catapult-best.json");
    assert_eq!(g.projectile, None);
    assert!(!g.to_text().contains("projectile"));
}

#[test]
fn a_genome_text_with_a_projectile_out_of_range_is_refused_with_the_range() {
    let g: DirectGenome = crate::util::genome_file("docs/evolve/direct-best.lsys");
    let text = format!("# projectile: 0.2 0.01 0.2\n{}", g.to_text());
    let err = DirectGenome::read_text(&text, &DirectLimits::default()).unwrap_err();
    assert!(
        err.0
            .contains("its projectile, 0.2 × 0.01 × 0.2 m, has an edge outside [0.05, 1] m"),
        "{}",
        err.0
    );
}

/// A 1 m arm of two parts hinged together.
fn arm() -> Creature {
    ontogeny::develop::creature_from_commands("forward(1) revolute2 forward(1)").unwrap()
}

#[test]
fn the_catapult_throws_the_creature_s_own_flat_projectile_at_its_size_and_mass() {
    let flat = [0.3, 0.05, 0.3];
    let c = Creature {
        projectile: Some(flat),
        ..arm()
    };
    let options = CatapultOptions {
        max_seconds: 5.0,
        ..CatapultOptions::default()
    };
    // 0.3 × 0.05 × 0.3 m at 1000 kg/m³: 4.5 kg (the task's 0.2 m cube weighs 8 kg).
    let size = options.projectile_for(&c);
    assert_eq!([size.x, size.y, size.z], flat);
    let mut world = World::new(&c, &SimOptions::default()).unwrap();
    world.attach_projectile(size, options.projectile_density);
    let mass = world.projectile_mass().unwrap();
    assert!((mass - 4.5).abs() < 1e-4, "{mass} kg");
    let e = task::catapult(&c, &SimOptions::default(), &options, false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let terms = [
        "projectile_x",
        "projectile_y",
        "projectile_z",
        "projectile_mass",
    ]
    .map(|k| e.terms[k]);
    assert_eq!(&terms[..3], &flat[..]);
    assert!((terms[3] - 4.5).abs() < 1e-12, "{}", terms[3]);
    // Without a projectile of its own it throws the task's: 0.2 m, 8 kg.
    let plain = task::catapult(&arm(), &SimOptions::default(), &options, false);
    assert_eq!(plain.terms["projectile_x"], 0.2);
    assert!((plain.terms["projectile_mass"] - 8.0).abs() < 1e-12);
}

/// An arm whose brain is a target sensor driving the release: it lets go at once when the
/// target lies to its left (the sensor reads a positive angle), else after the delay.
fn target_releaser() -> Creature {
    let neuron = |role| Neuron {
        function: NeuronFunction::Linear,
        params: vec![],
        bias: 0.0,
        role,
        part: None,
    };
    Creature {
        brain: Brain {
            neurons: vec![
                neuron(Role::Sensor {
                    sensor: Sensor::Target,
                }),
                neuron(Role::Actuator {
                    actuator: Actuator::Release,
                }),
            ],
            links: vec![Link {
                from: 0,
                to: 1,
                weight: 1.0,
            }],
        },
        ..arm()
    }
}

#[test]
fn without_the_target_sensor_the_aimer_learns_nothing_of_its_target_and_is_scored_alike() {
    let c = target_releaser();
    // The target 5 m to the side (−z): the sensor reads the angle from the arm's heading (+x)
    // to it, about +π/2 over π, a positive signal that fires the release.
    let sensing = CatapultOptions {
        target: Some(nalgebra::Vector3::new(0.0, 0.0, -5.0)),
        max_seconds: 5.0,
        ..CatapultOptions::default()
    };
    let blind = CatapultOptions {
        target_sensor: false,
        ..sensing.clone()
    };
    let seen = task::catapult(&c, &SimOptions::default(), &sensing, false);
    let unseen = task::catapult(&c, &SimOptions::default(), &blind, false);
    assert_eq!(seen.status, Status::Ok, "{:?}", seen.message);
    assert_eq!(unseen.status, Status::Ok, "{:?}", unseen.message);
    assert!(
        seen.terms["release_step"] < 30.0,
        "the sensed target fires the release: step {}",
        seen.terms["release_step"]
    );
    assert_eq!(
        unseen.terms["release_step"], 30.0,
        "the sensor reads 0: the release waits for its delay (0.5 s, 30 steps)"
    );
    // F_a = D_p − D_t either way (equation 3, α_p = α_t = 1).
    for e in [&seen, &unseen] {
        assert_eq!(e.fitness, e.terms["D_p"] - e.terms["D_t"]);
    }
    // The catapult's own evaluation ignores the setting: no target, nothing to sense.
    let plain = CatapultOptions {
        target: None,
        ..blind.clone()
    };
    let with_sensor = CatapultOptions {
        target_sensor: true,
        ..plain.clone()
    };
    let a = task::catapult(&c, &SimOptions::default(), &plain, false);
    let b = task::catapult(&c, &SimOptions::default(), &with_sensor, false);
    assert_eq!(a.fitness, b.fitness);
    assert_eq!(a.terms["release_step"], 30.0);
}

#[test]
fn the_shipped_examples_evolve_the_projectile_and_aim_blind() {
    let dir = scratch_dir("projectile-run");
    let out = dir.join("run");
    let short = [
        "--pop",
        "8",
        "--gens",
        "3",
        "--seconds",
        "3",
        "--threads",
        "1",
    ];
    evolve(
        Path::new("examples/evolve-catapult-projectile.toml"),
        &out,
        &short,
    );
    let store = RunStore::open(&out.join("run.sqlite")).unwrap();
    let (lo, hi) = PROJECTILE_EDGE;
    let mut evaluated = 0;
    for i in store.individuals(2).unwrap() {
        let genome: serde_json::Value = serde_json::from_str(&i.genome_text).unwrap();
        let edges: Vec<f64> = serde_json::from_value(genome["projectile"].clone()).unwrap();
        assert!(edges.iter().all(|e| (lo..=hi).contains(e)), "{edges:?}");
        if i.status == "ok" {
            let terms: serde_json::Value = serde_json::from_str(&i.terms_json).unwrap();
            assert_eq!(terms["projectile_x"], edges[0]);
            assert_eq!(terms["projectile_z"], edges[2]);
            evaluated += 1;
        }
    }
    assert!(evaluated > 0);
    // The champion's file carries it, and eval throws it (the task its file records).
    let best = std::fs::read_to_string(out.join("best.json")).unwrap();
    assert!(best.contains("\"projectile\""), "{best}");
    let o = ontogeny_ok(&["eval", out.join("best.json").to_str().unwrap()]);
    assert!(stdout(&o).contains("projectile_mass = "), "{}", stdout(&o));

    // `runs show` gives each generation's best's projectile: generation 0's is the start.
    let o = ontogeny_ok(&["runs", "show", out.to_str().unwrap()]);
    let table = stdout(&o);
    assert!(
        table
            .lines()
            .nth(1)
            .unwrap()
            .ends_with("projectile (m; kg)"),
        "{table}"
    );
    assert!(
        table
            .lines()
            .nth(2)
            .unwrap()
            .ends_with("0.200 × 0.200 × 0.200; 8.00"),
        "{table}"
    );

    let blind = dir.join("blind");
    evolve(Path::new("examples/evolve-aim-blind.toml"), &blind, &short);
    let config = std::fs::read_to_string(blind.join("config.toml")).unwrap();
    assert!(config.contains("target_sensor = false"), "{config}");
    let _ = std::fs::remove_dir_all(dir);
}
