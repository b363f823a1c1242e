//! Walking with Dinosaurs' mirroring crossover (3.3.1): a part of the elite, copied with what
//! grows from it and turned half a turn, replaces a part of the breeder. The turned copy's
//! pose by hand, the limits kept and the same child from the same seed for every encoding,
//! and the `wwd` preset's runs: new ones store and use it, old ones resume with the plain
//! crossover they began with.

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use nalgebra::{UnitQuaternion, Vector3};
use ontogeny::creature::{Creature, Face, JointKind};
use ontogeny::encoding::command::Command as C;
use ontogeny::encoding::graph::{Connection, Node};
use ontogeny::encoding::lsystem::{Arg, Item};
use ontogeny::encoding::{
    ContinuousGenome, ContinuousLimits, DirectGenome, DirectLimits, Genome, GraphGenome,
    GraphLimits, LSystemGenome, LSystemLimits, Rng,
};
use ontogeny::evolve::ga::{GaSettings, Preset, WwdCrossover};
use ontogeny::run::store::RunStore;
use rand::SeedableRng;

use crate::util::{ontogeny_command, scratch_dir, succeeded};

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

fn cmd(c: C, v: f64) -> Item {
    Item::Command(c, Some(Arg::Const(v)))
}

/// The pose of part `k`: its centre and its orientation.
fn pose(c: &Creature, k: usize) -> (Vector3<f64>, UnitQuaternion<f64>) {
    (c.parts[k].position, c.parts[k].orientation)
}

fn assert_pose(c: &Creature, k: usize, centre: [f64; 3], orientation: UnitQuaternion<f64>) {
    let (p, q) = pose(c, k);
    assert!(
        (p - Vector3::from(centre)).norm() < 1e-9,
        "part {k} at {p:?}, not {centre:?}"
    );
    assert!(
        q.angle_to(&orientation) < 1e-9,
        "part {k} turned {q:?}, not {orientation:?}"
    );
}

/// Half a turn about the world's up axis (+y) and a quarter turn either way.
fn about_up(angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::y_axis(), angle)
}

/// The elite `forward(1) [ right(1) forward(0.5) ]` has a leg on its right (+z: the turtle's
/// right): `right(1)` turns the heading +x a quarter turn about +y to +z, so the leg's centre
/// is (1, 0, 0.25) and its orientation a −90° turn about +y. Copied into the breeder
/// `forward(0.8) [ up(1) forward(0.3) ]` in place of its branch, it is turned half a turn about
/// the turtle's up axis where the branch starts, +y: `left(2)` first, so its orientation is
/// the half turn times the −90° turn, +90° about +y, its heading −z, and its centre
/// (0.8, 0, −0.25), on the breeder's left.
#[test]
fn a_leg_on_the_right_of_a_direct_genome_is_copied_onto_the_left() {
    let limits = DirectLimits::default();
    let elite = DirectGenome {
        modules: vec![
            cmd(C::Forward, 1.0),
            Item::Push,
            cmd(C::Right, 1.0),
            cmd(C::Forward, 0.5),
            Item::Pop,
        ],
        projectile: None,
    };
    let breeder = DirectGenome {
        modules: vec![
            cmd(C::Forward, 0.8),
            Item::Push,
            cmd(C::Up, 1.0),
            cmd(C::Forward, 0.3),
            Item::Pop,
        ],
        projectile: None,
    };
    let grown_elite = elite.develop(&limits, 0).unwrap();
    assert_pose(&grown_elite, 1, [1.0, 0.0, 0.25], about_up(-FRAC_PI_2));
    for seed in 0..5 {
        let child = breeder
            .mirroring_crossover(&elite, &limits, &mut rng(seed))
            .unwrap();
        assert_eq!(
            child.modules,
            vec![
                cmd(C::Forward, 0.8),
                Item::Push,
                cmd(C::Left, 2.0),
                cmd(C::Right, 1.0),
                cmd(C::Forward, 0.5),
                Item::Pop,
            ]
        );
        let grown = child.develop(&limits, 0).unwrap();
        assert_eq!(grown.parts.len(), 2);
        assert_pose(&grown, 0, [0.4, 0.0, 0.0], UnitQuaternion::identity());
        assert_pose(&grown, 1, [0.8, 0.0, -0.25], about_up(FRAC_PI_2));
        // Copied back, the half turn is taken away again: the leg is on the right once more.
        let back = elite
            .mirroring_crossover(&child, &limits, &mut rng(seed))
            .unwrap();
        assert_eq!(back, elite);
    }
}

/// The same leg in the L-system genome: a branch of a successor of the elite replaces the
/// breeder's branch, or its second part, half turned, with its call fitted to the breeder's
/// productions.
#[test]
fn a_branch_of_an_lsystem_successor_is_copied_half_turned_and_its_calls_fit_the_breeder() {
    let limits = LSystemLimits {
        params: 0,
        ..LSystemLimits::default()
    };
    let production = |successor: Vec<Item>| ontogeny::encoding::lsystem::Production {
        pairs: vec![ontogeny::encoding::lsystem::Pair {
            condition: None,
            successor,
        }],
        read: None,
    };
    let genome = |productions| LSystemGenome {
        start: vec![],
        derivation_length: 2,
        productions,
        environment: Vec::new(),
        projectile: None,
    };
    // The elite's leg calls its P2, which the one-production breeder lacks: 2 % 1 = P0.
    let elite = genome(vec![
        production(vec![cmd(C::Forward, 1.0)]),
        production(vec![]),
        production(vec![
            cmd(C::Forward, 1.0),
            Item::Push,
            cmd(C::Right, 1.0),
            Item::Call(2, vec![]),
            Item::Pop,
        ]),
    ]);
    let breeder = genome(vec![production(vec![
        cmd(C::Forward, 0.8),
        Item::Push,
        cmd(C::Forward, 0.3),
        Item::Pop,
    ])]);
    let child = breeder
        .mirroring_crossover(&elite, &limits, &mut rng(1))
        .unwrap();
    let leg = [
        Item::Push,
        cmd(C::Left, 2.0),
        cmd(C::Right, 1.0),
        Item::Call(0, vec![]),
        Item::Pop,
    ];
    let mut expected = vec![cmd(C::Forward, 0.8)];
    expected.extend(leg.clone());
    assert_eq!(child.productions[0].pairs[0].successor, expected);
    assert_eq!(child.check(&limits), Ok(()));
    // A breeder without a branch: its second part, with the turn that places it, is a part
    // too (a tail), and the copy takes its place.
    let breeder = genome(vec![production(vec![
        cmd(C::Forward, 0.8),
        cmd(C::Up, 1.0),
        cmd(C::Forward, 0.2),
    ])]);
    let child = breeder
        .mirroring_crossover(&elite, &limits, &mut rng(1))
        .unwrap();
    assert_eq!(child.productions[0].pairs[0].successor, expected);
}

fn leg_node(size: [f64; 3]) -> Node {
    Node {
        size,
        joint: JointKind::Revolute,
        limits: vec![(-0.5, 0.5)],
        recursive_limit: 1,
        neurons: vec![],
        connections: vec![],
    }
}

fn on_face(face: Face) -> Connection {
    Connection {
        to: 1,
        face,
        position: [0.0, 0.0],
        orientation: [0.0, 0.0, 0.0],
        scale: 1.0,
        reflection: false,
        terminal_only: false,
    }
}

/// A graph genome's leg on its root's right face: the root is 1 × 0.2 × 0.4 m, so the face is
/// 0.2 m from its centre along +z, and a 0.5 m leg leaving it along its normal has its centre
/// at (0, 0, 0.45) and the right face's frame [z, y, −x] as its orientation, a −90° turn
/// about +y. Copied onto a breeder whose root is the same box, in place of the part its one
/// connection grew, the connection is turned half a turn about the root's up axis (+y): the
/// left face, the leg's centre at (0, 0, −0.45) and the frame [−z, y, x], +90° about +y.
#[test]
fn a_leg_on_the_right_face_of_a_graph_genome_is_copied_onto_the_left_face() {
    let limits = GraphLimits::default();
    let mut root = leg_node([1.0, 0.2, 0.4]);
    root.connections = vec![on_face(Face::Right)];
    let elite = GraphGenome {
        nodes: vec![root.clone(), leg_node([0.5, 0.1, 0.1])],
        neurons: vec![],
        projectile: None,
    };
    root.connections = vec![on_face(Face::Front)];
    let breeder = GraphGenome {
        nodes: vec![root, leg_node([0.3, 0.3, 0.3])],
        neurons: vec![],
        projectile: None,
    };
    let grown_elite = elite.develop(&limits, 0).unwrap();
    assert_pose(&grown_elite, 1, [0.0, 0.0, 0.45], about_up(-FRAC_PI_2));
    let child = breeder
        .mirroring_crossover(&elite, &limits, &mut rng(2))
        .unwrap();
    assert_eq!(child.nodes.len(), 2);
    assert_eq!(child.nodes[0].connections[0].face, Face::Left);
    assert_eq!(child.nodes[1], elite.nodes[1]);
    let grown = child.develop(&limits, 0).unwrap();
    assert_eq!(grown.parts.len(), 2);
    assert_pose(&grown, 1, [0.0, 0.0, -0.45], about_up(FRAC_PI_2));
    // The joint's hinge is the leg's z axis, turned with it: +x on the left, −x on the right.
    assert!((grown.joints[0].axes[0] - Vector3::x()).norm() < 1e-9);
    assert!((grown_elite.joints[0].axes[0] + Vector3::x()).norm() < 1e-9);
}

/// Over many random pairs of every encoding, under tight limits: every child of the mirroring
/// crossover is within the limits, the same seed gives the same child, and the crossover makes
/// children (not only `None`) that differ from the breeder.
fn children_keep_the_limits<G: Genome + PartialEq>(
    limits: &G::Limits,
    check: impl Fn(&G) -> Result<(), String>,
) {
    let mut made = 0;
    let mut changed = 0;
    for seed in 0..300 {
        let mut r = rng(seed);
        let breeder = G::random(limits, &mut r).mutate(limits, 0.3, &mut r);
        let elite = G::random(limits, &mut r).mutate(limits, 0.3, &mut r);
        let child = breeder.mirroring_crossover(&elite, limits, &mut rng(seed + 1000));
        assert_eq!(
            child,
            breeder.mirroring_crossover(&elite, limits, &mut rng(seed + 1000)),
            "{} seed {seed}",
            G::NAME
        );
        if let Some(child) = child {
            made += 1;
            changed += usize::from(child != breeder);
            if let Err(e) = check(&child) {
                panic!("{} seed {seed}: {e}\n{}", G::NAME, child.to_text());
            }
            // Again and again: copies of copies stay within the limits too.
            let mut g = child;
            for k in 0..5 {
                if let Some(next) = g.mirroring_crossover(&elite, limits, &mut rng(seed + k)) {
                    check(&next).unwrap_or_else(|e| panic!("{} seed {seed}: {e}", G::NAME));
                    g = next;
                }
            }
        }
    }
    assert!(made >= 150, "{}: {made} children of 300", G::NAME);
    assert!(
        changed >= made / 2,
        "{}: {changed} of {made} changed",
        G::NAME
    );
}

#[test]
fn mirroring_children_of_every_encoding_keep_its_limits_and_are_determined_by_the_seed() {
    let lsystem = LSystemLimits {
        max_successor: 8,
        max_productions: 3,
        ..LSystemLimits::default()
    };
    children_keep_the_limits::<LSystemGenome>(&lsystem, |g| g.check(&lsystem));
    let direct = DirectLimits {
        max_modules: 20,
        ..DirectLimits::default()
    };
    children_keep_the_limits::<DirectGenome>(&direct, |g| g.check(&direct));
    let continuous = ContinuousLimits {
        max_successor: 6,
        max_axiom: 6,
        ..ContinuousLimits::default()
    };
    children_keep_the_limits::<ContinuousGenome>(&continuous, |g| g.check_limits(&continuous));
    let graph = GraphLimits {
        max_nodes: 4,
        max_connections: 2,
        ..GraphLimits::default()
    };
    children_keep_the_limits::<GraphGenome>(&graph, |g| g.check(&graph));
}

#[test]
fn the_wwd_preset_mirrors_and_a_config_without_the_key_reads_as_the_plain_crossover() {
    assert_eq!(
        GaSettings::preset(Preset::Wwd).wwd_crossover,
        WwdCrossover::Mirroring
    );
    assert_eq!(
        GaSettings::preset(Preset::Chaumont).wwd_crossover,
        WwdCrossover::Plain
    );
    // A `[ga]` table stored before the key existed.
    let old = "preset = \"wwd\"\npopulation = 6\ngenerations = 2\nelite = 0.2\nbreeders = 0.3\n\
               asexual = 0.0\ncrossover = 1.0\nmutation_rate = 0.05\n\
               mutation_chance_after_mating = 1.0\nmutation_rate_after_mating = 0.05\n";
    let read: GaSettings = toml::from_str(old).unwrap();
    assert_eq!(read.wwd_crossover, WwdCrossover::Plain);
    // Written back, it stays as it was.
    assert!(!toml::to_string(&read).unwrap().contains("wwd_crossover"));
    let new = toml::to_string(&GaSettings::preset(Preset::Wwd)).unwrap();
    assert!(new.contains("wwd_crossover = \"mirroring\""), "{new}");
}

/// `ontogeny evolve` of a `wwd` run of graph walkers from `config` into `out`, `gens`
/// generations of 8.
fn wwd_run(config: &Path, out: &Path, gens: &str) {
    succeeded(
        &ontogeny_command()
            .args(["evolve", "--encoding", "graph", "--task", "walker"])
            .args(["--preset", "wwd", "--pop", "8", "--gens", gens])
            .args(["--seconds", "0.5", "--seed", "5", "--config"])
            .arg(config)
            .arg("--out")
            .arg(out)
            .output()
            .unwrap(),
    );
}

/// Every genome of generation `g` of the run in `out`, in order.
fn genomes(out: &Path, g: u32) -> Vec<String> {
    let store = RunStore::open_read_only(&out.join("run.sqlite")).unwrap();
    store
        .individuals(g)
        .unwrap()
        .into_iter()
        .map(|i| i.genome_json)
        .collect()
}

#[test]
fn a_wwd_run_stores_the_mirroring_crossover_and_an_old_run_resumes_with_the_plain_one() {
    let dir = scratch_dir("mirroring-runs");
    let empty = dir.join("empty.toml");
    std::fs::write(&empty, "").unwrap();
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, "[ga]\nwwd_crossover = \"plain\"\n").unwrap();
    // A new wwd run writes the key and makes its children by crossover.
    let mirrored = dir.join("mirrored");
    wwd_run(&empty, &mirrored, "3");
    let stored = std::fs::read_to_string(mirrored.join("config.toml")).unwrap();
    assert!(
        stored.contains("wwd_crossover = \"mirroring\"\n"),
        "{stored}"
    );
    let store = RunStore::open_read_only(&mirrored.join("run.sqlite")).unwrap();
    let second = store.individuals(1).unwrap();
    assert!(
        second.iter().any(|i| i.operator == "crossover"),
        "{:?}",
        second.iter().map(|i| &i.operator).collect::<Vec<_>>()
    );
    // A run with the plain crossover writes no key: its config.toml is one written before the
    // key existed.
    let whole = dir.join("whole");
    wwd_run(&plain, &whole, "3");
    let stored = std::fs::read_to_string(whole.join("config.toml")).unwrap();
    assert!(!stored.contains("wwd_crossover"), "{stored}");
    assert_ne!(genomes(&whole, 2), genomes(&mirrored, 2));
    // Such a run stopped after two generations resumes to what it would have made: the plain
    // crossover, not the mirroring one that a new wwd run gets.
    let stopped = dir.join("stopped");
    wwd_run(&plain, &stopped, "2");
    succeeded(
        &ontogeny_command()
            .args(["evolve", "--gens", "3", "--resume"])
            .arg(&stopped)
            .output()
            .unwrap(),
    );
    assert_eq!(genomes(&stopped, 2), genomes(&whole, 2));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_crossover_that_is_not_one_of_the_two_is_refused_at_its_place() {
    let dir = scratch_dir("mirroring-refused");
    let config = dir.join("bad.toml");
    std::fs::write(
        &config,
        "[ga]\npreset = \"wwd\"\nwwd_crossover = \"mirror\"\n",
    )
    .unwrap();
    let o = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let said = crate::util::refused(&o, "[ga] wwd_crossover must be one of plain, mirroring");
    assert!(said.contains("bad.toml:3:17"), "{said}");
    let _ = std::fs::remove_dir_all(dir);
}
