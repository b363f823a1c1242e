//! The builder: bodies from turtle commands and brains from edge-encoding commands, checked
//! against hand calculation.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector3;
use ontogeny::creature::{
    Actuator, Creature, JointKind, Link, NeuronFunction, Role, Sensor, Severity,
};
use ontogeny::develop::{BuildOptions, build};
use ontogeny::environment::Environment;
use ontogeny::lsystem::LSystem;

/// Builds the axiom of a one-line L-system.
fn creature(axiom: &str) -> Creature {
    creature_in(axiom, Environment::default())
}

fn creature_in(axiom: &str, env: Environment) -> Creature {
    let lsys = LSystem::from_text("t.lsys", &format!("axiom: {axiom}\n")).unwrap();
    build(
        lsys.axiom(),
        lsys.symbols(),
        &env,
        None,
        &BuildOptions::default(),
    )
}

fn close(a: Vector3<f64>, b: [f64; 3]) -> bool {
    (a - Vector3::from(b)).norm() < 1e-9
}

fn links(c: &Creature) -> Vec<(usize, usize, f64)> {
    c.brain
        .links
        .iter()
        .map(|Link { from, to, weight }| (*from, *to, *weight))
        .collect()
}

#[test]
fn forward_makes_a_box_along_the_heading() {
    let c = creature("forward(2)");
    assert_eq!(c.parts.len(), 1);
    let p = &c.parts[0];
    assert!(close(p.size, [2.0, 0.25, 0.25]));
    assert!(close(p.position, [1.0, 0.0, 0.0]));
    assert!(p.orientation.angle() < 1e-12);
    assert!(!p.growing);
    assert!((c.mass() - 2.0 * 0.25 * 0.25 * 1000.0).abs() < 1e-9);
    assert!(c.joints.is_empty() && c.is_valid());
}

#[test]
fn width_and_thickness_set_the_next_parts_size() {
    let c = creature("width(0.5) thickness(0.1) forward(2) forward");
    assert!(close(c.parts[0].size, [2.0, 0.1, 0.5]));
    assert!(close(c.parts[1].size, [1.0, 0.1, 0.5]));
    assert!(close(c.parts[1].position, [2.5, 0.0, 0.0]));
}

#[test]
fn revolute_joints_hinge_about_the_turtles_z_axis() {
    let c = creature("forward(1) revolute1 forward(1) revolute2 forward(1)");
    assert_eq!(c.parts.len(), 3);
    assert!(close(c.parts[1].position, [1.5, 0.0, 0.0]));
    let j = &c.joints[0];
    assert_eq!((j.parent, j.child, j.kind), (0, 1, JointKind::Revolute));
    assert!(close(j.anchor, [1.0, 0.0, 0.0]));
    assert!(close(j.axes[0], [0.0, 0.0, 1.0]));
    assert_eq!(j.limits, vec![(0.0, FRAC_PI_2)]);
    assert_eq!(c.joints[1].limits, vec![(-FRAC_PI_2, FRAC_PI_2)]);
    assert!(close(c.joints[1].anchor, [2.0, 0.0, 0.0]));
}

#[test]
fn twist_joints_turn_about_the_heading_and_no_joint_command_fuses() {
    let c = creature("forward twist90 forward twist180 forward forward");
    assert_eq!(c.joints[0].kind, JointKind::Twist);
    assert!(close(c.joints[0].axes[0], [1.0, 0.0, 0.0]));
    assert_eq!(c.joints[0].limits, vec![(0.0, FRAC_PI_2)]);
    assert_eq!(c.joints[1].limits, vec![(-FRAC_PI_2, FRAC_PI_2)]);
    assert_eq!(c.joints[2].kind, JointKind::Rigid);
    assert!(c.joints[2].axes.is_empty());
}

#[test]
fn turns_are_quarter_turns_about_the_turtles_axes() {
    // left: about up (y), heading x -> -z; up: about z, x -> +y; clockwise: about x.
    let c = creature("forward(1) left(1) forward(1)");
    assert!(close(c.parts[1].position, [1.0, 0.0, -0.5]));
    let c = creature("forward(1) right(1) forward(1)");
    assert!(close(c.parts[1].position, [1.0, 0.0, 0.5]));
    let c = creature("forward(1) up(1) forward(1)");
    assert!(close(c.parts[1].position, [1.0, 0.5, 0.0]));
    let c = creature("forward(1) down(0.5) forward(2)");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close(c.parts[1].position, [1.0 + h, -h, 0.0]));
    // A roll changes the hinge axis: clockwise(1) turns the turtle about its heading, taking
    // its z (right) axis to world -y.
    let c = creature("forward(1) clockwise(1) revolute1 forward(1)");
    assert!(close(c.joints[0].axes[0], [0.0, -1.0, 0.0]));
    assert!(close(c.parts[1].position, [1.5, 0.0, 0.0]));
}

#[test]
fn brackets_restore_the_turtle_and_the_current_part() {
    let c = creature("forward(1) [ left(1) forward(1) ] right(1) forward(1)");
    assert_eq!(c.parts.len(), 3);
    assert!(close(c.parts[1].position, [1.0, 0.0, -0.5]));
    assert!(close(c.parts[2].position, [1.0, 0.0, 0.5]));
    assert_eq!((c.joints[1].parent, c.joints[1].child), (0, 2));
    assert!(
        c.is_valid(),
        "branches leaving one point may overlap there: {:?}",
        c.problems
    );
    // The pending joint kind is saved and restored too.
    let c = creature("forward revolute1 [ left(1) forward ] forward");
    assert_eq!(c.joints[0].kind, JointKind::Revolute);
    assert_eq!(c.joints[1].kind, JointKind::Revolute);
    // Forward onto the same place after the branch moves onto the branch's part.
    let c = creature("forward revolute1 [ forward ] forward");
    assert_eq!((c.parts.len(), c.joints.len()), (2, 1));
}

#[test]
fn repeat_blocks_repeat() {
    let c = creature("{ forward(1) revolute2 }(3) forward(1)");
    assert_eq!(c.parts.len(), 4);
    for (k, x) in [0.5, 1.5, 2.5, 3.5].iter().enumerate() {
        assert!(close(c.parts[k].position, [*x, 0.0, 0.0]), "part {k}");
    }
    assert_eq!(
        c.joints
            .iter()
            .filter(|j| j.kind == JointKind::Revolute)
            .count(),
        3
    );
    let c = creature("{ forward { left(1) }(2) }(2)");
    // forward, half turn, forward back over the first part's parent... two parts.
    assert_eq!(c.parts.len(), 2);
}

#[test]
fn forward_onto_an_identical_part_traverses_it() {
    let c = creature("forward forward backward forward");
    assert_eq!(c.parts.len(), 2, "the last forward moves onto part 1");
    let c = creature("forward forward backward forward(2)");
    assert_eq!(c.parts.len(), 3, "a different length is a new part");
    // backward on the root does nothing (a warning); the forwards then walk along part 1.
    let c = creature("forward forward backward backward forward forward");
    assert_eq!(c.parts.len(), 3);
    assert_eq!(c.problems.len(), 1);
}

#[test]
fn maturing_commands_mark_growing_parts_and_joints() {
    let c = creature("forward mrevolute1 mforward(0.5)");
    assert!(!c.parts[0].growing && c.parts[1].growing);
    assert!(c.joints[0].growing);
    assert_eq!(c.joints[0].kind, JointKind::Revolute);
}

#[test]
fn parts_shorter_than_the_minimum_length_are_not_built() {
    use ontogeny::develop::MIN_PART_LENGTH;
    assert_eq!(MIN_PART_LENGTH, 1e-6);
    // A maturing forward that short is a bud: nothing is built, the turtle stays, no warning
    // (mforward(0) included, and round-off either side of it).
    for bud in [
        "mforward(0)",
        "mforward(5e-14)",
        "mforward(-5e-14)",
        "mforward(9e-7)",
    ] {
        let c = creature(&format!("forward(1) {bud} revolute1 forward(1)"));
        assert_eq!(c.parts.len(), 2, "{bud}");
        assert!(close(c.parts[1].position, [1.5, 0.0, 0.0]), "{bud}");
        assert_eq!(
            c.joints[0].kind,
            JointKind::Revolute,
            "{bud}: the joint waits"
        );
        assert!(c.problems.is_empty(), "{bud}: {:?}", c.problems);
    }
    // Just over the minimum: a part.
    let c = creature("forward(1) mforward(2e-6)");
    assert_eq!(c.parts.len(), 2);
    assert!((c.parts[1].size.x - 2e-6).abs() < 1e-18);
    // A plain forward that short is ignored with a warning naming it.
    let c = creature("forward(1) forward(5e-7) forward(1)");
    assert_eq!(c.parts.len(), 2);
    assert!(close(c.parts[1].position, [1.5, 0.0, 0.0]));
    assert_eq!(c.problems.len(), 1, "{:?}", c.problems);
    assert_eq!(c.problems[0].severity, Severity::Warning);
    assert!(
        c.problems[0]
            .message
            .contains("shorter than the shortest part, 1e-6"),
        "{}",
        c.problems[0].message
    );
    // A negative maturing length beyond round-off is still a mistake.
    let c = creature("forward(1) mforward(-1)");
    assert_eq!(c.parts.len(), 1);
    assert_eq!(c.problems.len(), 1, "{:?}", c.problems);
}

#[test]
fn control_tokens_build_nothing() {
    let c = creature("A B(2) forward C");
    assert_eq!(c.parts.len(), 1);
    assert!(c.problems.is_empty());
}

#[test]
fn interpenetrating_parts_make_the_creature_invalid() {
    let c = creature("forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)");
    assert!(!c.is_valid());
    assert!(
        c.problems
            .iter()
            .any(|p| p.message == "parts 0 and 3 interpenetrate"),
        "{:?}",
        c.problems
    );
    let square = creature("forward(1) left(1) forward(1) left(1) forward(1)");
    assert!(square.is_valid(), "{:?}", square.problems);
}

/// Every frame of every shipped example that builds a body, grown for physics (continuous
/// ones to their final time), with the plastic one also in a rich environment. The
/// textbook's plants (`abop-*`, the stochastic plant) are pictures, tested in `textbook`.
#[test]
fn every_shipped_example_stays_valid() {
    use ontogeny::develop::grow;
    use ontogeny::lsystem::DeriveOptions;
    let mut paths: Vec<_> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lsys"))
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            !name.starts_with("abop-") && name != "stochastic-plant.lsys"
        })
        .collect();
    paths.sort();
    let mut bodies = Vec::new();
    for path in &paths {
        let lsys = LSystem::from_path(path).unwrap();
        let mut runs = vec![DeriveOptions::default()];
        if path.ends_with("plastic.lsys") || path.ends_with("plastic-genome.lsys") {
            runs.push(DeriveOptions {
                env: vec![(0, 1.0)],
                ..DeriveOptions::default()
            });
        }
        for options in runs {
            let frames = grow(&lsys, &options, None, &BuildOptions::default()).unwrap();
            for f in frames.iter().filter(|f| !f.creature.parts.is_empty()) {
                assert!(
                    f.creature.is_valid(),
                    "{} at t = {}: {:?}",
                    path.display(),
                    f.t,
                    f.creature.problems
                );
            }
            let last = &frames.last().unwrap().creature;
            bodies.push((path.clone(), last.parts.len()));
        }
    }
    let parts = |name: &str| {
        bodies
            .iter()
            .filter(|(p, _)| p.ends_with(name))
            .map(|(_, n)| *n)
            .collect::<Vec<_>>()
    };
    // The examples the test is about really build bodies (and branch at joints).
    assert_eq!(parts("snake.lsys"), [9]);
    assert_eq!(parts("quadruped.lsys"), [11]);
    assert_eq!(parts("thrower.lsys"), [2]);
    assert_eq!(parts("plastic.lsys"), [4, 15]);
}

#[test]
fn legitimate_turtle_shapes_do_not_interpenetrate() {
    for commands in [
        // A leg at 90 degrees from the end of a wide body, the body going on.
        "width(0.6) thickness(0.2) forward(0.8) [ left(1) width(0.15) thickness(0.15) forward(0.4) ] forward(0.8)",
        // Legs on both sides of one joint point.
        "width(0.6) thickness(0.2) forward(0.8) [ left(1) forward(0.4) ] [ right(1) forward(0.4) ] forward(0.8)",
        // A chain with revolute2 hinges at 90 degrees.
        "forward(1) revolute2 down(1) forward(1) revolute2 up(1) forward(1)",
        // A thin part on a thick one, straight and at 90 degrees (shorter than the thick
        // part's half height), and a thick part hanging from a thin one.
        "width(1) thickness(1) forward(1) width(0.1) thickness(0.1) forward(1)",
        "width(1) thickness(1) forward(1) width(0.1) thickness(0.1) up(1) forward(0.3)",
        "width(0.15) thickness(0.15) forward(1.2) down(1) revolute2 width(1) thickness(1) forward(0.4)",
        // Turns of 45 and 60 degrees, and a 90-degree turn whose part is then rolled 45 degrees
        // (its corner reaches deepest into its parent).
        "forward(1) left(0.5) forward(1)",
        "width(0.6) forward(1) up(0.6667) forward(1)",
        "forward(1) left(1) clockwise(0.5) forward(1)",
        // Two branches at 90 degrees to each other, each at 45 degrees to the parent.
        "forward(1) [ left(0.5) forward(1) ] right(0.5) forward(1)",
    ] {
        let c = creature(commands);
        assert!(c.parts.len() >= 2, "{commands}");
        assert_eq!(c.interpenetrating_pairs(), [], "{commands}");
        assert!(c.is_valid(), "{commands}: {:?}", c.problems);
    }
}

#[test]
fn a_branch_folding_back_onto_its_parent_interpenetrates() {
    // 180 degrees: the branch lies along its parent.
    let c = creature("forward(1) [ left(2) forward(1) ]");
    assert_eq!(c.interpenetrating_pairs(), [(0, 1)]);
    assert!(!c.is_valid());
    // 135 degrees: folded back far beyond the joint's contact region.
    let c = creature("forward(1) left(1.5) forward(1)");
    assert_eq!(c.interpenetrating_pairs(), [(0, 1)]);
    // A short branch folded into a fat parent lies inside it, within the contact radius of
    // the joint point: its centre inside the parent gives it away.
    let c = creature(
        "width(1) thickness(1) forward(1) [ left(2) width(0.25) thickness(0.25) forward(0.5) ]",
    );
    assert_eq!(c.interpenetrating_pairs(), [(0, 1)]);
    // Two branches 45 degrees apart from one point overlap beyond the contact region.
    let c = creature("forward(1) [ left(0.5) forward(1) ] forward(1)");
    assert_eq!(c.interpenetrating_pairs(), [(1, 2)]);
}

#[test]
fn out_of_range_arguments_are_warnings_with_the_module() {
    let c = creature("forward(-1) width(0) forward(1) backward");
    let warnings: Vec<_> = c
        .problems
        .iter()
        .filter(|p| p.severity == Severity::Warning)
        .collect();
    assert_eq!(warnings.len(), 3, "{:?}", c.problems);
    assert_eq!(warnings[0].module.as_deref(), Some("forward(-1)"));
    assert!(c.is_valid());
}

#[test]
fn too_many_parts_is_an_error() {
    let lsys = LSystem::from_text("t.lsys", "axiom: { forward }(50)\n").unwrap();
    let options = BuildOptions {
        max_parts: 10,
        ..BuildOptions::default()
    };
    let c = build(
        lsys.axiom(),
        lsys.symbols(),
        &Environment::default(),
        Some(2.0),
        &options,
    );
    assert!(!c.is_valid());
    let p = c
        .problems
        .iter()
        .find(|p| p.severity == Severity::Error)
        .unwrap();
    assert!(p.message.contains("more than 10 parts"), "{}", p.message);
    assert_eq!(p.t, Some(2.0));
}

// ---- brains ----------------------------------------------------------------------------

#[test]
fn the_network_starts_with_one_oscillator_and_a_link_into_it() {
    let c = creature("A");
    assert_eq!(c.brain.neurons.len(), 1);
    assert_eq!(c.brain.neurons[0].function, NeuronFunction::Oscillator);
    assert_eq!(links(&c), [(0, 0, 1.0)]);
}

#[test]
fn split_inserts_a_sigmoid_neuron_into_the_current_link() {
    let c = creature("split(0.5)");
    assert_eq!(c.brain.neurons[1].function, NeuronFunction::Sigmoid);
    assert_eq!(links(&c), [(0, 1, 1.0), (1, 0, 0.5)]);
    // The current link is now 1 -> 0: duplicate and weight act on it.
    let c = creature("split(0.5) duplicate(2) weight(0.25)");
    assert_eq!(links(&c), [(0, 1, 1.0), (1, 0, 0.75), (1, 0, 2.0)]);
}

#[test]
fn loop_reverse_cut_and_weights() {
    assert_eq!(
        links(&creature("split loop(3)")),
        [(0, 1, 1.0), (1, 0, 1.0), (0, 0, 3.0)]
    );
    assert_eq!(
        links(&creature("split reverse")),
        [(0, 1, 1.0), (0, 1, 1.0)]
    );
    assert_eq!(links(&creature("split cut")), [(0, 1, 1.0)]);
    // After a cut the current link is virtual: weight creates it again.
    assert_eq!(
        links(&creature("split cut increase(0.4)")),
        [(0, 1, 1.0), (1, 0, 0.4)]
    );
    assert_eq!(links(&creature("decrease(2)")), [(0, 0, -1.0)]);
    assert_eq!(links(&creature("weight(0.5)")), [(0, 0, 1.5)]);
}

#[test]
fn next_moves_the_current_link_to_another_input_of_the_target() {
    // Inputs of neuron 0 after split duplicate(2): links 1 (w 1) and 2 (w 2). next -> link 2.
    let c = creature("split duplicate(2) next weight(10)");
    assert_eq!(links(&c), [(0, 1, 1.0), (1, 0, 1.0), (1, 0, 12.0)]);
}

/// `split split(2) reverse target reverse`: links 0 -> 1 (w 1), 1 -> 2 (w 1), 2 -> 0 (w 2) and
/// the sensor 3 -> 2 (w 1); the current link is 2 -> 0, and its source, neuron 2, has two
/// inputs: from neuron 1 (input 0) and from the sensor 3 (input 1).
const TWO_PARENTS: &str = "split split(2) reverse target reverse";

#[test]
fn parent_moves_the_source_up_to_its_nth_input_and_keeps_the_target() {
    let base = [(0, 1, 1.0), (1, 2, 1.0), (2, 0, 2.0), (3, 2, 1.0)];
    assert_eq!(links(&creature(TWO_PARENTS)), base);
    // parent(0): the source becomes neuron 1; there is no link 1 -> 0, so the current link is
    // virtual and parent itself makes nothing; weight(5) makes it with weight 5.
    assert_eq!(links(&creature(&format!("{TWO_PARENTS} parent(0)"))), base);
    let c = creature(&format!("{TWO_PARENTS} parent(0) weight(5)"));
    assert_eq!(links(&c)[..4], base);
    assert_eq!(links(&c)[4..], [(1, 0, 5.0)]);
    // parent(1): the sensor; increase materialises 3 -> 0 with its weight.
    let c = creature(&format!("{TWO_PARENTS} parent(1) increase(0.25)"));
    assert_eq!(links(&c)[4..], [(3, 0, 0.25)]);
    // n counts from 0 modulo the number of inputs: parent(3) is parent(1), parent(2) parent(0).
    let c = creature(&format!("{TWO_PARENTS} parent(3) decrease(0.5)"));
    assert_eq!(links(&c)[4..], [(3, 0, -0.5)]);
    let c = creature(&format!("{TWO_PARENTS} parent(2) weight(5)"));
    assert_eq!(links(&c)[4..], [(1, 0, 5.0)]);
    // The default is parent(0); twice climbs two neurons: 2 -> 1 -> 0, still into neuron 0.
    let c = creature(&format!("{TWO_PARENTS} parent parent weight(7)"));
    assert_eq!(links(&c)[4..], [(0, 0, 7.0)]);
    assert!(c.problems.is_empty(), "{:?}", c.problems);
}

#[test]
fn parent_lands_on_an_actual_link_when_one_exists() {
    // split: 0 -> 1, 1 -> 0 (current). loop(3): 0 -> 0 (w 3). parent: the source 1's input is
    // neuron 0, and 0 -> 0 exists: it becomes the current link, so weight adds to it.
    assert_eq!(
        links(&creature("split loop(3) parent weight(0.5)")),
        [(0, 1, 1.0), (1, 0, 1.0), (0, 0, 3.5)]
    );
    // Two links 0 -> 0: the first made is the current link.
    assert_eq!(
        links(&creature("split loop(3) loop(4) parent weight(0.5)")),
        [(0, 1, 1.0), (1, 0, 1.0), (0, 0, 3.5), (0, 0, 4.0)]
    );
    // The first network's self-link: neuron 0's parent is itself, and the link stays current.
    assert_eq!(links(&creature("parent weight(2)")), [(0, 0, 3.0)]);
}

#[test]
fn parent_of_a_neuron_without_inputs_does_nothing() {
    // parent(1) moves the source to the sensor 3, which has no inputs: the second parent is
    // ignored with a warning, and the (virtual) current link 3 -> 0 stays.
    let c = creature(&format!("{TWO_PARENTS} parent(1) parent weight(1)"));
    assert_eq!(links(&c)[4..], [(3, 0, 1.0)]);
    assert_eq!(c.problems.len(), 1, "{:?}", c.problems);
    assert_eq!(c.problems[0].severity, Severity::Warning);
    assert!(
        c.problems[0].message.contains("no input links"),
        "{}",
        c.problems[0].message
    );
    assert_eq!(c.problems[0].module.as_deref(), Some("parent"));
}

#[test]
fn a_virtual_link_from_parent_survives_push_and_pop() {
    // The virtual link 1 -> 0 is saved by '[' and restored by ']'; then weight makes it.
    let c = creature(&format!("{TWO_PARENTS} parent [ reverse ] weight(5)"));
    assert_eq!(links(&c)[4..], [(1, 0, 5.0)]);
}

#[test]
fn merge_folds_the_source_neuron_into_the_target() {
    let c = creature("split merge");
    assert_eq!(c.brain.neurons.len(), 1);
    assert_eq!(links(&c), [(0, 0, 1.0), (0, 0, 1.0)]);
    let c = creature("split split setfunc(0) merge");
    // split split: 0 -> 1 -> 2 -> 0 (neurons 1, 2 sigmoid), current 2 -> 0.
    // setfunc(0): neuron 0 linear. merge: neuron 2 into 0.
    assert_eq!(c.brain.neurons.len(), 2);
    assert_eq!(c.brain.neurons[0].function, NeuronFunction::Linear);
    assert_eq!(links(&c), [(0, 1, 1.0), (1, 0, 1.0), (0, 0, 1.0)]);
}

#[test]
fn setfunc_changes_the_target_neurons_function() {
    assert_eq!(
        creature("setfunc(1)").brain.neurons[0].function,
        NeuronFunction::Sigmoid
    );
    assert_eq!(
        creature("setfunc(0)").brain.neurons[0].function,
        NeuronFunction::Linear
    );
    assert_eq!(
        creature("setfunc(2)").brain.neurons[0].function,
        NeuronFunction::Oscillator
    );
    assert_eq!(
        creature("setfunc(4)").brain.neurons[0].function,
        NeuronFunction::Sigmoid,
        "modulo 3"
    );
}

#[test]
fn bias_sets_the_target_neurons_bias() {
    let biases = |c: &Creature| c.brain.neurons.iter().map(|n| n.bias).collect::<Vec<_>>();
    assert_eq!(biases(&creature("A")), [0.0]);
    assert_eq!(biases(&creature("bias(0.4)")), [0.4]);
    assert_eq!(
        biases(&creature("bias")),
        [1.0],
        "defaults to 1, like a weight"
    );
    // It sets, it does not add.
    assert_eq!(biases(&creature("bias(0.4) bias(-0.25)")), [-0.25]);
    // After split the current link is 1 -> 0: the target is neuron 0; reversed, neuron 1.
    assert_eq!(biases(&creature("split(0.5) bias(0.3)")), [0.3, 0.0]);
    assert_eq!(
        biases(&creature("split(0.5) reverse bias(0.3)")),
        [0.0, 0.3]
    );
    // The bias survives a cut (the target is still there).
    assert_eq!(biases(&creature("split cut bias(0.2)")), [0.2, 0.0]);
    // A sensor's output is its reading: no bias, and a warning.
    let c = creature("forward touch next(1) reverse bias(0.5)");
    assert!(matches!(c.brain.neurons[1].role, Role::Sensor { .. }));
    assert_eq!(biases(&c), [0.0, 0.0]);
    assert!(
        c.problems
            .iter()
            .any(|p| p.severity == Severity::Warning && p.message.contains("bias ignored")),
        "{:?}",
        c.problems
    );
    assert!(c.is_valid());
}

#[test]
fn outputs_drive_the_current_parts_joint() {
    let c = creature("forward revolute1 forward output(0.7) output");
    let o = &c.brain.neurons[1];
    assert_eq!(
        o.role,
        Role::Actuator {
            actuator: Actuator::Joint { joint: 0, dof: 0 }
        }
    );
    assert_eq!(o.part, Some(1));
    assert_eq!(links(&c), [(0, 0, 1.0), (0, 1, 0.7)]);
    assert_eq!(c.brain.neurons.len(), 2, "a 1-DOF joint takes one output");
    assert_eq!(c.problems.len(), 1);
    // A rigid joint or the root part has nothing to drive.
    let c = creature("forward forward output");
    assert_eq!(c.brain.neurons.len(), 1);
    assert_eq!(c.problems.len(), 1);
}

#[test]
fn sensors_feed_the_current_links_target_and_effectors_read_it() {
    let env = Environment::new(vec![0.0, 0.0]);
    let c = creature_in(
        "forward revolute2 forward touch angle chem(1) target secrete(0) release chem(7)",
        env,
    );
    let roles: Vec<Role> = c.brain.neurons.iter().map(|n| n.role).collect();
    assert_eq!(
        roles[1..],
        [
            Role::Sensor {
                sensor: Sensor::Touch {
                    part: 1,
                    face: None
                }
            },
            Role::Sensor {
                sensor: Sensor::Angle { joint: 0, dof: 0 }
            },
            Role::Sensor {
                sensor: Sensor::Chemical { slot: 1 }
            },
            Role::Sensor {
                sensor: Sensor::Target
            },
            Role::Actuator {
                actuator: Actuator::Secrete { slot: 0 }
            },
            Role::Actuator {
                actuator: Actuator::Release
            },
        ]
    );
    assert_eq!(
        links(&c)[1..],
        [
            (1, 0, 1.0),
            (2, 0, 1.0),
            (3, 0, 1.0),
            (4, 0, 1.0),
            (0, 5, 1.0),
            (0, 6, 1.0)
        ]
    );
    assert!(
        c.problems.iter().any(|p| p.message.contains("slot 7")),
        "{:?}",
        c.problems
    );
    assert_eq!(c.environment, vec![0.0, 0.0]);
}

#[test]
fn brackets_restore_the_current_link() {
    let c = creature("[ split(2) ] weight(5)");
    // After ], the current link is the original one (now 0 -> 1 after the split moved it).
    assert_eq!(links(&c), [(0, 1, 6.0), (1, 0, 2.0)]);
}

#[test]
fn creature_json_round_trips() {
    let env = Environment::new(vec![0.5]);
    let c = creature_in(
        "forward revolute1 forward split output touch chem(0) mforward",
        env,
    );
    let text = serde_json::to_string(&c).unwrap();
    let back: Creature = serde_json::from_str(&text).unwrap();
    assert_eq!(back, c);
}

#[test]
fn a_merge_inside_a_branch_leaves_no_link_to_a_removed_neuron() {
    for axiom in [
        "forward revolute2 forward split(0.5) [ merge ] duplicate output",
        "split(0.5) [ merge ] cut split",
    ] {
        let c = creature(axiom);
        assert!(
            c.check_consistency().is_ok(),
            "{axiom}: {:?}",
            c.check_consistency()
        );
        let n = c.brain.neurons.len();
        assert!(
            c.brain.links.iter().all(|l| l.from < n && l.to < n),
            "{axiom}"
        );
    }
    // split(0.5): 0 -> 1 -> 0, current 1 -> 0. [ merge ]: 1 folds into 0. After ], the saved
    // current link (1 -> 0) is now 0 -> 0; duplicate copies it.
    let c = creature("split(0.5) [ merge ] duplicate(3)");
    assert_eq!(links(&c), [(0, 0, 1.0), (0, 0, 0.5), (0, 0, 3.0)]);
}

#[test]
fn a_joint_command_lost_to_traversal_is_a_warning() {
    let c = creature("forward forward backward revolute2 forward");
    assert_eq!(c.parts.len(), 2);
    assert!(
        c.problems
            .iter()
            .any(|p| p.message.contains("joint command")),
        "{:?}",
        c.problems
    );
}

#[test]
fn overlap_away_from_the_joint_is_caught_even_between_joined_parts_and_siblings() {
    for axiom in [
        "forward [ forward ] up(2) forward",
        "forward [ left(0.1) forward ] left(0.15) forward",
        "[ forward ] forward",
    ] {
        assert!(!creature(axiom).is_valid(), "{axiom}");
    }
    for axiom in [
        "forward(1) [ left(1) forward(1) ] right(1) forward(1)",
        "forward(1) up(0.5) forward(1)",
        "forward(1) [ left(0.5) forward(1) ] right(0.5) forward(1)",
    ] {
        let c = creature(axiom);
        assert!(c.is_valid(), "{axiom}: {:?}", c.problems);
    }
}

#[test]
fn an_unclosed_bracket_is_a_warning_as_an_unmatched_one_is() {
    let unclosed =
        ontogeny::develop::creature_from_commands("forward(1) [ revolute2 forward(1)").unwrap();
    assert_eq!(unclosed.parts.len(), 2);
    assert!(unclosed.is_valid());
    let warning = unclosed
        .problems
        .iter()
        .find(|p| p.message.contains("'[' without a matching ']'"))
        .expect("a warning");
    assert_eq!(warning.severity, ontogeny::creature::Severity::Warning);
    let balanced =
        ontogeny::develop::creature_from_commands("forward(1) [ revolute2 forward(1) ]").unwrap();
    assert!(balanced.problems.is_empty(), "{:?}", balanced.problems);
}

// ---- runaway work is bounded -------------------------------------------------------------

#[test]
fn the_builder_stops_at_the_first_part_past_the_limit_however_long_the_string() {
    let axiom = vec!["forward(0.5)"; 5000].join(" ");
    let lsys = LSystem::from_text("t.lsys", &format!("axiom: {axiom} [ left forward ]\n")).unwrap();
    let options = BuildOptions {
        max_parts: 10,
        ..BuildOptions::default()
    };
    let c = build(
        lsys.axiom(),
        lsys.symbols(),
        &Environment::default(),
        None,
        &options,
    );
    // The 11th part is the one that passes the limit; nothing after it is built.
    assert_eq!(c.parts.len(), 11);
    assert!(!c.is_valid());
    let errors: Vec<&str> = c
        .problems
        .iter()
        .filter(|p| p.severity == Severity::Error)
        .map(|p| p.message.as_str())
        .collect();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(errors[0].contains("more than 10 parts"), "{}", errors[0]);
    // A stopped build does not blame the string for the branch it never closed.
    assert!(c.problems.iter().all(|p| !p.message.contains("'['")));
    // Repeat blocks stop too.
    let lsys = LSystem::from_text("t.lsys", "axiom: { forward(0.5) }(100)\n").unwrap();
    let c = build(
        lsys.axiom(),
        lsys.symbols(),
        &Environment::default(),
        None,
        &options,
    );
    assert_eq!(c.parts.len(), 11);
}

#[test]
fn growth_that_keeps_every_frame_is_refused_before_deriving_past_the_frame_limit() {
    use ontogeny::develop::{MAX_KEPT_FRAMES, grow, grow_last};
    use ontogeny::lsystem::DeriveOptions;
    let text = |steps: u64| {
        format!("axiom: forward(1)\nderivation length: {steps}\nforward(x) --> forward(x)\n")
    };
    let options = DeriveOptions::default();
    let build_options = BuildOptions::default();
    // The last frame allowed: every frame is kept.
    let lsys = LSystem::from_text("ok.lsys", &text(MAX_KEPT_FRAMES - 1)).unwrap();
    let frames = grow(&lsys, &options, None, &build_options).unwrap();
    assert_eq!(frames.len() as u64, MAX_KEPT_FRAMES);
    // One more frame is refused, and so is a billion, before anything is derived.
    for steps in [MAX_KEPT_FRAMES, 1_000_000_000] {
        let lsys = LSystem::from_text("long.lsys", &text(steps)).unwrap();
        let err = grow(&lsys, &options, None, &build_options).unwrap_err();
        let shown = err.to_string();
        assert!(
            shown.contains(&format!("{} frames", steps + 1)) && shown.contains("derivation length"),
            "{shown}"
        );
    }
    // In continuous time, the frames are time / dt.
    let lsys = LSystem::from_text("t.lsys", "time: 20000\naxiom: forward(1)\n").unwrap();
    let shown = grow(&lsys, &options, None, &build_options)
        .unwrap_err()
        .to_string();
    assert!(
        shown.contains("20001 frames") && shown.contains("dt"),
        "{shown}"
    );
    // Keeping only the last frame has no such limit, and it is grow's last frame.
    let lsys = LSystem::from_text("long.lsys", &text(MAX_KEPT_FRAMES + 5)).unwrap();
    let last = grow_last(&lsys, &options, None, &build_options, &mut |_| {}).unwrap();
    assert_eq!(last.frame.step, MAX_KEPT_FRAMES + 5);
    let lsys = LSystem::from_path(std::path::Path::new("examples/snake.lsys")).unwrap();
    let all = grow(&lsys, &options, None, &build_options).unwrap();
    let last = grow_last(&lsys, &options, None, &build_options, &mut |_| {}).unwrap();
    assert_eq!(Some(&last.frame), all.last());
}

#[test]
fn repeat_blocks_that_build_nothing_stop_past_a_million_repeated_modules() {
    use ontogeny::develop::MAX_REPEATED_MODULES;
    // 10^8 turns (10^16 with eight levels) would run for seconds (years).
    let c = creature("forward(1) { { { { left }(100) }(100) }(100) }(100) forward(1)");
    assert!(!c.is_valid());
    let error = c
        .problems
        .iter()
        .find(|p| p.severity == Severity::Error)
        .expect("an error");
    assert!(
        error
            .message
            .contains(&format!("more than {MAX_REPEATED_MODULES} modules")),
        "{}",
        error.message
    );
    // The part after the blocks is never built.
    assert_eq!(c.parts.len(), 1);
    // Blocks within the budget build as before: 100 × 100 turns, then a part.
    let c = creature("forward(1) { { left }(100) }(100) forward(1)");
    assert!(c.is_valid(), "{:?}", c.problems);
    assert_eq!(c.parts.len(), 2);
    // Many '{' without a '}' are each ignored, in one pass over the string.
    let opens = vec!["{"; 200_000].join(" ");
    let c = creature(&format!("forward(1) {opens} forward(1)"));
    assert_eq!(c.parts.len(), 2);
    assert_eq!(
        c.problems
            .iter()
            .filter(|p| p.message.contains("no matching '}'"))
            .count(),
        200_000
    );
}
