//! `ontogeny export --format mjcf`: the exported model read back with dimforge's
//! `rapier3d-mjcf` and compared with the creature — bodies, poses, joints, limits, masses,
//! contacts, actuators and settings — plus the errors and the command line.

use crate::util::{assert_bad_input, grown, ontogeny, scratch_dir};

use nalgebra::{UnitQuaternion, Vector3};
use ontogeny::creature::{Actuator, Creature, JointKind, NeuronFunction, Role};
use ontogeny::develop::creature_from_commands;
use ontogeny::export::mjcf::z_up;
use ontogeny::export::{ExportError, mjcf_actuators, to_mjcf, to_mjcf_in};
use ontogeny::sim::{
    ANGLE_DAMPING, ANGLE_STIFFNESS, ActuatorModel, GRAVITY, SATURATION_DAMPING, SimOptions,
    StrengthFrom, max_torque,
};
use rapier3d::dynamics::JointAxis;
use rapier3d::math::Vector;
use rapier3d_mjcf::mjcf_rs::Model;
use rapier3d_mjcf::mjcf_rs::extras::ActuatorKind;
use rapier3d_mjcf::{MjcfLoaderOptions, MjcfRobot};

fn load(xml: &str) -> (MjcfRobot, Model) {
    MjcfRobot::from_str(xml, MjcfLoaderOptions::default(), ".")
        .unwrap_or_else(|e| panic!("rapier3d-mjcf cannot read the export: {e}\n{xml}"))
}

fn na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// Where the simulator puts part `i` (lifted to the drop height), in MuJoCo's Z-up world.
fn expected_pose(
    c: &Creature,
    options: &SimOptions,
    i: usize,
) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let lift = Vector3::new(0.0, options.drop_height - c.bounding_box().0.y, 0.0);
    let p = &c.parts[i];
    (z_up() * (p.position + lift), z_up() * p.orientation)
}

fn close(a: &Vector3<f64>, b: &Vector3<f64>, tolerance: f64) -> bool {
    (a - b).norm() <= tolerance
}

/// The simulator's joint frame axes in Ontogeny's world (x along the first axis, y along the
/// second made perpendicular, z = x × y), computed here independently of the exporter.
fn frame(axes: &[Vector3<f64>], dof: usize) -> Vec<Vector3<f64>> {
    if dof == 0 {
        return Vec::new();
    }
    let x = axes[0].normalize();
    let mut out = vec![x];
    if dof >= 2 {
        let y = (axes[1] - x * axes[1].dot(&x)).normalize();
        out.push(y);
        out.push(x.cross(&y));
    }
    out.truncate(dof);
    out
}

/// Checks everything the loader can see against the creature and the settings.
fn compare(c: &Creature, options: &SimOptions) -> (MjcfRobot, Model, String) {
    let xml = to_mjcf(c, options, "test").unwrap();
    let (robot, model) = load(&xml);

    // Bodies: one per part, not counting the loader's spacers between stacked hinges.
    let real: Vec<_> = robot
        .bodies
        .iter()
        .skip(1)
        .filter(|b| !b.is_intermediate)
        .collect();
    assert_eq!(real.len(), c.parts.len());
    for (i, part) in c.parts.iter().enumerate() {
        let b = &robot.bodies[robot.body_name_to_idx[&format!("part{i}")]];
        let relative = (b.mass as f64 - part.mass()).abs() / part.mass();
        assert!(
            relative < 1e-6,
            "part {i}: mass {} against {}",
            b.mass,
            part.mass()
        );
        let (position, orientation) = expected_pose(c, options, i);
        let pose = b.body.position();
        assert!(
            close(&na(pose.translation), &position, 1e-5),
            "part {i}: at {:?}, expected {position:?}",
            pose.translation
        );
        let q = pose.rotation;
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            q.w as f64, q.x as f64, q.y as f64, q.z as f64,
        ));
        assert!(q.angle_to(&orientation) < 1e-5, "part {i}: orientation");
        // Box geoms of half the edge lengths, with the part's density.
        let (id, _) = model.geom_by_name(&format!("part{i}")).unwrap();
        let geom = &model.bodies[id].body.geoms[0];
        assert_eq!(geom.type_, rapier3d_mjcf::mjcf_rs::body::GeomType::Box);
        let half = part.size / 2.0;
        assert_eq!(geom.size, [half.x, half.y, half.z]);
        assert_eq!(geom.density, Some(part.density));
        assert_eq!(geom.friction[0], options.friction);
    }
    // Only roots are free; every other part hangs from its parent part.
    for (i, _) in c.parts.iter().enumerate() {
        let id = model.body_id_by_name(&format!("part{i}")).unwrap();
        let entry = &model.bodies[id];
        let free = entry
            .body
            .joints
            .iter()
            .any(|j| j.type_ == rapier3d_mjcf::mjcf_rs::body::JointType::Free);
        match c.joints.iter().find(|j| j.child == i) {
            None => {
                assert!(free, "root part {i} has a free joint");
                assert_eq!(entry.parent, Some(0));
            }
            Some(joint) => {
                assert!(!free);
                let parent = model.body_id_by_name(&format!("part{}", joint.parent));
                assert_eq!(entry.parent, parent, "part {i} hangs from its parent part");
            }
        }
    }

    // Joints: a rigid joint welds (one fixed rapier joint), an n-DOF joint is n hinges.
    let hinges: usize = c.joints.iter().map(|j| j.kind.dof()).sum();
    let welds = c.joints.iter().filter(|j| j.kind.dof() == 0).count();
    assert_eq!(robot.joints.len(), hinges + welds);
    let lift = Vector3::new(0.0, options.drop_height - c.bounding_box().0.y, 0.0);
    for (j, joint) in c.joints.iter().enumerate() {
        let axes = frame(&joint.axes, joint.kind.dof());
        for (k, axis) in axes.iter().enumerate() {
            let index = robot.joint_name_to_idx[&format!("joint{j}_dof{k}")];
            let loaded = &robot.joints[index];
            let limits = loaded
                .joint
                .limits(JointAxis::AngX)
                .expect("a limited hinge");
            let (lo, hi) = joint.limits[k];
            assert!((limits.min as f64 - lo).abs() < 1e-6 && (limits.max as f64 - hi).abs() < 1e-6);
            // The hinge's axis and anchor in the world, from the child side of the joint.
            let body = robot.bodies[loaded.link2].body.position();
            let frame2 = body * loaded.joint.local_frame2;
            let world_axis = na(frame2.rotation * Vector::X);
            assert!(
                close(&world_axis, &(z_up() * axis), 1e-5),
                "joint {j} dof {k}: axis {world_axis:?}, expected {:?}",
                z_up() * axis
            );
            let anchor = z_up() * (joint.anchor + lift);
            assert!(
                close(&na(frame2.translation), &anchor, 1e-5),
                "joint {j} anchor"
            );
        }
        if joint.kind.dof() == 0 {
            let child = model
                .body_id_by_name(&format!("part{}", joint.child))
                .unwrap();
            assert!(
                model.bodies[child].body.joints.is_empty(),
                "a rigid joint welds"
            );
        }
    }

    // Contacts: excluded between the two parts of every joint, and MuJoCo's own parent
    // filter off, so that nothing else is excluded.
    let mut excluded: Vec<(String, String)> = robot
        .contact_excludes
        .iter()
        .map(|e| (e.body1.clone(), e.body2.clone()))
        .collect();
    let mut expected: Vec<(String, String)> = c
        .joints
        .iter()
        .map(|j| (format!("part{}", j.parent), format!("part{}", j.child)))
        .collect();
    excluded.sort();
    expected.sort();
    assert_eq!(excluded, expected);
    assert!(xml.contains("<flag filterparent=\"disable\"/>"));

    // Settings: the physics step, Z-up gravity.
    assert!((model.option.timestep - options.control_step / options.substeps as f64).abs() < 1e-15);
    assert_eq!(model.option.gravity, [0.0, 0.0, -GRAVITY]);
    assert!(xml.contains(&format!("iterations=\"{}\"", options.solver_iterations)));
    (robot, model, xml)
}

#[test]
fn the_shipped_examples_read_back_as_they_were_exported() {
    for (file, parts, hinges) in [
        ("examples/snake.lsys", 9, 8),
        ("examples/quadruped.lsys", 11, 8),
        ("examples/thrower.lsys", 2, 1),
    ] {
        let c = grown(file);
        assert_eq!(c.parts.len(), parts, "{file}");
        let options = SimOptions::default();
        let (robot, _, _) = compare(&c, &options);
        // Every movable joint of these creatures is driven by an output neuron.
        assert_eq!(robot.actuators.len(), hinges, "{file}");
    }
}

#[test]
fn quadruped_settings_follow_the_simulator_options() {
    let c = grown("examples/quadruped.lsys");
    let options = SimOptions {
        control_step: 0.01,
        substeps: 5,
        solver_iterations: 7,
        friction: 0.6,
        drop_height: 0.3,
        strength_from: StrengthFrom::Bigger,
        ..SimOptions::default()
    };
    let (_, model, xml) = compare(&c, &options);
    assert!((model.option.timestep - 0.002).abs() < 1e-15);
    assert!(xml.contains("<numeric name=\"ontogeny_control_step\" data=\"0.01\"/>"));
    assert!(xml.contains("<numeric name=\"ontogeny_substeps\" data=\"5\"/>"));
    assert!(xml.contains("iterations=\"7\""));
    // The ground has the parts' friction.
    let ground = model.geom_by_name("ground").unwrap();
    assert_eq!(model.bodies[ground.0].body.geoms[ground.1].friction[0], 0.6);
}

/// Two parts on a universal joint, then a third on a spherical joint, with axes that are not
/// perpendicular (the simulator makes the second perpendicular to the first).
fn multi_dof() -> Creature {
    let mut c = creature_from_commands(
        "width(0.3) thickness(0.2) forward(1) revolute2 forward(0.8) output(1) revolute2 forward(0.6) output(1)",
    )
    .unwrap();
    let tilted = Vector3::new(1.0, 1.0, 0.0).normalize();
    c.joints[0].kind = JointKind::Universal;
    c.joints[0].axes = vec![Vector3::z(), tilted];
    c.joints[0].limits = vec![(-0.5, 0.7), (-0.2, 0.3)];
    c.joints[1].kind = JointKind::Spherical;
    c.joints[1].axes = vec![Vector3::y(), tilted, Vector3::x()];
    c.joints[1].limits = vec![(-1.0, 1.0), (-0.4, 0.1), (0.0, 0.9)];
    // Drive the universal joint's second axis and the spherical joint's third too.
    let first = c.brain.neurons.len();
    for (joint, dof) in [(0, 1), (1, 2)] {
        c.brain.neurons.push(ontogeny::creature::Neuron {
            function: NeuronFunction::Linear,
            params: Vec::new(),
            bias: 0.0,
            role: Role::Actuator {
                actuator: Actuator::Joint { joint, dof },
            },
            part: None,
        });
    }
    c.brain.links.push(ontogeny::creature::Link {
        from: 0,
        to: first,
        weight: 1.0,
    });
    c.check_consistency().unwrap();
    c
}

#[test]
fn two_and_three_degree_joints_are_stacked_hinges_about_the_simulator_frame() {
    let c = multi_dof();
    let (robot, model, _) = compare(&c, &SimOptions::default());
    // 2 + 3 hinges; the loader adds a spacer body between stacked hinges (1 + 2).
    assert_eq!(robot.joints.len(), 5);
    assert_eq!(robot.bodies.iter().filter(|b| b.is_intermediate).count(), 3);
    // The hinges of one joint are declared in order in the child's body, at one anchor.
    let id = model.body_id_by_name("part2").unwrap();
    let names: Vec<_> = model.bodies[id]
        .body
        .joints
        .iter()
        .map(|j| j.name.clone().unwrap())
        .collect();
    assert_eq!(names, ["joint1_dof0", "joint1_dof1", "joint1_dof2"]);
    let anchors: Vec<_> = model.bodies[id].body.joints.iter().map(|j| j.pos).collect();
    assert!(anchors.iter().all(|a| a == &anchors[0]));
    // Both outputs of the turtle and both added neurons drive a hinge each.
    assert_eq!(robot.actuators.len(), 4);
    let driven: Vec<_> = mjcf_actuators(&c, &SimOptions::default())
        .iter()
        .map(|a| (a.joint, a.dof))
        .collect();
    assert_eq!(driven, [(0, 0), (0, 1), (1, 0), (1, 2)]);
}

#[test]
fn actuators_match_each_actuator_model() {
    let c = multi_dof();
    for model in [
        ActuatorModel::Muscle,
        ActuatorModel::MuscleTorque,
        ActuatorModel::Velocity,
        ActuatorModel::Angle,
    ] {
        let options = SimOptions {
            actuator: model,
            ..SimOptions::default()
        };
        let xml = to_mjcf(&c, &options, "test").unwrap();
        let (robot, _) = load(&xml);
        let listed = mjcf_actuators(&c, &options);
        assert_eq!(robot.actuators.len(), listed.len());
        for (loaded, a) in robot.actuators.iter().zip(&listed) {
            let loaded = &loaded.actuator;
            let joint = &c.joints[a.joint];
            // By hand: 50 N·m/m² × strength 1 × the smaller section, 0.2 × 0.3 m.
            let t = max_torque(&c, joint, &options);
            assert!((t - options.strength * 0.06).abs() < 1e-12);
            assert_eq!(a.max_torque, t);
            assert_eq!(loaded.joint.as_deref(), Some(a.name.as_str()));
            assert_eq!(loaded.force_range, Some([-t, t]));
            let (lo, hi) = joint.limits[a.dof];
            match model {
                ActuatorModel::Muscle | ActuatorModel::Velocity => {
                    assert_eq!(loaded.kind, ActuatorKind::Velocity);
                    assert_eq!(loaded.kv, Some(t * SATURATION_DAMPING));
                    let v = if model == ActuatorModel::Muscle {
                        options.muscle_speed
                    } else {
                        options.max_speed
                    };
                    assert_eq!(loaded.ctrl_range, Some([-v, v]));
                }
                ActuatorModel::MuscleTorque => {
                    // A torque of s × t: MuJoCo's motor with gear t and s in [-1, 1].
                    assert_eq!(loaded.kind, ActuatorKind::Motor);
                    assert_eq!(loaded.gear[0], t);
                    assert_eq!(loaded.ctrl_range, Some([-1.0, 1.0]));
                }
                ActuatorModel::Angle => {
                    assert_eq!(loaded.kind, ActuatorKind::Position);
                    assert_eq!(loaded.kp, Some(t * ANGLE_STIFFNESS));
                    assert_eq!(loaded.ctrl_range, Some([lo, hi]));
                    assert!(xml.contains(&format!("kv=\"{}\"", t * ANGLE_DAMPING)));
                }
            }
        }
        let name = match model {
            ActuatorModel::Muscle => "muscle",
            ActuatorModel::MuscleTorque => "muscle-torque",
            ActuatorModel::Velocity => "velocity",
            ActuatorModel::Angle => "angle",
        };
        assert!(xml.contains(&format!(
            "<text name=\"ontogeny_actuator_model\" data=\"{name}\"/>"
        )));
    }
}

#[test]
fn the_last_neuron_driving_a_hinge_is_the_one_listed() {
    let mut c = creature_from_commands("forward(1) revolute2 forward(1) output(1)").unwrap();
    // A second output on the same hinge, added by hand (the turtle makes one per hinge).
    let first = c
        .brain
        .neurons
        .iter()
        .position(|n| matches!(n.role, Role::Actuator { .. }))
        .unwrap();
    let second = c.brain.neurons[first].clone();
    c.brain.neurons.push(second);
    c.check_consistency().unwrap();
    let drivers: Vec<usize> = c
        .brain
        .neurons
        .iter()
        .enumerate()
        .filter(|(_, n)| matches!(n.role, Role::Actuator { .. }))
        .map(|(i, _)| i)
        .collect();
    assert_eq!(drivers.len(), 2, "two outputs on one hinge");
    let options = SimOptions::default();
    let listed = mjcf_actuators(&c, &options);
    assert_eq!(listed.len(), 1);
    assert_eq!(listed[0].neuron, drivers[1]);
    let xml = to_mjcf(&c, &options, "t").unwrap();
    assert!(xml.contains(&format!(
        "<numeric name=\"ontogeny_actuator_neurons\" data=\"{}\"/>",
        drivers[1]
    )));
    // A joint of no strength gets no actuator.
    c.joints[0].strength = 0.0;
    assert!(mjcf_actuators(&c, &options).is_empty());
    assert!(!to_mjcf(&c, &options, "t").unwrap().contains("<actuator>"));
}

#[test]
fn the_lowest_point_starts_at_the_drop_height_above_a_z_up_ground() {
    let c = grown("examples/snake.lsys");
    let options = SimOptions {
        drop_height: 0.25,
        ..SimOptions::default()
    };
    let (robot, _) = load(&to_mjcf(&c, &options, "snake").unwrap());
    let mut lowest = f64::INFINITY;
    for b in robot.bodies.iter().skip(1) {
        for collider in &b.colliders {
            let half = collider.shape().as_cuboid().unwrap().half_extents;
            let pose = b.body.position();
            for corner in 0..8 {
                let local = Vector::new(
                    if corner & 1 == 0 { -half.x } else { half.x },
                    if corner & 2 == 0 { -half.y } else { half.y },
                    if corner & 4 == 0 { -half.z } else { half.z },
                );
                // The geom's pose in its body (the identity here) before the body's.
                let world = *pose * *collider.position() * local;
                lowest = lowest.min(world.z as f64);
            }
        }
    }
    assert!((lowest - 0.25).abs() < 1e-5, "lowest point at z = {lowest}");
}

#[test]
fn without_self_collision_parts_touch_the_ground_only() {
    let c = grown("examples/snake.lsys");
    for (self_collision, affinity) in [(true, 1), (false, 0)] {
        let options = SimOptions {
            self_collision,
            ..SimOptions::default()
        };
        let (_, model) = load(&to_mjcf(&c, &options, "snake").unwrap());
        for i in 0..c.parts.len() {
            let (id, g) = model.geom_by_name(&format!("part{i}")).unwrap();
            let geom = &model.bodies[id].body.geoms[g];
            assert_eq!((geom.contype, geom.conaffinity), (1, affinity));
        }
        let (id, g) = model.geom_by_name("ground").unwrap();
        let ground = &model.bodies[id].body.geoms[g];
        assert_eq!((ground.contype, ground.conaffinity), (1, 1));
    }
}

#[test]
fn a_part_joined_to_nothing_is_a_second_free_body() {
    let mut c = creature_from_commands("forward(1) revolute2 forward(1)").unwrap();
    let mut loose = c.parts[1].clone();
    loose.position += Vector3::new(0.0, 0.0, 2.0);
    c.parts.push(loose);
    let (robot, model, _) = compare(&c, &SimOptions::default());
    assert_eq!(robot.joints.len(), 1);
    let id = model.body_id_by_name("part2").unwrap();
    assert_eq!(model.bodies[id].parent, Some(0));
}

#[test]
fn loops_and_bad_creatures_are_errors() {
    let options = SimOptions::default();
    // A third joint makes part 2 the child of parts 0 and 1.
    let mut c =
        creature_from_commands("forward(1) [ revolute2 forward(1) ] left(1) revolute2 forward(1)")
            .unwrap();
    assert_eq!(c.joints.len(), 2);
    let mut extra = c.joints[1].clone();
    extra.parent = 1;
    extra.child = 2;
    c.joints.push(extra);
    let e = to_mjcf(&c, &options, "t").unwrap_err();
    assert!(
        matches!(
            e,
            ExportError::SecondParent {
                joint: 2,
                part: 2,
                first: 1
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("loop"));

    // Parts 1 and 2 hold each other, and nothing holds them.
    let mut c = creature_from_commands("forward(1) revolute2 forward(1)").unwrap();
    c.parts.push(c.parts[1].clone());
    c.parts[2].position.z += 2.0;
    let mut a = c.joints[0].clone();
    a.parent = 1;
    a.child = 2;
    let mut b = c.joints[0].clone();
    b.parent = 2;
    b.child = 1;
    c.joints = vec![a, b];
    c.brain = Default::default();
    let e = to_mjcf(&c, &options, "t").unwrap_err();
    assert!(matches!(e, ExportError::Ring { part: 1 }), "{e}");

    // Equal limits have no MJCF range.
    let mut c = creature_from_commands("forward(1) revolute2 forward(1)").unwrap();
    c.joints[0].limits[0] = (0.3, 0.3);
    let e = to_mjcf(&c, &options, "t").unwrap_err();
    assert!(
        matches!(e, ExportError::EqualLimits { joint: 0, dof: 0 }),
        "{e}"
    );

    assert!(matches!(
        to_mjcf(&Creature::default(), &options, "t"),
        Err(ExportError::NoParts)
    ));
    let mut c = creature_from_commands("forward(1)").unwrap();
    c.parts[0].size.x = -1.0;
    assert!(matches!(
        to_mjcf(&c, &options, "t"),
        Err(ExportError::Malformed(_))
    ));
    let bad = SimOptions {
        control_step: 0.0,
        ..SimOptions::default()
    };
    let c = creature_from_commands("forward(1)").unwrap();
    assert!(matches!(
        to_mjcf(&c, &bad, "t"),
        Err(ExportError::Settings(_))
    ));
}

#[test]
fn the_model_name_is_escaped() {
    let c = creature_from_commands("forward(1)").unwrap();
    let xml = to_mjcf(&c, &SimOptions::default(), "a<b>&\"c\"").unwrap();
    let (robot, _) = load(&xml);
    assert_eq!(robot.name.as_deref(), Some("a<b>&\"c\""));
}

#[test]
fn the_command_writes_to_standard_output_or_a_file() {
    let out = ontogeny(&["export", "examples/thrower.lsys", "--format", "mjcf"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let printed = String::from_utf8(out.stdout).unwrap();
    let expected = to_mjcf(
        &grown("examples/thrower.lsys"),
        &SimOptions::default(),
        "thrower",
    )
    .unwrap();
    assert_eq!(printed, expected);

    let dir = scratch_dir("export-thrower");
    let path = dir.join("thrower.xml");
    let out = ontogeny(&[
        "export",
        "examples/thrower.lsys",
        "--out",
        path.to_str().unwrap(),
        "--actuator",
        "angle",
        "--time-step",
        "0.01",
        "--substeps",
        "4",
        "--solver-iterations",
        "9",
        "--strength-from",
        "bigger",
        "--no-self-collision",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout.is_empty());
    let written = std::fs::read_to_string(&path).unwrap();
    let options = SimOptions {
        actuator: ActuatorModel::Angle,
        control_step: 0.01,
        substeps: 4,
        solver_iterations: 9,
        strength_from: StrengthFrom::Bigger,
        self_collision: false,
        ..SimOptions::default()
    };
    let expected = to_mjcf(&grown("examples/thrower.lsys"), &options, "thrower").unwrap();
    assert_eq!(written, expected);
}

#[test]
fn the_command_reads_a_creature_json() {
    let c = grown("examples/quadruped.lsys");
    let dir = scratch_dir("export-json");
    let path = dir.join("creature.json");
    std::fs::write(&path, serde_json::to_string(&c).unwrap()).unwrap();
    let out = ontogeny(&["export", path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        to_mjcf(&c, &SimOptions::default(), "creature").unwrap()
    );
}

#[test]
fn bad_input_exits_2_with_a_message() {
    let dir = scratch_dir("export-bad");
    let garbage = dir.join("garbage.json");
    std::fs::write(&garbage, "{\"parts\": 3}").unwrap();
    let mut looped = creature_from_commands("forward(1) revolute2 forward(1)").unwrap();
    let mut extra = looped.joints[0].clone();
    extra.parent = 1;
    extra.child = 0;
    looped.joints.push(extra);
    let looped_path = dir.join("loop.json");
    std::fs::write(&looped_path, serde_json::to_string(&looped).unwrap()).unwrap();
    let missing = dir.join("missing.lsys");
    for (args, says) in [
        (vec![missing.to_str().unwrap()], "missing.lsys"),
        (vec![garbage.to_str().unwrap()], "not a creature"),
        (vec![looped_path.to_str().unwrap()], "cannot export"),
        (vec!["examples/snake.lsys", "--format", "urdf"], "urdf"),
        (
            vec!["examples/snake.lsys", "--time-step", "0"],
            "--time-step",
        ),
        (
            vec!["examples/snake.lsys", "--out", "/nonexistent/dir/x.xml"],
            "cannot write",
        ),
    ] {
        let mut all = vec!["export"];
        all.extend(args.iter().copied());
        assert_bad_input(&all, says);
    }
}

#[test]
fn export_takes_a_named_step_setting_and_explicit_flags_over_it() {
    let out = ontogeny(&["export", "examples/snake.lsys", "--setting", "fast"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let expected = to_mjcf(
        &grown("examples/snake.lsys"),
        &SimOptions::default().fast(),
        "snake",
    )
    .unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
    let out = ontogeny(&[
        "export",
        "examples/snake.lsys",
        "--setting",
        "fine",
        "--solver-iterations",
        "5",
    ]);
    assert!(out.status.success());
    let options = SimOptions {
        solver_iterations: 5,
        ..SimOptions::default().fine_reference()
    };
    let expected = to_mjcf(&grown("examples/snake.lsys"), &options, "snake").unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
}

/// The exported worldbody geom `name` of `model`: its centre and its local z axis, in
/// MuJoCo's axes.
fn world_geom<'a>(
    model: &'a Model,
    name: &str,
) -> (
    &'a rapier3d_mjcf::mjcf_rs::body::Geom,
    Vector3<f64>,
    Vector3<f64>,
) {
    let (body, index) = model
        .geom_by_name(name)
        .unwrap_or_else(|| panic!("no geom {name}"));
    assert_eq!(body, 0, "{name} is on the worldbody");
    let g = &model.bodies[0].body.geoms[index];
    let t = g.pose.translation;
    let r = g.pose.rotation;
    let turn = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(r.w, r.x, r.y, r.z));
    (g, Vector3::new(t.x, t.y, t.z), turn * Vector3::z())
}

fn world(text: &str) -> ontogeny::sim::WorldSpec {
    let world: ontogeny::sim::WorldSpec = toml::from_str(text).unwrap();
    world.check().unwrap();
    world
}

#[test]
fn a_slope_is_exported_as_the_ground_plane_tilted_to_its_normal() {
    let c = creature_from_commands("forward(1)").unwrap();
    let xml = to_mjcf_in(
        &c,
        &SimOptions::default(),
        "slope",
        &world("slope = { degrees = 30, direction = 0 }"),
    )
    .unwrap();
    let (_, model) = load(&xml);
    let (plane, centre, up) = world_geom(&model, "ground");
    assert_eq!(
        plane.type_,
        rapier3d_mjcf::mjcf_rs::body::GeomType::Plane,
        "{xml}"
    );
    assert!(close(&centre, &Vector3::zeros(), 1e-12));
    // Uphill along +x: the normal leans back towards -x; Ontogeny's y is MuJoCo's z.
    assert!(
        close(&up, &Vector3::new(-0.5, 0.0, 0.75f64.sqrt()), 1e-9),
        "{up:?}"
    );
}

#[test]
fn steps_obstacles_and_objects_are_exported_as_boxes_and_free_bodies() {
    let c = creature_from_commands("forward(1)").unwrap();
    let xml = to_mjcf_in(
        &c,
        &SimOptions::default(),
        "steps",
        &world(
            "steps = { height = 0.1, depth = 0.5, count = 3, start = 1, direction = 0 }\n\
             obstacles = { size = [0.2, 0.3, 0.4], at = [[-2, 1]] }\n\
             objects = [{ shape = \"ball\", size = 0.1, mass = 2, position = [0, 0.5, -2] },\n\
                        { shape = \"box\", size = 0.2, mass = 1, position = [-2, 0.3, -2] }]",
        ),
    )
    .unwrap();
    let (robot, model) = load(&xml);
    // Three steps and the obstacle on the worldbody (the plane under them is not loaded
    // by rapier3d-mjcf), each a box.
    assert_eq!(robot.bodies[0].colliders.len(), 4, "{xml}");
    let (step, centre, normal) = world_geom(&model, "step0");
    assert_eq!(step.type_, rapier3d_mjcf::mjcf_rs::body::GeomType::Box);
    assert_eq!(step.size, [0.25, 0.55, 500.0]);
    assert!(
        close(&centre, &Vector3::new(1.25, 0.0, -0.45), 1e-12),
        "{centre:?}"
    );
    // The box's own z is Ontogeny's z, MuJoCo's -y: its height (size's y) is MuJoCo's z.
    assert!(close(&normal, &-Vector3::y(), 1e-12), "{normal:?}");
    let (top, centre, _) = world_geom(&model, "step2");
    assert_eq!(top.size[0], 250.0 - 1.0);
    assert!((centre.z - (0.3 - 1.0) / 2.0).abs() < 1e-12);
    let (obstacle, centre, _) = world_geom(&model, "obstacle0");
    assert_eq!(obstacle.size, [0.1, 0.15, 0.2]);
    // At x = -2, z = 1 (MuJoCo's y = -1), on level ground.
    assert!(
        close(&centre, &Vector3::new(-2.0, -1.0, 0.15), 1e-12),
        "{centre:?}"
    );
    for (name, kind, size, mass, at) in [
        (
            "object0",
            rapier3d_mjcf::mjcf_rs::body::GeomType::Sphere,
            0.1,
            2.0,
            [0.0, 2.0, 0.5],
        ),
        (
            "object1",
            rapier3d_mjcf::mjcf_rs::body::GeomType::Box,
            0.1,
            1.0,
            [-2.0, 2.0, 0.3],
        ),
    ] {
        let body = model.body_id_by_name(name).unwrap();
        let entry = &model.bodies[body];
        assert_eq!(entry.parent, Some(0), "{name} is a free body of the world");
        assert_eq!(entry.body.joints.len(), 1, "{name}'s freejoint");
        let t = entry.body.pose.translation;
        assert!(close(
            &Vector3::new(t.x, t.y, t.z),
            &Vector3::from(at),
            1e-12
        ));
        let geom = &entry.body.geoms[0];
        assert_eq!(
            (geom.type_, geom.size[0], geom.mass),
            (kind, size, Some(mass))
        );
    }
}

#[test]
fn rough_ground_is_exported_as_a_heightfield_of_its_samples_and_water_as_options() {
    let c = creature_from_commands("forward(1)").unwrap();
    let spec = world("rough = { amplitude = 0.1, wavelength = 1, seed = 5, size = 4 }");
    let xml = to_mjcf_in(&c, &SimOptions::default(), "rough", &spec).unwrap();
    let (robot, model) = load(&xml);
    let field = ontogeny::sim::terrain::Terrain::new(&spec)
        .heightfield()
        .unwrap()
        .clone();
    let (lo, hi) = field
        .heights
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| {
            (a.min(h), b.max(h))
        });
    let asset = model.assets.hfield("rough").unwrap();
    let n = field.samples;
    assert_eq!((asset.nrow as usize, asset.ncol as usize), (n, n));
    assert_eq!(asset.size, [2.0, 2.0, hi - lo, 1.0]);
    // MuJoCo's first row is at -y, Ontogeny's last row (+z); heights normalised to [0, 1].
    let elevation = asset.elevation.as_ref().unwrap();
    for (row, column) in [(0, 0), (0, n - 1), (n / 3, n / 2), (n - 1, 1)] {
        let written = elevation[(n - 1 - row) * n + column];
        let expected = (field.heights[row * n + column] - lo) / (hi - lo);
        assert!(
            (written - expected).abs() < 1e-9,
            "row {row}, column {column}"
        );
    }
    let (ground, centre, _) = world_geom(&model, "ground");
    assert_eq!(ground.hfield.as_deref(), Some("rough"));
    assert!((centre.z - lo).abs() < 1e-12);
    // The heightfield and the four level slabs round it are loaded as colliders.
    assert_eq!(robot.bodies[0].colliders.len(), 5, "{xml}");

    let water = world("medium = { kind = \"water\", viscosity = 5 }");
    let xml = to_mjcf_in(&c, &SimOptions::default(), "water", &water).unwrap();
    let (_, model) = load(&xml);
    assert_eq!(model.option.gravity, [0.0, 0.0, 0.0]);
    assert!(xml.contains("density=\"1000\" viscosity=\"5\""), "{xml}");
    assert!(xml.contains("not Ontogeny's resistance"), "{xml}");
    assert!(
        model.geom_by_name("ground").is_none(),
        "water has no ground"
    );
}

#[test]
fn export_takes_the_world_of_a_configuration() {
    let dir = scratch_dir("export-world");
    let config = dir.join("world.toml");
    std::fs::write(
        &config,
        "[task.world]\nobstacles = { size = [0.2, 0.2, 0.2], at = [[2, 0]] }\n",
    )
    .unwrap();
    let out = dir.join("model.xml");
    let output = ontogeny(&[
        "export",
        "examples/quadruped.lsys",
        "--world",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    let xml = std::fs::read_to_string(&out).unwrap();
    assert_eq!(xml.matches("<geom name=\"obstacle").count(), 1, "{xml}");
    std::fs::write(&config, "[task.world]\nslope = { degrees = 95 }\n").unwrap();
    let said = assert_bad_input(
        &[
            "export",
            "examples/quadruped.lsys",
            "--world",
            config.to_str().unwrap(),
        ],
        "[task.world]",
    );
    assert!(said.contains("world.toml"), "{said}");
}
