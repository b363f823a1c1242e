//! The `graph` genome (Sims 1994 as Chaumont et al. 2007 reimplemented it): operators stay
//! within the limits, development is what the nodes and connections say (hand-computed poses,
//! recursion, reflection), crossover and grafting move the expected nodes, every joint kind is
//! built, simulated and driven by its neurons, and the command line runs it.

use std::path::PathBuf;

use nalgebra::{Matrix3, Vector3};
use ontogeny::creature::{Creature, Face, JointKind, NeuronFunction, PartId};
use ontogeny::encoding::graph::{Connection, Effector, Input, NeuronGene, Node, Source};
use ontogeny::encoding::{Genome, GraphGenome, GraphLimits, JointSet, Purpose, Rng};
use ontogeny::sim::{SimOptions, World};
use ontogeny::task::{Status, WalkerOptions, walker};
use proptest::prelude::*;
use rand::SeedableRng;

use crate::util::{assert_bad_input, ontogeny_command, refused, scratch_dir};

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// A graph node of `size` joined to its parent by `joint`, with no neurons or connections.
pub(crate) fn node(size: [f64; 3], joint: JointKind, recursive_limit: u32) -> Node {
    Node {
        size,
        joint,
        limits: vec![(-1.0, 1.0); joint.dof()],
        recursive_limit,
        neurons: vec![],
        connections: vec![],
    }
}

/// A connection from a node's `face` to node `to`, straight out, at `scale`.
pub(crate) fn straight(to: usize, face: Face, scale: f64) -> Connection {
    Connection {
        to,
        face,
        position: [0.0, 0.0],
        orientation: [0.0, 0.0, 0.0],
        scale,
        reflection: false,
        terminal_only: false,
    }
}

fn near(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    (a - b).norm() < 1e-9
}

fn develop(g: &GraphGenome) -> Creature {
    g.develop(&GraphLimits::default(), 0).expect("develops")
}

/// Root (1 × 0.5 × 0.5) → limb (0.5 × 0.2 × 0.2, revolute) on the root's front face; the limb
/// → itself on its front face at scale 0.5, recursive limit 3.
fn two_nodes() -> GraphGenome {
    let mut root = node([1.0, 0.5, 0.5], JointKind::Rigid, 1);
    root.connections.push(straight(1, Face::Front, 1.0));
    let mut limb = node([0.5, 0.2, 0.2], JointKind::Revolute, 3);
    limb.connections.push(straight(1, Face::Front, 0.5));
    GraphGenome {
        nodes: vec![root, limb],
        neurons: vec![],
        projectile: None,
    }
}

#[test]
fn a_two_node_graph_with_a_recursive_limit_of_3_develops_into_a_chain_of_three_limbs() {
    let c = develop(&two_nodes());
    assert!(c.is_valid(), "{:?}", c.problems);
    // By hand: the root centred at 0, front face at x = 0.5. Limb 1 (scale 1): 0.5 long,
    // centre 0.75. Limb 2 (scale 0.5): 0.25 long, from 1.0, centre 1.125. Limb 3 (scale
    // 0.25): 0.125 long, from 1.25, centre 1.3125. The fourth visit exceeds the limit.
    let expect = [
        (0.0, [1.0, 0.5, 0.5]),
        (0.75, [0.5, 0.2, 0.2]),
        (1.125, [0.25, 0.1, 0.1]),
        (1.3125, [0.125, 0.05, 0.05]),
    ];
    assert_eq!(c.parts.len(), 4);
    for (part, (x, size)) in c.parts.iter().zip(expect) {
        assert!(near(&part.position, &Vector3::new(x, 0.0, 0.0)), "{part:?}");
        assert!(near(&part.size, &Vector3::from(size)), "{part:?}");
        assert!(part.orientation.angle() < 1e-12);
    }
    assert_eq!(c.joints.len(), 3);
    for (k, (j, anchor)) in c.joints.iter().zip([0.5, 1.0, 1.25]).enumerate() {
        assert_eq!((j.parent, j.child), (k, k + 1));
        assert_eq!(j.kind, JointKind::Revolute);
        assert!(near(&j.anchor, &Vector3::new(anchor, 0.0, 0.0)));
        assert_eq!(j.axes.len(), 1);
        assert!(
            near(&j.axes[0], &Vector3::z()),
            "bends about the width axis"
        );
        assert_eq!(j.limits, vec![(-1.0, 1.0)]);
    }
}

#[test]
fn a_connection_on_a_side_face_places_and_turns_the_child_as_computed_by_hand() {
    let mut g = two_nodes();
    g.nodes[1].recursive_limit = 1;
    let c = &mut g.nodes[0].connections[0];
    c.face = Face::Top;
    c.position = [0.5, 0.0]; // half way towards the root's back end (the top face's y is −x)
    let a: f64 = 0.785; // the largest bend (45° on the 0.001 grid)
    c.orientation = [0.0, a, 0.0];
    let creature = develop(&g);
    assert_eq!(creature.parts.len(), 2);
    // Anchor: top face (y = 0.25), x = −0.5 · 0.5 = −0.25. Direction: the face normal (+y)
    // bent by a about z towards −x: (−sin a, cos a, 0); centre 0.25 along it.
    let direction = Vector3::new(-a.sin(), a.cos(), 0.0);
    let anchor = Vector3::new(-0.25, 0.25, 0.0);
    assert!(near(&creature.joints[0].anchor, &anchor));
    let centre = anchor + direction * 0.25;
    assert!(
        near(&creature.parts[1].position, &centre),
        "{:?}",
        creature.parts[1]
    );
    let length_axis = creature.parts[1].orientation * Vector3::x();
    assert!(near(&length_axis, &direction));
}

#[test]
fn a_terminal_only_connection_applies_only_at_the_end_of_the_recursion() {
    let mut g = two_nodes();
    g.nodes.push(node([0.1, 0.1, 0.1], JointKind::Rigid, 1)); // the "hand"
    let mut hand = straight(2, Face::Top, 1.0);
    hand.terminal_only = true;
    g.nodes[1].connections.push(hand);
    let c = develop(&g);
    assert_eq!(c.parts.len(), 5);
    let hands: Vec<usize> = c
        .joints
        .iter()
        .filter(|j| c.parts[j.child].size.x < 0.09)
        .map(|j| j.parent)
        .collect();
    // The hand's size is scaled with its limb: limb 3's scale is 0.25 (0.025 m), on limb 3
    // (part 3) only.
    assert_eq!(hands, vec![3]);
}

#[test]
fn reflection_mirrors_a_limb_and_everything_below_it_across_the_roots_plane() {
    let mut root = node([1.0, 0.5, 0.5], JointKind::Rigid, 1);
    let mut left = straight(1, Face::Right, 1.0);
    left.position = [0.2, 0.5];
    left.orientation = [0.3, 0.2, 0.4];
    let mut right = left.clone();
    right.reflection = true;
    root.connections = vec![left, right];
    let mut limb = node([0.4, 0.2, 0.1], JointKind::Universal, 2);
    let mut onward = straight(1, Face::Front, 0.8);
    onward.orientation = [0.5, -0.3, 0.1];
    limb.connections.push(onward);
    let g = GraphGenome {
        nodes: vec![root, limb],
        neurons: vec![],
        projectile: None,
    };
    let c = develop(&g);
    assert!(c.is_valid(), "{:?}", c.problems);
    assert_eq!(c.parts.len(), 5, "root, two limbs of two parts each");
    // Depth first: parts 1, 2 are the unreflected limb, parts 3, 4 its mirror image.
    let p = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
    for (a, b) in [(1, 3), (2, 4)] {
        let (pa, pb) = (&c.parts[a], &c.parts[b]);
        assert!(pa.position.z > 0.3, "the first limb is on the +z side");
        assert!(near(&pb.position, &(p * pa.position)), "{pa:?} {pb:?}");
        assert!(near(&pb.size, &pa.size));
        // The mirror image of the box: the same axes mirrored, the width axis flipped to
        // keep the frame right-handed.
        let ra = pa.orientation.to_rotation_matrix().into_inner();
        let rb = pb.orientation.to_rotation_matrix().into_inner();
        assert!((rb - p * ra * p).norm() < 1e-9);
    }
    for (a, b) in [(0, 2), (1, 3)] {
        assert!(near(&c.joints[b].anchor, &(p * c.joints[a].anchor)));
    }
}

/// A chain of `sizes.len()` nodes, each connected to the next on its front face.
fn chain(sizes: &[f64]) -> GraphGenome {
    let nodes = sizes
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            let mut n = node([s, 0.2, 0.2], JointKind::Revolute, 1);
            if i + 1 < sizes.len() {
                n.connections.push(straight(i + 1, Face::Front, 1.0));
            }
            n
        })
        .collect();
    GraphGenome {
        nodes,
        neurons: vec![],
        projectile: None,
    }
}

fn lengths(g: &GraphGenome) -> Vec<f64> {
    g.nodes.iter().map(|n| n.size[0]).collect()
}

fn is_chain(g: &GraphGenome) -> bool {
    g.nodes.iter().enumerate().all(|(i, n)| {
        let to: Vec<usize> = n.connections.iter().map(|c| c.to).collect();
        if i + 1 < g.nodes.len() {
            to == vec![i + 1]
        } else {
            to.is_empty()
        }
    })
}

#[test]
fn crossover_takes_the_first_parents_nodes_up_to_a_point_and_the_seconds_after_it() {
    let a = chain(&[0.11, 0.12, 0.13]);
    let b = chain(&[0.21, 0.22, 0.23]);
    let limits = GraphLimits::default();
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..40 {
        let child = a.crossover(&b, &limits, &mut rng(seed)).expect("a child");
        let got = lengths(&child);
        let k = (1..=3)
            .find(|&k| {
                let mut want = vec![0.11, 0.12, 0.13][..k].to_vec();
                want.extend(&[0.21, 0.22, 0.23][k..]);
                want == got
            })
            .unwrap_or_else(|| panic!("seed {seed}: {got:?} is not a crossover"));
        seen.insert(k);
        assert!(is_chain(&child), "the chains' connections line up");
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![1, 2, 3]);
}

#[test]
fn grafting_redirects_a_connection_of_the_first_parent_to_a_subgraph_of_the_second() {
    let a = chain(&[0.11, 0.12, 0.13]);
    let b = chain(&[0.21, 0.22, 0.23]);
    let limits = GraphLimits::default();
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..60 {
        let child = a.graft(&b, &limits, &mut rng(seed)).expect("a child");
        let got = lengths(&child);
        // Redirecting connection 0 → 1 keeps [0.11]; 1 → 2 keeps [0.11, 0.12]; then the
        // nodes of the second parent reachable from the chosen one.
        let form = (1..=2)
            .flat_map(|kept| (0..3).map(move |from| (kept, from)))
            .find(|&(kept, from)| {
                let mut want = vec![0.11, 0.12][..kept].to_vec();
                want.extend(&[0.21, 0.22, 0.23][from..]);
                want == got
            })
            .unwrap_or_else(|| panic!("seed {seed}: {got:?} is not a graft"));
        seen.insert(form);
        assert!(is_chain(&child));
    }
    assert_eq!(
        seen.len(),
        6,
        "every connection and every node was chosen: {seen:?}"
    );
}

#[test]
fn new_nodes_and_joint_mutations_draw_from_the_configured_joint_set() {
    // Chaumont 5.1: one degree of freedom per joint by default; `sims` allows all seven kinds.
    let kinds_seen = |joints: JointSet| {
        let limits = GraphLimits {
            joint_kinds: joints,
            ..GraphLimits::default()
        };
        let mut seen = std::collections::BTreeSet::new();
        for seed in 0..40 {
            let mut r = rng(seed);
            let mut g = GraphGenome::random(&limits, &mut r);
            for _ in 0..10 {
                seen.extend(g.nodes.iter().map(|n| format!("{:?}", n.joint)));
                g = g.mutate(&limits, 0.5, &mut r);
            }
        }
        seen
    };
    let one_axis = kinds_seen(JointSet::OneAxis);
    assert_eq!(
        one_axis,
        ["Revolute", "Rigid", "Twist"].map(String::from).into(),
        "the default joint set"
    );
    assert_eq!(JointSet::default(), JointSet::OneAxis);
    assert!(JointSet::OneAxis.kinds().iter().all(|k| k.dof() <= 1));
    let sims = kinds_seen(JointSet::Sims);
    assert_eq!(sims.len(), 7, "Sims' seven kinds all appear: {sims:?}");
    // The key as a config writes it.
    let limits: GraphLimits = toml::from_str("joint_kinds = \"sims\"").unwrap();
    assert_eq!(limits.joint_kinds, JointSet::Sims);
    assert!(toml::from_str::<GraphLimits>("joint_kinds = \"two-axis\"").is_err());
}

#[test]
fn for_throwing_the_root_is_the_first_parents_arm_and_keeps_its_back_face_free() {
    let mut limits = GraphLimits::default();
    GraphGenome::adapt_limits(&mut limits, Purpose::Throwing);
    assert_eq!(limits.purpose, Purpose::Throwing);
    for seed in 0..30 {
        let mut r = rng(seed);
        let a = GraphGenome::random(&limits, &mut r);
        let b = GraphGenome::random(&limits, &mut r);
        let mut children = vec![a.mutate(&limits, 0.5, &mut r)];
        children.extend(a.crossover(&b, &limits, &mut r));
        for child in children.iter().skip(1) {
            let mut arm = child.nodes[0].clone();
            let mut expected = a.nodes[0].clone();
            arm.connections.clear();
            expected.connections.clear();
            assert_eq!(arm, expected, "seed {seed}: crossover keeps parent 1's arm");
        }
        if let Some(g) = a.graft(&b, &limits, &mut r) {
            let mut arm = g.nodes[0].clone();
            let mut expected = a.nodes[0].clone();
            arm.connections.clear();
            expected.connections.clear();
            assert_eq!(arm, expected, "seed {seed}: grafting keeps parent 1's arm");
        }
        for g in [&a, &b, &children[0]] {
            assert!(g.nodes[0].connections.iter().all(|c| c.face != Face::Back));
        }
    }
}

/// A root and one child joined by `kind`, each degree of freedom driven by a constant
/// neuron of value `drive[dof]`.
fn driven(kind: JointKind, drive: &[f64]) -> GraphGenome {
    let mut root = node([0.6, 0.3, 0.6], JointKind::Rigid, 1);
    root.connections.push(straight(1, Face::Front, 1.0));
    let mut limb = node([0.5, 0.2, 0.2], kind, 1);
    limb.neurons = (0..kind.dof())
        .map(|k| NeuronGene {
            function: NeuronFunction::Constant,
            params: vec![drive[k]],
            bias: 0.0,
            inputs: vec![Input {
                source: Source::Angle { dof: k },
                weight: 1.0,
            }],
            effector: Some(Effector::Joint { dof: k }),
        })
        .collect();
    GraphGenome {
        nodes: vec![root, limb],
        neurons: vec![],
        projectile: None,
    }
}

/// The child's orientation relative to the root after 0.5 s of simulation.
fn relative_pose(g: &GraphGenome) -> nalgebra::UnitQuaternion<f64> {
    let c = develop(g);
    let mut world = World::new(&c, &SimOptions::default()).expect("builds");
    for _ in 0..(0.5 / SimOptions::default().control_step).round() as usize {
        world.step(true).expect("no explosion");
    }
    let (_, root) = world.part_pose(PartId(0));
    let (_, limb) = world.part_pose(PartId(1));
    root.inverse() * limb
}

#[test]
fn every_joint_kind_builds_simulates_and_is_driven_by_its_neurons() {
    let kinds = [
        JointKind::Rigid,
        JointKind::Revolute,
        JointKind::Twist,
        JointKind::Universal,
        JointKind::BendTwist,
        JointKind::TwistBend,
        JointKind::Spherical,
    ];
    for kind in kinds {
        let dof = kind.dof();
        let still = driven(kind, &[0.0; 3]);
        let c = develop(&still);
        assert!(c.is_valid(), "{kind:?}: {:?}", c.problems);
        assert_eq!(c.check_consistency(), Ok(()));
        assert_eq!(c.joints[0].kind, kind);
        assert_eq!(c.joints[0].axes.len(), dof);
        let actuators = c
            .brain
            .neurons
            .iter()
            .filter(|n| matches!(n.role, ontogeny::creature::Role::Actuator { .. }))
            .count();
        assert_eq!(
            actuators, dof,
            "{kind:?}: one driven neuron per degree of freedom"
        );
        let walk = walker(
            &c,
            &SimOptions::default(),
            &WalkerOptions {
                seconds: 1.0,
                ..WalkerOptions::default()
            },
            false,
        );
        assert_eq!(walk.status, Status::Ok, "{kind:?}: {walk:?}");
        let rest = relative_pose(&still);
        let mut poses = Vec::new();
        for k in 0..dof {
            let mut drive = [0.0; 3];
            drive[k] = 1.0;
            let moved = relative_pose(&driven(kind, &drive));
            let angle = moved.angle_to(&rest);
            assert!(angle > 0.05, "{kind:?} dof {k}: turned only {angle} rad");
            poses.push(moved);
        }
        for a in 0..poses.len() {
            for b in a + 1..poses.len() {
                assert!(
                    poses[a].angle_to(&poses[b]) > 0.05,
                    "{kind:?}: dofs {a} and {b} turn the limb alike"
                );
            }
        }
    }
}

fn small_limits() -> impl Strategy<Value = GraphLimits> {
    (
        1usize..6,
        1usize..8,
        0usize..3,
        1u32..4,
        0usize..3,
        0usize..3,
        0usize..4,
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(
            |(nodes, parts, connections, recursion, local, global, inputs, throwing, sims)| {
                GraphLimits {
                    max_nodes: nodes,
                    max_parts: parts,
                    max_connections: connections,
                    max_recursion: recursion,
                    max_local_neurons: local,
                    max_global_neurons: global,
                    max_inputs: inputs,
                    regenerate_tries: 2,
                    max_neurons: None,
                    max_chain: None,
                    projectile: None,
                    joint_kinds: if sims {
                        JointSet::Sims
                    } else {
                        JointSet::OneAxis
                    },
                    purpose: if throwing {
                        Purpose::Throwing
                    } else {
                        Purpose::Locomotion
                    },
                }
            },
        )
}

fn limits_strategy() -> impl Strategy<Value = GraphLimits> {
    prop_oneof![Just(GraphLimits::default()), small_limits()]
}

fn check_developed(g: &GraphGenome, limits: &GraphLimits) -> Result<(), TestCaseError> {
    prop_assert_eq!(g.check(limits), Ok(()));
    let c = g.develop(limits, 7).expect("a checked genome develops");
    prop_assert!(c.parts.len() <= limits.max_parts.max(1));
    prop_assert_eq!(c.check_consistency(), Ok(()));
    if limits.purpose == Purpose::Throwing {
        prop_assert!(g.nodes[0].connections.iter().all(|c| c.face != Face::Back));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn operators_stay_within_the_limits_and_their_genomes_develop(
        limits in limits_strategy(),
        seed in any::<u64>(),
        rate in 0.0f64..1.0,
    ) {
        let mut r = rng(seed);
        let a = GraphGenome::random(&limits, &mut r);
        let b = GraphGenome::random(&limits, &mut r);
        check_developed(&a, &limits)?;
        let mut m = a.clone();
        for _ in 0..3 {
            m = m.mutate(&limits, rate, &mut r);
            check_developed(&m, &limits)?;
        }
        if let Some(x) = m.crossover(&b, &limits, &mut r) {
            check_developed(&x, &limits)?;
        }
        if let Some(x) = b.graft(&m, &limits, &mut r) {
            check_developed(&x, &limits)?;
        }
    }

    #[test]
    fn the_text_form_round_trips(seed in any::<u64>(), rate in 0.0f64..1.0) {
        let limits = GraphLimits::default();
        let mut r = rng(seed);
        let g = GraphGenome::random(&limits, &mut r).mutate(&limits, rate, &mut r);
        let back = GraphGenome::from_text(&g.to_text(), &limits).expect("reads back");
        prop_assert_eq!(&back, &g);
        prop_assert_eq!(back.develop(&limits, 0), g.develop(&limits, 0));
    }
}

#[test]
fn random_genomes_are_regenerated_until_their_parts_do_not_interpenetrate() {
    let limits = GraphLimits::default();
    let once = GraphLimits {
        regenerate_tries: 1,
        ..GraphLimits::default()
    };
    let (mut clean, mut clean_once) = (0, 0);
    for seed in 0..100 {
        let ok = |g: GraphGenome| g.creature(20).interpenetrating_pairs().is_empty();
        clean += usize::from(ok(GraphGenome::random(&limits, &mut rng(seed))));
        clean_once += usize::from(ok(GraphGenome::random(&once, &mut rng(seed))));
    }
    assert!(
        clean_once < 90,
        "without regeneration some interpenetrate ({clean_once})"
    );
    assert!(clean >= 98, "with ten tries nearly none do ({clean})");
}

#[test]
fn a_genome_outside_the_limits_does_not_develop_and_says_why() {
    let mut g = two_nodes();
    g.nodes[1].connections[0].to = 5;
    let e = g.develop(&GraphLimits::default(), 0).unwrap_err();
    assert!(e.0.contains("node 1 connection 0 leads to node 5"), "{e}");
    let mut g = two_nodes();
    g.nodes[1].limits.clear();
    let e = g.develop(&GraphLimits::default(), 0).unwrap_err();
    assert!(
        e.0.contains("revolute joint needs 1 pairs of limits"),
        "{e}"
    );
    let e = GraphGenome::from_text("{\"nodes\": 3}", &GraphLimits::default()).unwrap_err();
    assert!(e.0.starts_with("not a graph genome"), "{e}");
}

/// A scratch directory of this module's, named after `name`: a fresh, empty directory's
/// path, the directory itself not yet made.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("genome-graph-{name}")).join("dir")
}

#[test]
fn genome_show_prints_nodes_connections_and_neurons() {
    let dir = scratch("show");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("g.json");
    let mut g = driven(JointKind::Universal, &[0.5, -0.5]);
    g.nodes[0].connections[0].reflection = true;
    std::fs::write(&file, g.to_text()).unwrap();
    let o = ontogeny_command()
        .args(["genome", "show"])
        .arg(&file)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for want in [
        "graph genome: 2 nodes, 0 global neurons",
        "node 0 (root): part 0.6 x 0.3 x 0.6 m, rigid joint, recursive limit 1",
        "-> node 1 on the front face at (0, 0), turned (0, 0, 0) rad, scale 1, reflected",
        "node 1: part 0.5 x 0.2 x 0.2 m, universal joint limits [-1, 1] [-1, 1]",
        "neuron 1: constant(-0.5) bias 0 inputs [1 × angle 1] -> joint dof 1",
        "develops into 2 parts, 1 joint (1 universal), 4 neurons, 2 links; valid",
    ] {
        assert!(out.contains(want), "missing {want:?} in\n{out}");
    }
    // The same file evaluates as a creature.
    let o = ontogeny_command()
        .args(["eval", "--task", "walker", "--seconds", "1"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Bad input: exit code 2 and a message.
    std::fs::write(&file, "{\"nodes\": []}").unwrap();
    assert_bad_input(
        &["genome", "show", file.to_str().unwrap()],
        "0 nodes; 1 to 20 allowed",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn evolve_with_the_graph_encoding_runs_resumes_and_throws() {
    let dir = scratch("evolve");
    let run = |extra: &[&str]| {
        let mut cmd = ontogeny_command();
        cmd.args(["evolve", "--threads", "2"]).args(extra);
        cmd.output().unwrap()
    };
    let out = dir.join("walker");
    let o = run(&[
        "--encoding",
        "graph",
        "--task",
        "walker",
        "--pop",
        "6",
        "--gens",
        "1",
        "--seconds",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Lengthen the run to two generations, then resume it.
    let config = out.join("config.toml");
    let text = std::fs::read_to_string(&config).unwrap();
    // The run's config names its joint kinds; one written before the key existed (the
    // line removed) is read as the seven kinds that run drew from.
    let read = |text: &str| {
        let source = ontogeny::lang::Source::new("config.toml", text);
        ontogeny::run::config::read_run_config::<GraphLimits>(&source)
            .unwrap()
            .limits
            .joint_kinds
    };
    assert!(text.contains("joint_kinds = \"one-axis\""), "{text}");
    assert_eq!(read(&text), JointSet::OneAxis);
    let older: String = text
        .lines()
        .filter(|l| !l.starts_with("joint_kinds"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(read(&older), JointSet::Sims);
    std::fs::write(&config, text.replace("generations = 1", "generations = 2")).unwrap();
    let o = run(&["--resume", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("resuming after generation 0"));
    let best = std::fs::read_to_string(out.join("best.json")).unwrap();
    GraphGenome::from_text(&best, &GraphLimits::default()).expect("best.json is a genome");
    assert!(!out.join("best.lsys").exists());
    let o = ontogeny_command()
        .args(["genome", "show"])
        .arg(out.join("best.json"))
        .output()
        .unwrap();
    assert!(o.status.success());

    let out = dir.join("catapult");
    let o = run(&[
        "--encoding",
        "graph",
        "--task",
        "catapult",
        "--pop",
        "6",
        "--gens",
        "2",
        "--seconds",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let best = std::fs::read_to_string(out.join("best.json")).unwrap();
    let g = GraphGenome::from_text(&best, &GraphLimits::default()).unwrap();
    assert!(g.nodes[0].connections.iter().all(|c| c.face != Face::Back));
    // The other tasks and the other preset.
    for (task, preset) in [("jump", "wwd"), ("walker", "wwd")] {
        let out = dir.join(format!("{task}-{preset}"));
        let o = run(&[
            "--encoding",
            "graph",
            "--task",
            task,
            "--preset",
            preset,
            "--pop",
            "6",
            "--gens",
            "2",
            "--seconds",
            "2",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            o.status.success(),
            "{task} {preset}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(out.join("best.json").exists());
    }
    // The aim task, from the shipped example (it names the target).
    let out = dir.join("aim");
    let o = run(&[
        "--config",
        "examples/evolve-aim.toml",
        "--pop",
        "6",
        "--gens",
        "2",
        "--seconds",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("best.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `GraphGenome::creature` takes any genome, checked or not: out-of-range and
    /// non-finite values, connections and inputs to nothing.
    #[test]
    fn development_never_panics_even_on_unchecked_genomes(
        seed in any::<u64>(),
        values in proptest::collection::vec(
            prop_oneof![any::<f64>(), Just(f64::NAN), Just(f64::INFINITY), -10.0f64..10.0],
            16,
        ),
        index in 0usize..50,
    ) {
        let mut g = GraphGenome::random(&GraphLimits::default(), &mut rng(seed));
        let mut v = values.into_iter().cycle();
        for node in &mut g.nodes {
            node.size = [v.next().unwrap(), v.next().unwrap(), v.next().unwrap()];
            node.limits = vec![(v.next().unwrap(), v.next().unwrap()); 3];
            node.recursive_limit = index as u32 % 7;
            for c in &mut node.connections {
                c.to = index;
                c.position = [v.next().unwrap(), v.next().unwrap()];
                c.orientation = [v.next().unwrap(), v.next().unwrap(), v.next().unwrap()];
                c.scale = v.next().unwrap();
            }
            for n in &mut node.neurons {
                n.bias = v.next().unwrap();
                for i in &mut n.inputs {
                    i.weight = v.next().unwrap();
                    i.source = Source::Local { neuron: index };
                }
            }
        }
        g.nodes[0].connections.push(straight(0, Face::Top, v.next().unwrap()));
        let c = g.creature(20);
        prop_assert!(c.parts.len() <= 20);
    }
}

#[test]
fn a_graph_genome_far_beyond_the_node_limit_is_refused_by_its_sizes_with_the_limits_name() {
    let one = node([0.5, 0.2, 0.2], JointKind::Revolute, 1);
    let genome = GraphGenome {
        nodes: vec![one; 100_000],
        neurons: vec![],
        projectile: None,
    };
    let text = serde_json::to_string(&genome).unwrap();
    let err = GraphGenome::from_text(&text, &GraphLimits::default()).unwrap_err();
    assert!(
        err.to_string()
            .contains("100000 nodes; 1 to 20 allowed (max_nodes)"),
        "{err}"
    );
    // The same for the command line: refused with exit code 2.
    let dir = scratch_dir("genome-graph-100000-nodes");
    let file = dir.join("huge.json");
    std::fs::write(&file, &text).unwrap();
    for verb in [&["genome", "show"][..], &["eval", "--task", "walker"][..]] {
        let o = ontogeny_command().args(verb).arg(&file).output().unwrap();
        refused(&o, "(max_nodes)");
    }
    // Too many connections on one node, named the same way.
    let mut wide = node([0.5, 0.2, 0.2], JointKind::Revolute, 1);
    wide.connections = vec![straight(0, Face::Front, 1.0); 1000];
    let text = serde_json::to_string(&GraphGenome {
        nodes: vec![wide],
        neurons: vec![],
        projectile: None,
    })
    .unwrap();
    let err = GraphGenome::from_text(&text, &GraphLimits::default()).unwrap_err();
    assert!(
        err.to_string()
            .contains("node 0: 1000 connections; at most 4 allowed (max_connections)"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_graph_genome_with_a_nan_or_text_after_it_is_refused_at_its_line_and_column() {
    use rand::SeedableRng;
    let limits = ontogeny::encoding::GraphLimits::default();
    let mut rng = ontogeny::encoding::Rng::seed_from_u64(3);
    let genome =
        <ontogeny::encoding::GraphGenome as ontogeny::encoding::Genome>::random(&limits, &mut rng);
    let text = serde_json::to_string_pretty(&genome).unwrap();
    let dir = crate::util::scratch_dir("genome-graph-broken-json");
    // The first size of the root part made NaN, which JSON cannot hold.
    let at = text.find("\"size\": [").unwrap() + "\"size\": [".len();
    let at = at + text[at..].find(|c: char| c.is_ascii_digit()).unwrap();
    let end = at + text[at..].find([',', '\n']).unwrap();
    let nan = format!("{}NaN{}", &text[..at], &text[end..]);
    let line = text[..at].lines().count();
    let column = at - text[..at].rfind('\n').unwrap();
    let file = dir.join("nan.json");
    std::fs::write(&file, &nan).unwrap();
    let said = crate::util::assert_bad_input(
        &["eval", file.to_str().unwrap(), "--task", "walker"],
        "not a graph genome: NaN is not a number JSON can hold",
    );
    assert!(
        said.contains(&format!("nan.json:{line}:{column}")),
        "{said}"
    );
    assert!(!said.contains("not a creature"), "{said}");
    // Text after the genome's closing brace.
    let file = dir.join("junk.json");
    std::fs::write(&file, format!("{text}\njunk\n")).unwrap();
    let said = crate::util::assert_bad_input(
        &["eval", file.to_str().unwrap(), "--task", "walker"],
        "not a graph genome: text after the end of the genome",
    );
    let line = text.lines().count() + 1;
    assert!(said.contains(&format!("junk.json:{line}:1")), "{said}");
}
