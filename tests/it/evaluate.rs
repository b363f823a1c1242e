//! The evaluator and the tasks: fitness terms by hand, the activation sequence, explosions,
//! statuses, determinism across thread counts.

mod scoring;

use crate::util::grown;

use ontogeny::creature::{Creature, JointId, PartId};
use ontogeny::sim::{ActuatorModel, SimOptions};
use ontogeny::task::{self, JumpOptions, Status, WalkerOptions, size_coefficients};
use rayon::prelude::*;

fn creature(axiom: &str) -> Creature {
    ontogeny::develop::creature_from_commands(axiom).unwrap()
}

fn short_walk() -> WalkerOptions {
    WalkerOptions {
        seconds: 2.0,
        ..WalkerOptions::default()
    }
}

#[test]
fn size_coefficients_by_hand() {
    // Two parts: 1 x 0.25 x 0.25 and 2 x 0.5 x 0.25.
    let c = creature("forward(1) width(0.25) thickness(0.5) forward(2)");
    let (c_l, c_s, c_v) = size_coefficients(&c);
    assert!((c_l - (1.5 + 2.75) / 2.0).abs() < 1e-12);
    let s1 = 2.0 * (0.25 + 0.25 + 0.0625);
    let s2 = 2.0 * (1.0 + 0.5 + 0.125);
    assert!((c_s - (s1 + s2) / 2.0).abs() < 1e-12);
    assert!((c_v - (0.0625 + 0.25) / 2.0).abs() < 1e-12);
}

#[test]
fn a_passive_creature_scores_near_zero_and_its_terms_follow_equation_1() {
    let c = creature("forward(1) revolute2 forward(1)");
    let e = task::walker(&c, &SimOptions::default(), &short_walk(), false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let d = e.terms["D_w"];
    assert!(d < 0.01, "a passive creature does not walk: D_w = {d}");
    let expected = d * e.terms["C_v"] / (e.terms["C_s"] * e.terms["C_l"]) * 1.02f64.powi(2);
    assert!((e.fitness - expected).abs() < 1e-15);
    assert_eq!(e.terms["N"], 2.0);
}

#[test]
fn the_activation_sequence_happens_at_the_right_times() {
    let c = grown("examples/snake.lsys");
    let options = short_walk();
    let sim = SimOptions::default();
    let e = task::walker(&c, &sim, &options, true);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let settled = e.terms["settled_at"];
    // At rest takes at least the 0.5 s calm window.
    assert!(settled >= 0.5 - 1e-9, "{settled}");
    // Measuring starts after 1 s of controller (Chaumont 3.3's final protocol) and at least
    // 0.5 s of rest.
    assert_eq!(options.activation, 1.0);
    assert!(e.terms["measured_from"] - settled >= 1.0 + 0.5 - 1e-9);
    // The recording covers every step to the end of the measured walk.
    let last = e.recording.last().unwrap().t;
    assert!(
        (last - (e.terms["measured_from"] + 2.0)).abs() < 1e-9,
        "{last}"
    );
    assert!(e.terms["D_w"] > 0.05, "the snake moves: {}", e.terms["D_w"]);
}

#[test]
fn an_exploding_creature_is_caught() {
    let c = grown("examples/snake.lsys");
    let sim = SimOptions {
        actuator: ActuatorModel::Velocity,
        strength: 1e9,
        max_speed: 1e6,
        ..SimOptions::default()
    };
    let e = task::walker(&c, &sim, &short_walk(), false);
    assert_eq!(e.status, Status::Exploded, "{e:?}");
    assert_eq!(e.fitness, task::FAILURE_FITNESS);
}

#[test]
fn rejected_creatures_are_not_simulated() {
    let crossing = creature("forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)");
    let e = task::walker(&crossing, &SimOptions::default(), &short_walk(), false);
    assert_eq!(e.status, Status::SelfIntersecting);
    let tall = creature("up(1) { forward(1) }(20)");
    let e = task::walker(&tall, &SimOptions::default(), &short_walk(), false);
    assert_eq!(e.status, Status::TooTall);
    let empty = creature("A");
    assert_eq!(
        task::jump(
            &empty,
            &SimOptions::default(),
            &JumpOptions::default(),
            false
        )
        .status,
        Status::Invalid
    );
}

#[test]
fn a_passive_creature_does_not_jump() {
    let c = creature("forward(1) revolute2 forward(1)");
    let options = JumpOptions {
        seconds: 1.0,
        ..JumpOptions::default()
    };
    let e = task::jump(&c, &SimOptions::default(), &options, false);
    assert_eq!(e.status, Status::Ok);
    assert!(e.fitness < 0.01, "{}", e.fitness);
}

#[test]
fn fitness_is_bit_identical_across_thread_counts() {
    let creatures: Vec<Creature> = ["examples/snake.lsys", "examples/quadruped.lsys"]
        .iter()
        .map(|p| grown(p))
        .collect();
    let sim = SimOptions::default();
    let options = short_walk();
    let evaluate = |c: &Creature| task::walker(c, &sim, &options, false).fitness.to_bits();
    let sequential: Vec<u64> = creatures.iter().map(evaluate).collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let parallel: Vec<u64> = pool.install(|| creatures.par_iter().map(evaluate).collect());
        assert_eq!(parallel, sequential, "{threads} threads");
    }
}

#[test]
fn the_release_fires_at_step_30_without_a_signal_and_earlier_with_one() {
    let options = task::CatapultOptions {
        max_seconds: 2.0,
        ..task::CatapultOptions::default()
    };
    let plain = creature("forward(1) revolute2 forward(1) output(1)");
    let e = task::catapult(&plain, &SimOptions::default(), &options, false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    assert_eq!(e.terms["release_step"], 30.0);
    // The release neuron reads the oscillator, positive from the first update; updates are
    // synchronous, so the release neuron is positive after the second step.
    let signalled = creature("forward(1) revolute2 forward(1) output(1) release");
    let e = task::catapult(&signalled, &SimOptions::default(), &options, false);
    assert_eq!(e.terms["release_step"], 2.0);
}

#[test]
fn distance_to_a_known_trajectory() {
    use nalgebra::Vector3;
    let path = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(2.0, 2.0, 0.0),
        Vector3::new(4.0, 0.0, 0.0),
    ];
    // The closest point to (2, 0, 0) is on either segment, at (1, 1, 0): √2 away.
    let d = task::distance_to_trajectory(&path, &Vector3::new(2.0, 0.0, 0.0));
    assert!((d - 2f64.sqrt()).abs() < 1e-12);
    // Beyond the end along the last segment, the end point is closest: 2√2 away.
    let d = task::distance_to_trajectory(&path, &Vector3::new(6.0, -2.0, 0.0));
    assert!((d - 8f64.sqrt()).abs() < 1e-12);
    // A point on the trajectory.
    assert!(task::distance_to_trajectory(&path, &Vector3::new(3.0, 1.0, 0.0)) < 1e-12);
}

#[test]
fn the_thrower_throws_and_aiming_subtracts_the_miss() {
    let c = grown("examples/thrower.lsys");
    let e = task::catapult(
        &c,
        &SimOptions::default(),
        &task::CatapultOptions::default(),
        false,
    );
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    assert!(e.fitness > 3.0, "D_p = {}", e.fitness);
    let aim = task::CatapultOptions {
        target: Some(nalgebra::Vector3::new(5.0, 0.0, 0.0)),
        ..task::CatapultOptions::default()
    };
    let a = task::catapult(&c, &SimOptions::default(), &aim, false);
    assert!((a.fitness - (a.terms["D_p"] - a.terms["D_t"])).abs() < 1e-12);
    assert!(
        (a.terms["D_p"] - e.terms["D_p"]).abs() < 1e-12,
        "the target does not change the throw"
    );
}

#[test]
fn walking_with_dinosaurs_fitness_variants() {
    use ontogeny::task::WalkerFitness;
    let c = grown("examples/snake.lsys");
    let run = |fitness: WalkerFitness| {
        let options = WalkerOptions {
            fitness: fitness.into(),
            ..short_walk()
        };
        task::walker(&c, &SimOptions::default(), &options, false)
    };
    let iterative = run(WalkerFitness::IterativeMove);
    let i = iterative.terms["iterative_move"];
    assert_eq!(iterative.fitness, i);
    assert!(i > 0.0);
    assert!((run(WalkerFitness::BoxLover).fitness - i * 9.0).abs() < 1e-12);
    assert!((run(WalkerFitness::FatLover).fitness - i * c.mass()).abs() < 1e-12);
    assert_eq!(run(WalkerFitness::DwarfSlayer).fitness, i);
    let small = creature("forward(1) revolute2 forward(1) output(1)");
    let options = WalkerOptions {
        fitness: WalkerFitness::DwarfSlayer.into(),
        ..short_walk()
    };
    assert_eq!(
        task::walker(&small, &SimOptions::default(), &options, false).fitness,
        0.0
    );
}

#[test]
fn joints_of_two_and_three_degrees_of_freedom_simulate() {
    use nalgebra::Vector3;
    use ontogeny::creature::{Actuator, JointKind, Link, Neuron, NeuronFunction, Role, Sensor};
    let half_pi = std::f64::consts::FRAC_PI_2;
    for (kind, dof) in [(JointKind::Universal, 2), (JointKind::Spherical, 3)] {
        let mut c = creature("forward(1) forward(1)");
        let joint = &mut c.joints[0];
        joint.kind = kind;
        joint.axes = vec![Vector3::z(), Vector3::y(), Vector3::x()][..dof].to_vec();
        joint.limits = vec![(-half_pi, half_pi); dof];
        for d in 0..dof {
            let output = c.brain.neurons.len();
            c.brain.neurons.push(Neuron {
                function: NeuronFunction::Linear,
                params: vec![],
                bias: 0.0,
                role: Role::Actuator {
                    actuator: Actuator::Joint { joint: 0, dof: d },
                },
                part: Some(1),
            });
            c.brain.links.push(Link {
                from: 0,
                to: output,
                weight: 1.0,
            });
            let sensor = c.brain.neurons.len();
            c.brain.neurons.push(Neuron {
                function: NeuronFunction::Linear,
                params: vec![],
                bias: 0.0,
                role: Role::Sensor {
                    sensor: Sensor::Angle { joint: 0, dof: d },
                },
                part: Some(1),
            });
            c.brain.links.push(Link {
                from: sensor,
                to: 0,
                weight: 0.1,
            });
        }
        let e = task::walker(&c, &SimOptions::default(), &short_walk(), false);
        assert_eq!(e.status, Status::Ok, "{kind:?}: {:?}", e.message);
        assert!(e.terms["D_w"].is_finite());
    }
}

/// A heavy 1 m cube with a 1 m cube hinged to its far end (revolute2 about z), driven by a
/// constant signal +1 read from environment slot 0.
fn lifter() -> Creature {
    use ontogeny::creature::{Actuator, Brain, Link, Neuron, NeuronFunction, Role, Sensor};
    let mut c = creature("width(1) thickness(1) forward(1) revolute2 forward(1)");
    c.parts[0].density = 100.0;
    c.parts[1].density = 2.0;
    c.environment = vec![1.0];
    let neuron = |role| Neuron {
        function: NeuronFunction::Linear,
        params: vec![],
        bias: 0.0,
        role,
        part: None,
    };
    c.brain = Brain {
        neurons: vec![
            neuron(Role::Sensor {
                sensor: Sensor::Chemical { slot: 0 },
            }),
            neuron(Role::Actuator {
                actuator: Actuator::Joint { joint: 0, dof: 0 },
            }),
        ],
        links: vec![Link {
            from: 0,
            to: 1,
            weight: 1.0,
        }],
    };
    c
}

#[test]
fn every_actuator_model_delivers_its_torque_against_gravity() {
    use ontogeny::sim::World;
    // The child weighs 2 kg: lifting it about the hinge takes about 9.8 N·m; the joint's
    // strength is 10⁴ N·m per m² × 1 m².
    for model in [
        ActuatorModel::Muscle,
        ActuatorModel::MuscleTorque,
        ActuatorModel::Velocity,
        ActuatorModel::Angle,
    ] {
        let sim = SimOptions {
            actuator: model,
            ..SimOptions::default()
        };
        let c = lifter();
        let mut world = World::new(&c, &sim).unwrap();
        let before = world.part_position(PartId(1));
        for _ in 0..240 {
            world.step(true).unwrap();
        }
        let after = world.part_position(PartId(1));
        assert!(
            after.y > before.y + 0.3,
            "{model:?}: the child should swing up, from {before:?} to {after:?}"
        );
    }
}

#[test]
fn both_muscles_give_the_signal_times_the_strength() {
    use ontogeny::sim::World;
    // The lifter's child (2 kg, its centre 0.5 m beyond the hinge) needs 2 × 9.81 × 0.5 =
    // 9.81 N·m to rise. A signal of 0.5 on a joint of 1 m² cross-section gives 0.5 × strength
    // N·m: 13 N·m at 26 N·m/m² lifts it, 8 N·m at 16 does not, for the motor and the torque.
    for model in [ActuatorModel::Muscle, ActuatorModel::MuscleTorque] {
        for (strength, lifts) in [(26.0, true), (16.0, false)] {
            let sim = SimOptions {
                actuator: model,
                strength,
                ..SimOptions::default()
            };
            let mut c = lifter();
            c.environment = vec![0.5];
            let mut world = World::new(&c, &sim).unwrap();
            let before = world.part_position(PartId(1));
            for _ in 0..240 {
                world.step(true).unwrap();
            }
            let risen = world.part_position(PartId(1)).y - before.y;
            assert_eq!(
                risen > 0.3,
                lifts,
                "{model:?} at {strength} N·m/m²: the child rose {risen} m"
            );
        }
    }
}

#[test]
fn a_second_joint_axis_is_the_second_degree_of_freedom() {
    use nalgebra::Vector3;
    use ontogeny::creature::{Actuator, JointKind, Role};
    use ontogeny::sim::World;
    // A universal joint driven on its second degree of freedom only. With the second axis
    // vertical (y) the child yaws on the ground; with it along the length (x) the child would
    // have to twist through the ground, and stays put.
    let run = |second: Vector3<f64>| {
        let mut c = lifter();
        c.joints[0].kind = JointKind::Universal;
        c.joints[0].axes = vec![Vector3::z(), second];
        let half_pi = std::f64::consts::FRAC_PI_2;
        c.joints[0].limits = vec![(-half_pi, half_pi); 2];
        c.brain.neurons[1].role = Role::Actuator {
            actuator: Actuator::Joint { joint: 0, dof: 1 },
        };
        // A gentle motor (50 N·m per m²), so that the yaw does not lift the root.
        let sim = SimOptions {
            actuator: ActuatorModel::Angle,
            strength: 50.0,
            ..SimOptions::default()
        };
        let mut world = World::new(&c, &sim).unwrap();
        for _ in 0..240 {
            world.step(true).unwrap();
        }
        let (_, orientation) = world.part_pose(PartId(1));
        orientation * Vector3::x()
    };
    let yawed = run(Vector3::y());
    assert!(
        yawed.z.abs() > 0.5,
        "about y the child turns sideways: {yawed:?}"
    );
    let twisted = run(Vector3::x());
    assert!(
        twisted.z.abs() < 0.1,
        "about x it does not turn sideways: {twisted:?}"
    );
}

#[test]
fn a_run_too_short_to_release_is_invalid_and_bad_durations_are_refused() {
    let c = grown("examples/thrower.lsys");
    let short = task::CatapultOptions {
        max_seconds: 0.2,
        ..task::CatapultOptions::default()
    };
    let e = task::catapult(&c, &SimOptions::default(), &short, false);
    assert_eq!(e.status, Status::Invalid);
    assert!(
        e.message
            .unwrap()
            .contains("before the projectile was released")
    );
    for seconds in [f64::INFINITY, -5.0, f64::NAN] {
        let options = WalkerOptions {
            seconds,
            ..WalkerOptions::default()
        };
        let e = task::walker(&c, &SimOptions::default(), &options, false);
        assert_eq!(e.status, Status::Invalid, "{seconds}");
    }
}

#[test]
fn the_projectile_starts_above_the_ground_even_on_a_thin_arm() {
    let c = creature("thickness(0.05) forward(1)");
    let e = task::catapult(
        &c,
        &SimOptions::default(),
        &task::CatapultOptions::default(),
        true,
    );
    let first = &e.recording[0];
    let projectile = first.projectile.unwrap();
    assert!(projectile.y - 0.1 > 0.0, "{projectile:?}");
}

#[test]
fn overlapping_parts_in_a_loaded_creature_are_caught() {
    let mut c = grown("examples/snake.lsys");
    c.parts[2].position = c.parts[0].position;
    c.parts[2].orientation = c.parts[0].orientation;
    c.problems.clear();
    let e = task::walker(&c, &SimOptions::default(), &short_walk(), false);
    assert_eq!(e.status, Status::SelfIntersecting, "{:?}", e.message);
    let mut zero = grown("examples/snake.lsys");
    zero.parts[0].orientation =
        nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0));
    assert!(zero.check_consistency().is_err());
}

/// The snake with part 1 (the first segment of its left limb) shrunk and moved inside the
/// root, as a hand-edited creature.json could have it; `anchor` places its joint.
fn snake_with_a_buried_part(anchor: impl Fn(&Creature) -> nalgebra::Vector3<f64>) -> Creature {
    let mut c = grown("examples/snake.lsys");
    let root = c.parts[0].clone();
    let joint = c.joints.iter().position(|j| j.child == 1).unwrap();
    assert_eq!(c.joints[joint].parent, 0);
    c.parts[1].size = nalgebra::Vector3::new(0.1, 0.1, 0.1);
    c.parts[1].position = root.position;
    c.parts[1].orientation = root.orientation;
    c.joints[joint].anchor = anchor(&c);
    c.problems.clear();
    assert_eq!(c.check_consistency(), Ok(()));
    c
}

#[test]
fn a_part_buried_in_the_root_is_self_intersecting() {
    // The joint anchor at the root's centre, inside it.
    let inside = snake_with_a_buried_part(|c| c.parts[0].position);
    // The joint anchor on the root's surface (the centre of its far end face), the part
    // inside, centred or with its near end at the anchor.
    let far_end = |c: &Creature| {
        let root = &c.parts[0];
        root.position + root.orientation * nalgebra::Vector3::new(root.size.x / 2.0, 0.0, 0.0)
    };
    let on_surface = snake_with_a_buried_part(far_end);
    let mut touching = on_surface.clone();
    touching.parts[1].position =
        far_end(&touching) - touching.parts[0].orientation * nalgebra::Vector3::new(0.05, 0.0, 0.0);
    for (name, c) in [
        ("anchor inside", inside),
        ("anchor on the surface", on_surface),
        ("near end at the anchor", touching),
    ] {
        assert!(c.interpenetrating_pairs().contains(&(0, 1)), "{name}");
        let e = task::walker(&c, &SimOptions::default(), &short_walk(), false);
        assert_eq!(
            e.status,
            Status::SelfIntersecting,
            "{name}: {:?}",
            e.message
        );
        assert_eq!(e.fitness, task::FAILURE_FITNESS);
        assert!(
            e.message
                .as_deref()
                .unwrap_or("")
                .contains("parts 0 and 1 interpenetrate"),
            "{name}: {:?}",
            e.message
        );
    }
}

#[test]
fn strength_follows_the_smaller_or_the_bigger_section() {
    use ontogeny::sim::{StrengthFrom, World};
    // A thin 2 kg child (0.1 m² section) on the 1 m² root: lifting it takes about 9.8 N·m.
    // Strength 20 N·m/m² gives 2 N·m from the smaller section, 20 N·m from the bigger.
    let mut c = lifter();
    c.parts[1].size = nalgebra::Vector3::new(1.0, 0.1, 1.0);
    c.parts[1].density = 20.0;
    let lift = |from| {
        let sim = SimOptions {
            strength_from: from,
            strength: 20.0,
            ..SimOptions::default()
        };
        let mut world = World::new(&c, &sim).unwrap();
        for _ in 0..240 {
            world.step(true).unwrap();
        }
        world.part_position(PartId(1)).y
    };
    assert!(lift(StrengthFrom::Bigger) > lift(StrengthFrom::Smaller) + 0.2);
}

#[test]
fn every_failure_ranks_below_every_success() {
    use ontogeny::task::FAILURE_FITNESS;
    // An aim far off: D_p − D_t is negative, but above the failure floor.
    let thrower = grown("examples/thrower.lsys");
    let far = task::CatapultOptions {
        target: Some(nalgebra::Vector3::new(50.0, 0.0, 0.0)),
        ..task::CatapultOptions::default()
    };
    let aim = task::catapult(&thrower, &SimOptions::default(), &far, false);
    assert_eq!(aim.status, Status::Ok, "{:?}", aim.message);
    assert!(aim.fitness < 0.0 && aim.fitness > FAILURE_FITNESS);
    // D_t is at most the target's distance from the start, so an aim score is at least
    // −|target| > −MAX_TARGET_DISTANCE > FAILURE_FITNESS.
    const { assert!(-task::MAX_TARGET_DISTANCE > FAILURE_FITNESS) };
    let beyond = task::CatapultOptions {
        target: Some(nalgebra::Vector3::new(
            2.0 * task::MAX_TARGET_DISTANCE,
            0.0,
            0.0,
        )),
        ..task::CatapultOptions::default()
    };
    let refused = task::catapult(&thrower, &SimOptions::default(), &beyond, false);
    assert_eq!(refused.status, Status::Invalid);
    // Every failed status scores the floor, and its JSON holds no NaN or infinity.
    let crossing = creature("forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)");
    let tall = creature("up(1) { forward(1) }(20)");
    for (c, status) in [
        (crossing, Status::SelfIntersecting),
        (tall, Status::TooTall),
        (creature("A"), Status::Invalid),
    ] {
        let e = task::walker(&c, &SimOptions::default(), &short_walk(), false);
        assert_eq!(e.status, status);
        assert_eq!(e.fitness, FAILURE_FITNESS);
        let json = serde_json::to_string(&e).unwrap();
        assert!(!json.contains("null") && !json.contains("NaN"), "{json}");
    }
}

#[test]
fn a_muscle_runs_at_saturation_its_torque_not_its_speed_limited() {
    use nalgebra::Vector3;
    use ontogeny::sim::{StrengthFrom, World};
    // A 1 m × 0.2 m × 0.2 m limb (40 kg) yawing about a vertical hinge on a root so dense
    // that it barely moves, without friction or gravity torque about the axis. Its moment of
    // inertia about the hinge is m (L² + w²) / 12 + m (L / 2)² = 13.4667 kg·m², the muscle's
    // torque 10⁴ N·m/m² × 0.04 m² = 400 N·m: the hinge accelerates at α = 29.70 rad/s².
    let mut c = lifter();
    c.parts[0].density = 1e7;
    c.parts[1].size = Vector3::new(1.0, 0.2, 0.2);
    c.parts[1].density = 1000.0;
    c.joints[0].axes = vec![Vector3::y()];
    let sim = SimOptions {
        strength_from: StrengthFrom::Smaller,
        friction: 0.0,
        ..SimOptions::default()
    };
    let alpha = 400.0 / (40.0 * (1.0 + 0.04) / 12.0 + 40.0 * 0.25);
    let mut world = World::new(&c, &sim).unwrap();
    // The sensor is read before the brain updates, so the torque acts from the first step.
    for k in 1..=15 {
        world.step(true).unwrap();
        let expected = alpha * k as f64 * sim.control_step;
        let speed = world.joint_speed(JointId(0)).abs();
        assert!(
            (speed - expected).abs() < 0.03 * expected,
            "step {k}: {speed} rad/s, a saturated muscle gives {expected}"
        );
    }
    // 7.4 rad/s: past the old 5 rad/s target speed, far below V_des.
    assert!(world.joint_speed(JointId(0)).abs() > 7.0);
    assert!(sim.muscle_speed > 10.0 * world.joint_speed(JointId(0)).abs());
}

#[test]
fn the_shipped_thrower_stays_torque_limited() {
    use ontogeny::sim::World;
    let c = grown("examples/thrower.lsys");
    let sim = SimOptions::default();
    let mut world = World::new(&c, &sim).unwrap();
    let mut fastest: f64 = 0.0;
    for _ in 0..180 {
        world.step(true).unwrap();
        fastest = fastest.max(world.joint_speed(JointId(0)).abs());
    }
    assert!(fastest > 1.0, "the arm swings: {fastest}");
    assert!(
        fastest < 0.5 * sim.muscle_speed,
        "the muscle never nears its target speed: {fastest} rad/s"
    );
}

#[test]
fn a_toppling_tower_is_not_at_rest_until_it_has_fallen() {
    // Balanced on a passive hinge, the upper half creeps over below Chaumont's speed
    // threshold; measuring must wait until it lies on the ground.
    let tower = creature("up(1) forward(2) revolute2 forward(2)");
    let e = task::walker(&tower, &SimOptions::default(), &short_walk(), false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    // Measured while falling it scored 0.73 m; once fallen, only the last settling of the
    // two halves on their passive hinge remains (7 cm at the fast setting, under 1 cm at the
    // default).
    assert!(e.terms["D_w"] < 0.1, "D_w = {}", e.terms["D_w"]);
    assert!(
        e.terms["measured_from"] > 2.0,
        "{}",
        e.terms["measured_from"]
    );
}

#[test]
fn iterative_move_weights_the_gains_of_each_second() {
    use ontogeny::task::iterative_move;
    let d = 3.0;
    // K = 20 seconds; weights 2k / (K + 1).
    let mut sprint = vec![0.0; 20];
    sprint[0] = d;
    assert!((iterative_move(&sprint) - 2.0 * d / 21.0).abs() < 1e-12);
    let steady = vec![d / 20.0; 20];
    assert!((iterative_move(&steady) - d).abs() < 1e-12);
    let mut late = vec![0.0; 20];
    late[19] = d;
    assert!((iterative_move(&late) - 40.0 * d / 21.0).abs() < 1e-12);
    // Continuous movement beats a sprint then a stop, as Walking with Dinosaurs intends.
    assert!(iterative_move(&steady) > 10.0 * iterative_move(&sprint));
}

#[test]
fn durations_are_seconds_at_any_time_step() {
    let sim = SimOptions {
        control_step: 1.0 / 120.0,
        ..SimOptions::default()
    };
    let options = task::CatapultOptions {
        max_seconds: 20.0,
        ..task::CatapultOptions::default()
    };
    let plain = creature("forward(1) revolute2 forward(1) output(1)");
    let e = task::catapult(&plain, &sim, &options, false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    assert_eq!(e.terms["release_step"], 60.0);
    assert!((e.terms["release_time"] - 0.5).abs() < 1e-12);
    let walk = task::walker(&grown("examples/snake.lsys"), &sim, &short_walk(), false);
    assert_eq!(walk.status, Status::Ok, "{:?}", walk.message);
    assert!(walk.terms["settled_at"] >= 0.5 - 1e-9);
    assert!(walk.terms["measured_from"] - walk.terms["settled_at"] >= 0.15 + 0.5 - 1e-9);
}

#[test]
fn the_projectile_is_measured_at_rest_or_the_run_is_unstable() {
    let c = grown("examples/thrower.lsys");
    let e = task::catapult(
        &c,
        &SimOptions::default(),
        &task::CatapultOptions::default(),
        true,
    );
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    // The last 0.5 s of the recording: the projectile does not move.
    let frames = &e.recording[e.recording.len() - 30..];
    let first = frames[0].projectile.unwrap();
    for f in frames {
        assert!((f.projectile.unwrap() - first).norm() < 0.01);
    }
    // Cut before it comes to rest: unstable, with the failure floor.
    let short = task::CatapultOptions {
        max_seconds: e.terms["release_time"] + 0.1,
        ..task::CatapultOptions::default()
    };
    let cut = task::catapult(&c, &SimOptions::default(), &short, false);
    assert_eq!(cut.status, Status::Unstable, "{:?}", cut.message);
    assert_eq!(cut.fitness, task::FAILURE_FITNESS);
}

#[test]
fn a_walker_that_never_comes_to_rest_scores_zero_where_scores_are_never_negative() {
    // Chaumont et al. 3.3: "Such individuals will never be considered stable, and no distance
    // will ever be recorded for them, so their fitness will be zero." A snake dropped from its
    // safe height cannot be at rest 0.2 s after it is let go (it is still falling).
    use ontogeny::task::{Fitness, Rest, WalkerFitness};
    let snake = grown("examples/snake.lsys");
    let restless = |fitness: &str| {
        let options = WalkerOptions {
            rest: Rest {
                limit: 0.2,
                ..Rest::default()
            },
            fitness: Fitness::new(fitness),
            ..short_walk()
        };
        task::walker(&snake, &SimOptions::default(), &options, false)
    };
    for formula in [
        WalkerFitness::Normalised,
        WalkerFitness::Distance,
        WalkerFitness::IterativeMove,
    ] {
        let e = restless(formula.name());
        assert_eq!(
            (e.status, e.fitness),
            (Status::Unstable, 0.0),
            "{formula:?}"
        );
        assert!(e.message.unwrap().contains("not at rest"));
    }
    // Where a valid score may be negative, 0 would rank it above creatures that walked: the
    // floor.
    for fitness in ["hornby-pollack", "D_w - 1"] {
        let e = restless(fitness);
        assert_eq!(
            (e.status, e.fitness),
            (Status::Unstable, task::FAILURE_FITNESS),
            "{fitness}"
        );
    }
    // The same creature given time to settle walks, status ok.
    let settled = task::walker(&snake, &SimOptions::default(), &short_walk(), false);
    assert_eq!(settled.status, Status::Ok, "{:?}", settled.message);
}

#[test]
fn the_height_test_applies_again_after_settling() {
    // A 3 m limb lying flat on a heavy cube, its hinge's limits [1.2, 1.5] rad: as built it
    // is 1 m tall, but the limit raises the limb to 1.2 rad (69°) as it settles.
    let mut c =
        creature("width(1) thickness(1) forward(1) revolute2 width(0.1) thickness(0.1) forward(3)");
    c.joints[0].limits = vec![(1.2, 1.5)];
    let (lo, hi) = c.bounding_box();
    assert!(hi.y - lo.y < 1.01);
    let options = WalkerOptions {
        max_height: 2.0,
        ..short_walk()
    };
    let e = task::walker(&c, &SimOptions::default(), &options, false);
    assert_eq!(e.status, Status::TooTall, "{:?}", e.message);
    assert!(e.message.unwrap().contains("after settling"));
}

#[test]
fn a_touch_sensor_on_one_face_senses_only_that_face() {
    use ontogeny::creature::{Face, Role, Sensor};
    use ontogeny::sim::World;
    // One part lying on the ground: its bottom face touches, its top face does not.
    let mut c = creature("forward(1) touch");
    let sensor = c
        .brain
        .neurons
        .iter()
        .position(|n| matches!(n.role, Role::Sensor { .. }))
        .unwrap();
    let read = |face: Option<Face>| {
        let mut c = c.clone();
        c.brain.neurons[sensor].role = Role::Sensor {
            sensor: Sensor::Touch { part: 0, face },
        };
        let mut world = World::new(&c, &SimOptions::default()).unwrap();
        for _ in 0..60 {
            world.step(true).unwrap();
        }
        world.sensor_reading(sensor)
    };
    assert_eq!(read(None), 1.0);
    assert_eq!(read(Some(Face::Bottom)), 1.0);
    assert_eq!(read(Some(Face::Top)), -1.0);
    assert_eq!(read(Some(Face::Front)), -1.0);
    c.brain.neurons[sensor].role = Role::Sensor {
        sensor: Sensor::Touch {
            part: 0,
            face: Some(Face::Left),
        },
    };
    let json = serde_json::to_string(&c.brain.neurons[sensor].role).unwrap();
    assert!(json.contains("\"face\":\"left\""), "{json}");
}

#[test]
fn the_rest_setting_steps_as_a_world_built_with_it_does() {
    // A world switched to its rest setting (2 substeps of 4 iterations by default) moves
    // exactly as a world built with that stepping, and switching back restores the walking
    // setting.
    use ontogeny::sim::World;
    let c = grown("examples/snake.lsys");
    let fast = SimOptions::default();
    assert_ne!(
        (fast.substeps, fast.solver_iterations, fast.pgs_iterations),
        (fast.rest_substeps, fast.rest_solver_iterations, 1),
        "the default rest setting differs from the walking one"
    );
    let steady = SimOptions {
        substeps: fast.rest_substeps,
        solver_iterations: fast.rest_solver_iterations,
        pgs_iterations: 1,
        ..fast.clone()
    };
    let run = |world: &mut World, steps: usize| {
        for _ in 0..steps {
            world.step(false).unwrap();
        }
        world
            .part_ids()
            .map(|id| world.part_position(id))
            .collect::<Vec<_>>()
    };
    let mut switched = World::new(&c, &fast).unwrap();
    switched.set_resting(true);
    let mut reference = World::new(&c, &steady).unwrap();
    assert_eq!(run(&mut switched, 40), run(&mut reference, 40));
    let mut fast_world = World::new(&c, &fast).unwrap();
    let mut steady_world = World::new(&c, &steady).unwrap();
    let (a, b) = (run(&mut fast_world, 40), run(&mut steady_world, 40));
    assert_ne!(a, b, "the two settings move the snake differently");
    // Switching to rest and back leaves the walking setting as it was.
    let falling = creature("forward(1)");
    let mut w = World::new(&falling, &fast).unwrap();
    w.set_resting(true);
    w.set_resting(false);
    let mut plain = World::new(&falling, &fast).unwrap();
    assert_eq!(run(&mut w, 10), run(&mut plain, 10));
}

/// The top of a part of edge lengths `size` (length, thickness, width) at `pose`: its centre's
/// height plus the half edges' reach upwards.
fn top(
    size: nalgebra::Vector3<f64>,
    pose: &(nalgebra::Vector3<f64>, nalgebra::UnitQuaternion<f64>),
) -> f64 {
    let (centre, rotation) = pose;
    let rotation = rotation.to_rotation_matrix();
    centre.y
        + (0..3)
            .map(|i| (rotation[(1, i)] * size[i] / 2.0).abs())
            .sum::<f64>()
}

#[test]
fn standing_scores_the_mean_height_of_the_highest_point_while_measured() {
    // Two parts on a hinge: the mean, over the measured steps, of the higher part's top.
    let c = creature("forward(1) revolute2 forward(1)");
    let spec = task::TaskSpec {
        task: task::TaskOptions::Stand(task::StandOptions {
            seconds: 0.5,
            ..task::StandOptions::default()
        }),
        ..task::TaskSpec::new(task::TaskKind::Stand)
    };
    let e = spec.evaluate(&c, true);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let sizes: Vec<_> = c.parts.iter().map(|p| p.size).collect();
    let measured: Vec<f64> = e
        .recording
        .iter()
        .filter(|s| s.phase == Some(task::Phase::Measuring))
        .map(|s| {
            s.parts
                .iter()
                .zip(&sizes)
                .map(|(pose, &size)| top(size, pose))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect();
    assert_eq!(measured.len(), 30);
    let by_hand = measured.iter().sum::<f64>() / 30.0;
    assert!(
        (e.fitness - by_hand).abs() < 1e-5,
        "{} by hand {by_hand}",
        e.fitness
    );
    assert_eq!(e.terms["height"], e.fitness);
    // Lying on the ground, the parts' 0.25 m thickness is the height.
    assert!((e.fitness - 0.25).abs() < 0.01, "{}", e.fitness);
    assert_eq!(spec.fitness_label(), "stand, mean height (m)");
    assert_eq!(spec.fitness_floor(), Some(0.0));
}
