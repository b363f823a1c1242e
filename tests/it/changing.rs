//! A creature that changes while it acts: parts and joints added to a running world, a part
//! resized, neurons and links added to a running brain, and development stepped by any Δt.

use std::sync::Arc;

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use ontogeny::creature::Creature;
use ontogeny::creature::{
    Brain, Joint, JointId, JointKind, Link, Neuron, NeuronFunction, Part, PartId, Role, Sensor,
};
use ontogeny::develop::{Growth, GrowthEvent, creature_from_commands};
use ontogeny::lsystem::{DeriveOptions, Development, LSystem, ModuleString};
use ontogeny::sim::{Attach, BrainRuntime, SimOptions, World};

/// A 1 m × 0.25 m × 0.25 m box (62.5 kg at 1000 kg/m³) settled on the ground.
fn settled_root() -> World {
    let creature = creature_from_commands("forward(1)").unwrap();
    let mut world = World::new(&creature, &SimOptions::default()).unwrap();
    for _ in 0..60 {
        world.step(false).unwrap();
    }
    world
}

/// `mass` is `expected` kg, to rapier's single precision.
fn assert_kg(mass: f64, expected: f64) {
    assert!(
        (mass - expected).abs() < 1e-6 * expected,
        "{mass} kg, not {expected}"
    );
}

/// A point `local` in part `id`'s axes, in the world.
fn on_part(world: &World, id: PartId, local: Vector3<f64>) -> Vector3<f64> {
    let (centre, orientation) = world.part_pose(id);
    centre + orientation * local
}

/// Adds to `world`'s root a 0.5 m tail (31.25 kg) beyond its +x end, held as `attach` says,
/// joined at the root's end face by a hinge about the root's z axis.
fn add_tail(world: &mut World, attach: Attach) -> (PartId, JointId) {
    let (_, orientation): (_, UnitQuaternion<f64>) = world.part_pose(PartId(0));
    let tail = Part {
        size: Vector3::new(0.5, 0.25, 0.25),
        position: on_part(world, PartId(0), Vector3::new(0.75, 0.0, 0.0)),
        orientation,
        density: 1000.0,
        growing: false,
    };
    let part = world.add_part(&tail, attach);
    let hinge = Joint {
        parent: 0,
        child: part.0,
        kind: JointKind::Revolute,
        anchor: on_part(world, PartId(0), Vector3::new(0.5, 0.0, 0.0)),
        axes: vec![orientation * Vector3::z()],
        limits: vec![(-0.5, 0.5)],
        strength: 1.0,
        growing: false,
    };
    let joint = world.add_joint(&hinge).unwrap();
    (part, joint)
}

#[test]
fn a_part_and_a_joint_added_mid_simulation_add_their_mass_keep_the_momentum_and_hold() {
    let mut world = settled_root();
    let momentum = world.creature_momentum();
    assert_kg(world.creature_mass(), 62.5);

    let (part, joint) = add_tail(&mut world, Attach::Free);
    // The next ids, after the builder's.
    assert_eq!((part, joint), (PartId(1), JointId(0)));
    assert_eq!(world.part_count(), 2);
    assert_eq!(world.joint_count(), 1);
    assert_eq!(world.part_ids().collect::<Vec<_>>(), [PartId(0), PartId(1)]);
    assert_kg(world.creature_mass(), 62.5 + 31.25);
    // Added at rest: the creature's momentum is what it was.
    assert_eq!(world.creature_momentum(), momentum);

    for _ in 0..60 {
        world.step(false).unwrap();
    }
    // The hinge holds the tail at the root's end: its two anchors together, the centres
    // 0.75 m apart.
    let (parent_side, child_side) = world.joint_anchors(joint).unwrap();
    let gap = (parent_side - child_side).norm();
    assert!(gap < 1e-3, "the joint's anchors are {gap} m apart");
    let apart = (world.part_position(part) - world.part_position(PartId(0))).norm();
    assert!(
        (apart - 0.75).abs() < 0.01,
        "the centres are {apart} m apart"
    );
    // The tail's own energy (31.25 kg at 0.125 m: 38 J) is not energy from nowhere.
    let unexplained = world.peak_unexplained_energy();
    assert!(unexplained < 0.01, "{unexplained} J from nowhere");

    // A sensor added now can name the part that appeared: the tail lies on the ground.
    let neurons = world.brain().neuron_count();
    let touch = world.add_neuron(&Neuron {
        function: NeuronFunction::Linear,
        params: Vec::new(),
        bias: 0.0,
        role: Role::Sensor {
            sensor: Sensor::Touch {
                part: part.0,
                face: None,
            },
        },
        part: Some(part.0),
    });
    assert_eq!(touch, neurons);
    world.step(true).unwrap();
    assert_eq!(world.sensor_reading(touch), 1.0);
}

#[test]
fn a_joint_naming_a_part_the_world_lacks_is_refused() {
    let mut world = settled_root();
    let joint = Joint {
        parent: 0,
        child: 3,
        kind: JointKind::Revolute,
        anchor: Vector3::zeros(),
        axes: vec![Vector3::z()],
        limits: vec![(-0.5, 0.5)],
        strength: 1.0,
        growing: false,
    };
    let error = world.add_joint(&joint).unwrap_err();
    assert_eq!(
        error.to_string(),
        "malformed creature: joint 0 joins part 0 to part 3, but the world has 1 parts"
    );
    assert_eq!(world.joint_count(), 0);
}

#[test]
fn a_resized_part_has_the_mass_inertia_and_joint_anchors_of_its_new_size() {
    let mut world = settled_root();
    let (tail, joint) = add_tail(&mut world, Attach::Free);
    let (parent_side, _) = world.joint_anchors(joint).unwrap();

    // The tail doubles in length, about its centre: 0.5 m → 1 m, 31.25 kg → 62.5 kg.
    world.resize_part(tail, Vector3::new(1.0, 0.25, 0.25));
    assert_eq!(world.part_size(tail), Vector3::new(1.0, 0.25, 0.25));
    let (mass, inertia) = world.part_body_mass(tail);
    assert_kg(mass, 62.5);
    // A box's principal moments: m/12 · (b² + c²) about each axis.
    let by_hand = [
        62.5 / 12.0 * (0.25f64.powi(2) + 0.25f64.powi(2)),
        62.5 / 12.0 * (1.0 + 0.25f64.powi(2)),
        62.5 / 12.0 * (1.0 + 0.25f64.powi(2)),
    ];
    for (axis, expected) in by_hand.iter().enumerate() {
        assert!(
            (inertia[axis] - expected).abs() < 1e-5 * expected,
            "inertia about axis {axis}: {} kg·m², not {expected}",
            inertia[axis]
        );
    }
    assert_kg(world.creature_mass(), 62.5 + 62.5);
    // The anchor on the tail moved with its near face, from 0.25 m to 0.5 m behind its
    // centre; the root's anchor stayed.
    let (parent_now, child_now) = world.joint_anchors(joint).unwrap();
    assert!((parent_now - parent_side).norm() < 1e-6);
    let face = on_part(&world, tail, Vector3::new(-0.5, 0.0, 0.0));
    let off = (child_now - face).norm();
    assert!(
        off < 1e-5,
        "the tail's anchor is {off} m from its near face"
    );
}

/// The 1 m root of `settled_root`, 5 m up in the air, pushed to move at 1.0, 0.5, −0.25 m/s
/// while it turns at 0.3, −0.2, 2.0 rad/s, and flown for two control steps.
fn flying_root() -> World {
    let sim = SimOptions {
        drop_height: 5.0,
        ..SimOptions::default()
    };
    let mut world = World::new(&creature_from_commands("forward(1)").unwrap(), &sim).unwrap();
    world.set_part_velocity(
        PartId(0),
        Vector3::new(1.0, 0.5, -0.25),
        Vector3::new(0.3, -0.2, 2.0),
    );
    for _ in 0..2 {
        world.step(false).unwrap();
    }
    world
}

/// `actual` is `expected` to within `tolerance` (each coordinate).
fn assert_near(actual: Vector3<f64>, expected: Vector3<f64>, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).amax() < tolerance,
        "{what}: {actual:?}, not {expected:?}"
    );
}

/// A box's inertia in the world (kg·m²): m/12 · (b² + c², …) in its own axes, turned by
/// `orientation`.
fn box_inertia(mass: f64, size: Vector3<f64>, orientation: UnitQuaternion<f64>) -> Matrix3<f64> {
    let s = size.component_mul(&size);
    let own = Matrix3::from_diagonal(&Vector3::new(s.y + s.z, s.x + s.z, s.x + s.y)) * mass / 12.0;
    let r = orientation.to_rotation_matrix();
    r.matrix() * own * r.matrix().transpose()
}

/// The root's motion and the creature's momenta before a tail joins it.
struct RootMotion {
    /// The root's velocity (m/s) and angular velocity (rad/s).
    v: Vector3<f64>,
    w: Vector3<f64>,
    /// The root's centre and orientation.
    root: Vector3<f64>,
    orientation: UnitQuaternion<f64>,
    /// The creature's linear and angular momentum.
    momentum: Vector3<f64>,
    angular: Vector3<f64>,
}

impl RootMotion {
    fn of(world: &World) -> RootMotion {
        let (v, w) = world.part_velocity(PartId(0));
        let (root, orientation) = world.part_pose(PartId(0));
        RootMotion {
            v,
            w,
            root,
            orientation,
            momentum: world.creature_momentum(),
            angular: world.creature_angular_momentum(),
        }
    }

    /// The 0.5 m tail (31.25 kg) `tail` is 0.75 m along the root's x axis from its centre,
    /// moves as the root's material point there would (v + ω × r, turning at ω), and the
    /// creature's momentum rose by the tail's: 31.25 kg × that velocity; its angular momentum
    /// about the origin by m c × v + I ω.
    fn assert_tail_arrived(&self, world: &World, tail: PartId) {
        let centre = self.root + self.orientation * Vector3::new(0.75, 0.0, 0.0);
        assert_near(world.part_position(tail), centre, 1e-5, "the tail's centre");
        let arrives = self.v + self.w.cross(&(centre - self.root));
        let (tail_v, tail_w) = world.part_velocity(tail);
        assert_near(tail_v, arrives, 1e-5, "the tail's velocity");
        assert_near(tail_w, self.w, 1e-6, "the tail's angular velocity");
        assert_near(
            world.creature_momentum() - self.momentum,
            arrives * 31.25,
            1e-3,
            "the momentum gained",
        );
        let spin = box_inertia(31.25, Vector3::new(0.5, 0.25, 0.25), self.orientation) * self.w;
        assert_near(
            world.creature_angular_momentum() - self.angular,
            centre.cross(&arrives) * 31.25 + spin,
            1e-2,
            "the angular momentum gained",
        );
    }
}

#[test]
fn a_part_added_to_a_moving_creature_arrives_with_its_parent_s_velocity_and_momentum() {
    let mut world = flying_root();
    let before = RootMotion::of(&world);
    let (tail, joint) = add_tail(&mut world, Attach::MovingWith(PartId(0)));
    // Where the tail was asked to be, with no drop lift.
    before.assert_tail_arrived(&world, tail);
    // Moving together, the hinge holds from the first step.
    world.step(false).unwrap();
    let (parent_side, child_side) = world.joint_anchors(joint).unwrap();
    let gap = (parent_side - child_side).norm();
    assert!(gap < 1e-4, "the joint's anchors are {gap} m apart");
}

#[test]
fn a_part_fused_to_a_turning_body_keeps_the_body_s_velocity_field() {
    let mut world = flying_root();
    let (v, w) = world.part_velocity(PartId(0));
    let (root, orientation) = world.part_pose(PartId(0));
    let momentum = world.creature_momentum();

    let (_, tail_orientation): (_, UnitQuaternion<f64>) = world.part_pose(PartId(0));
    let fused = world.add_part(
        &Part {
            size: Vector3::new(0.5, 0.25, 0.25),
            position: root + orientation * Vector3::new(0.75, 0.0, 0.0),
            orientation: tail_orientation,
            density: 1000.0,
            growing: false,
        },
        Attach::FusedTo(PartId(0)),
    );
    // The root's centre moves and turns as before, though the body's centre of mass moved.
    let (root_v, root_w) = world.part_velocity(PartId(0));
    assert_near(root_v, v, 1e-5, "the root's velocity");
    assert_near(root_w, w, 1e-6, "the root's angular velocity");
    let centre = root + orientation * Vector3::new(0.75, 0.0, 0.0);
    let arrives = v + w.cross(&(centre - root));
    assert_near(
        world.part_velocity(fused).0,
        arrives,
        1e-5,
        "the new part's velocity",
    );
    assert_near(
        world.creature_momentum() - momentum,
        arrives * 31.25,
        1e-3,
        "the momentum gained",
    );
    assert_kg(world.part_body_mass(fused).0, 62.5 + 31.25);
}

#[test]
fn a_part_resized_under_a_child_carries_the_child_and_keeps_the_joint_closed() {
    let mut world = flying_root();
    let (tail, joint) = add_tail(&mut world, Attach::MovingWith(PartId(0)));
    let (v, w) = world.part_velocity(PartId(0));
    let (root, orientation) = world.part_pose(PartId(0));
    let (tail_at, _) = world.part_pose(tail);
    let (tail_v, _) = world.part_velocity(tail);

    // The root grows from 1 m to 1.5 m about its centre: its +x face, and the hinge on it,
    // move 0.25 m along its x axis, and the tail with them.
    world.resize_part(PartId(0), Vector3::new(1.5, 0.25, 0.25));
    let d = orientation * Vector3::new(0.25, 0.0, 0.0);
    let (parent_side, child_side) = world.joint_anchors(joint).unwrap();
    assert_near(
        parent_side,
        root + orientation * Vector3::new(0.75, 0.0, 0.0),
        1e-5,
        "the root's anchor",
    );
    assert_near(child_side, parent_side, 1e-5, "the tail's anchor");
    assert_near(
        world.part_position(tail),
        tail_at + d,
        1e-5,
        "the tail's centre",
    );
    // The root keeps its velocity field; the tail moves as the root's field where it now is.
    let (root_v, root_w) = world.part_velocity(PartId(0));
    assert_near(root_v, v, 1e-5, "the root's velocity");
    assert_near(root_w, w, 1e-6, "the root's angular velocity");
    let carried = tail_v + w.cross(&d);
    assert_near(
        world.part_velocity(tail).0,
        carried,
        1e-5,
        "the tail's velocity",
    );
    // 93.75 kg at v, the tail 31.25 kg at its carried velocity.
    assert_near(
        world.creature_momentum(),
        v * 93.75 + carried * 31.25,
        1e-3,
        "the momentum",
    );
    let (mass, inertia) = world.part_body_mass(PartId(0));
    assert_kg(mass, 93.75);
    let by_hand = [
        93.75 / 12.0 * (0.25f64.powi(2) * 2.0),
        93.75 / 12.0 * (1.5f64.powi(2) + 0.25f64.powi(2)),
        93.75 / 12.0 * (1.5f64.powi(2) + 0.25f64.powi(2)),
    ];
    for (axis, expected) in by_hand.iter().enumerate() {
        assert!(
            (inertia[axis] - expected).abs() < 1e-5 * expected,
            "inertia about axis {axis}: {} kg·m², not {expected}",
            inertia[axis]
        );
    }
    assert_kg(world.creature_mass(), 93.75 + 31.25);
    world.step(false).unwrap();
    let (parent_side, child_side) = world.joint_anchors(joint).unwrap();
    let gap = (parent_side - child_side).norm();
    assert!(
        gap < 1e-3,
        "the joint's anchors are {gap} m apart after a step"
    );
}

/// The motion a flying root (62.5 kg) has after growth made it, with what it grew, one rigid
/// 1.5 m × 0.25 m × 0.25 m box of 93.75 kg centred at `centre`, turned by `orientation`, that
/// kept the creature's momentum `momentum` and its angular momentum `angular` about the origin:
/// by hand, its centre moves at P / 93.75 and it turns at ω = I⁻¹ (L − c × P), I the box's
/// inertia about its centre. Returns the velocity of the point `at` and ω.
fn closed_body_motion(
    centre: Vector3<f64>,
    orientation: UnitQuaternion<f64>,
    momentum: Vector3<f64>,
    angular: Vector3<f64>,
    at: Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let inertia = box_inertia(93.75, Vector3::new(1.5, 0.25, 0.25), orientation);
    let w = inertia.try_inverse().unwrap() * (angular - centre.cross(&momentum));
    (momentum / 93.75 + w.cross(&(at - centre)), w)
}

#[test]
fn a_lengthened_part_keeps_its_near_face_and_the_creature_s_momenta() {
    let mut world = flying_root();
    let (c, q) = world.part_pose(PartId(0));
    let near = c + q * Vector3::new(-0.5, 0.0, 0.0);
    let (momentum, angular) = (world.creature_momentum(), world.creature_angular_momentum());
    let energy = world.kinetic_energy();

    // 1 m → 1.5 m: 31.25 kg more, the centre 0.25 m further along the part's x axis.
    assert!(world.grow_part(PartId(0), Vector3::new(1.5, 0.25, 0.25)));
    let (c2, q2) = world.part_pose(PartId(0));
    assert_near(
        c2 + q2 * Vector3::new(-0.75, 0.0, 0.0),
        near,
        1e-5,
        "the near face",
    );
    let d = q * Vector3::new(0.25, 0.0, 0.0);
    assert_near(c2, c + d, 1e-5, "the centre");
    // The creature grew from within: its momenta are what they were, so the longer, heavier
    // part moves and turns slower, as hand calculation says.
    assert_near(world.creature_momentum(), momentum, 1e-3, "the momentum");
    assert_near(
        world.creature_angular_momentum(),
        angular,
        1e-2,
        "the angular momentum",
    );
    let (v, w) = closed_body_motion(c + d, q, momentum, angular, c + d);
    let (v2, w2) = world.part_velocity(PartId(0));
    assert_near(v2, v, 1e-4, "the centre's velocity");
    assert_near(w2, w, 1e-4, "the angular velocity");
    assert!(
        world.kinetic_energy() < energy,
        "growth gave kinetic energy"
    );
}

/// Growth that adds a 0.5 m tail with a hinge at the far end of a 1 m root, as a new
/// string built from the origin would place it.
fn tail_growth(world: &World) -> Growth {
    let mut creature = creature_from_commands("forward(1)").unwrap();
    let shape = Part {
        size: Vector3::new(0.5, 0.25, 0.25),
        position: Vector3::new(1.25, 0.0, 0.0),
        orientation: UnitQuaternion::identity(),
        density: 1000.0,
        growing: true,
    };
    let spec = Joint {
        parent: 0,
        child: 1,
        kind: JointKind::Revolute,
        anchor: Vector3::new(1.0, 0.0, 0.0),
        axes: vec![Vector3::z()],
        limits: vec![(-0.5, 0.5)],
        strength: 1.0,
        growing: true,
    };
    creature.parts.push(shape.clone());
    creature.joints.push(spec.clone());
    assert_eq!(world.part_count(), 1);
    Growth {
        events: vec![GrowthEvent::NewPart {
            part: PartId(1),
            shape,
            parent: PartId(0),
            joint: JointId(0),
            spec,
        }],
        creature,
        lost: Vec::new(),
    }
}

#[test]
fn a_new_bud_arrives_at_its_place_on_its_parent_and_the_creature_keeps_its_momenta() {
    let mut world = flying_root();
    let before = RootMotion::of(&world);
    let energy = world.kinetic_energy();
    let mut growth = tail_growth(&world);
    let grown = world.apply_growth(&mut growth);
    assert_eq!((grown.added, grown.resized), (1, 0));
    assert!(grown.stopped.is_empty());
    // Where the turtle puts it: 0.75 m along the root's x axis.
    let tail = before.root + before.orientation * Vector3::new(0.75, 0.0, 0.0);
    assert_near(
        world.part_position(PartId(1)),
        tail,
        1e-5,
        "the tail's centre",
    );
    // The creature's momenta are what they were: root and tail move as one 1.5 m box.
    assert_near(
        world.creature_momentum(),
        before.momentum,
        1e-3,
        "the momentum",
    );
    assert_near(
        world.creature_angular_momentum(),
        before.angular,
        1e-2,
        "the angular momentum",
    );
    let centre = before.root + before.orientation * Vector3::new(0.25, 0.0, 0.0);
    for (part, at) in [(PartId(0), before.root), (PartId(1), tail)] {
        let (v, w) = closed_body_motion(
            centre,
            before.orientation,
            before.momentum,
            before.angular,
            at,
        );
        let (part_v, part_w) = world.part_velocity(part);
        assert_near(part_v, v, 1e-4, "a part's velocity");
        assert_near(part_w, w, 1e-4, "a part's angular velocity");
    }
    assert!(
        world.kinetic_energy() < energy,
        "growth gave kinetic energy"
    );
    // The energy it brought (the tail's weight lifted 5 m up, less the kinetic energy it
    // cost) is growth's work, not energy from nowhere.
    assert!((world.growth_work() - grown.work).abs() < 1e-9);
    assert!(grown.work > 0.0);
}

#[test]
fn the_audit_passes_honest_growth_of_a_flying_turning_root() {
    let mut world = flying_root();
    // The root lengthens by 2 cm a control step for 25 steps while it flies and turns.
    for k in 1..=25 {
        let size = Vector3::new(1.0 + 0.02 * k as f64, 0.25, 0.25);
        assert!(world.grow_part(PartId(0), size));
        world.step(false).unwrap();
    }
    let honest = world.peak_unexplained_energy();
    assert!(honest < 0.5, "{honest} J from nowhere in honest growth");
    assert!(
        world.growth_work() > 1.0,
        "{} J of growth",
        world.growth_work()
    );
}

#[test]
fn a_root_that_lengthens_on_the_spot_walks_no_distance() {
    let mut world = settled_root();
    let near = |world: &World| {
        let (c, q) = world.part_pose(PartId(0));
        let size = world.part_size(PartId(0));
        c + q * Vector3::new(-size.x / 2.0, 0.0, 0.0)
    };
    let start = near(&world);
    let centre = world.part_position(PartId(0));
    // 1 m → 1.5 m, 1 cm a control step, lying on the ground.
    for k in 1..=50 {
        assert!(world.grow_part(PartId(0), Vector3::new(1.0 + 0.01 * k as f64, 0.25, 0.25)));
        world.step(false).unwrap();
    }
    for _ in 0..20 {
        world.step(false).unwrap();
    }
    let walked = (near(&world) - start).xz().norm();
    assert!(walked < 1e-3, "the root's near face moved {walked} m");
    let moved = world.part_position(PartId(0)).x - centre.x;
    assert!((moved - 0.25).abs() < 1e-3, "the centre moved {moved} m");
}

#[test]
fn a_part_that_would_grow_into_the_ground_stops_growing() {
    let creature = creature_from_commands("forward(1)").unwrap();
    let mut world = settled_root();
    let energy = world.growth_work();
    // Thicker about its axis, its underside would sink 5 cm into the ground.
    assert!(!world.grow_part(PartId(0), Vector3::new(1.0, 0.35, 0.25)));
    assert_eq!(world.part_size(PartId(0)), Vector3::new(1.0, 0.25, 0.25));
    assert_eq!(world.growth_work(), energy);
    // Growth in a step that applies it is reported as stopped, and the creature keeps
    // the size the world has.
    let mut growth = Growth {
        events: vec![GrowthEvent::Resize {
            part: PartId(0),
            size: Vector3::new(1.0, 0.35, 0.25),
        }],
        creature: Creature {
            parts: vec![Part {
                size: Vector3::new(1.0, 0.35, 0.25),
                ..creature.parts[0].clone()
            }],
            ..creature.clone()
        },
        lost: Vec::new(),
    };
    let grown = world.apply_growth(&mut growth);
    assert_eq!(grown.stopped, [PartId(0)]);
    assert_eq!(growth.creature.parts[0].size, Vector3::new(1.0, 0.25, 0.25));
}

/// Growth that adds to a root with a 0.5 m tail (`add_tail`) a 0.5 m branch leaving the
/// root's end face, where the tail hangs from, turned `turn` radians about z from the tail,
/// jointed to the root by `kind`, as a new string built from the origin would place it.
fn branch_beside_the_tail(turn: f64, kind: JointKind) -> Growth {
    let mut creature = creature_from_commands("forward(1)").unwrap();
    let turned = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn);
    let tail = Part {
        size: Vector3::new(0.5, 0.25, 0.25),
        position: Vector3::new(1.25, 0.0, 0.0),
        orientation: UnitQuaternion::identity(),
        density: 1000.0,
        growing: false,
    };
    let shape = Part {
        position: Vector3::new(1.0, 0.0, 0.0) + turned * Vector3::new(0.25, 0.0, 0.0),
        orientation: turned,
        growing: true,
        ..tail.clone()
    };
    let hinge = |child: usize, axis: Vector3<f64>| Joint {
        parent: 0,
        child,
        kind,
        anchor: Vector3::new(1.0, 0.0, 0.0),
        axes: if kind == JointKind::Rigid {
            Vec::new()
        } else {
            vec![axis]
        },
        limits: if kind == JointKind::Rigid {
            Vec::new()
        } else {
            vec![(-0.5, 0.5)]
        },
        strength: 1.0,
        growing: false,
    };
    creature.parts.extend([tail, shape.clone()]);
    let spec = hinge(2, Vector3::z());
    creature.joints.extend([
        Joint {
            kind: JointKind::Revolute,
            axes: vec![Vector3::z()],
            limits: vec![(-0.5, 0.5)],
            ..hinge(1, Vector3::z())
        },
        spec.clone(),
    ]);
    Growth {
        events: vec![GrowthEvent::NewPart {
            part: PartId(2),
            shape,
            parent: PartId(0),
            joint: JointId(1),
            spec,
        }],
        creature,
        lost: Vec::new(),
    }
}

#[test]
fn a_new_branch_may_not_appear_inside_a_sibling_but_may_leave_their_anchor_beside_it() {
    for kind in [JointKind::Rigid, JointKind::Revolute] {
        // Where the tail is: the two would overlap by the tail's whole box, and the contact
        // solver would push them apart every step.
        let mut world = flying_root();
        add_tail(&mut world, Attach::MovingWith(PartId(0)));
        let mut growth = branch_beside_the_tail(0.0, kind);
        let grown = world.apply_growth(&mut growth);
        assert_eq!(grown.added, 0, "{kind:?}");
        assert_eq!(grown.stopped, [PartId(2)], "{kind:?}");
        assert_eq!(world.part_count(), 2);
        assert_eq!(growth.creature.parts.len(), 2, "the creature lacks it too");
        // Turned 90° from the tail it meets the tail and the root only in their joint's
        // contact region (the builder's rule): it appears.
        let mut world = flying_root();
        add_tail(&mut world, Attach::MovingWith(PartId(0)));
        let mut growth = branch_beside_the_tail(std::f64::consts::FRAC_PI_2, kind);
        let grown = world.apply_growth(&mut growth);
        assert_eq!((grown.added, grown.stopped.len()), (1, 0), "{kind:?}");
        assert_eq!(world.part_count(), 3);
        assert!(growth.creature.interpenetrating_pairs().is_empty());
    }
}

/// A neuron with `function`, `params` and `role`, no bias.
fn neuron(function: NeuronFunction, params: Vec<f64>) -> Neuron {
    Neuron {
        function,
        params,
        bias: 0.0,
        role: Role::Hidden,
        part: None,
    }
}

#[test]
fn a_running_brain_gains_a_neuron_and_links_that_act_from_the_next_step() {
    // 0: constant 0.5; 1: linear, no input; 2: linear, reading 0 with weight 1.
    let brain = Brain {
        neurons: vec![
            neuron(NeuronFunction::Constant, vec![0.5]),
            neuron(NeuronFunction::Linear, Vec::new()),
            neuron(NeuronFunction::Linear, Vec::new()),
        ],
        links: vec![Link {
            from: 0,
            to: 2,
            weight: 1.0,
        }],
    };
    let mut runtime = BrainRuntime::new(&brain);
    runtime.step(0.0, 0.05);
    assert_eq!(runtime.outputs(), [0.5, 0.0, 0.0]);

    // 3: constant 0.25; links 0 → 1 (weight 0.5, a first input between existing ones) and
    // 3 → 2 (a second input).
    let added = runtime.add_neuron(&neuron(NeuronFunction::Constant, vec![0.25]));
    assert_eq!(added, 3);
    assert_eq!(runtime.neuron_count(), 4);
    runtime.add_link(&Link {
        from: 0,
        to: 1,
        weight: 0.5,
    });
    runtime.add_link(&Link {
        from: 3,
        to: 2,
        weight: 1.0,
    });
    assert_eq!(runtime.outputs(), [0.5, 0.0, 0.0, 0.0]);
    // Synchronous updates: each step reads the outputs of the one before.
    runtime.step(0.05, 0.05);
    assert_eq!(runtime.outputs(), [0.5, 0.25, 0.5, 0.25]);
    runtime.step(0.1, 0.05);
    assert_eq!(runtime.outputs(), [0.5, 0.25, 0.75, 0.25]);
}

/// Figure 1 of Matos & Arita: B grows until it splits at x = 4, A until y = 2.
const FIGURE_1: &str = "\
time: 5.5
dt: 0.5
axiom: B(1) A(0, 0)
B(x) : x < 4 --> solve dx/dt = 1
B(x) : x >= 4 --> A(2, 2) B(1)
A(x, y) : y < 2 --> solve dx/dt = 2, dy/dt = 1
A(x, y) : y >= 2 --> B(x) C(2)
";

/// The symbols of `string`, and its parameters.
fn state(lsys: &LSystem, string: &ModuleString) -> (Vec<String>, Vec<f64>) {
    let names = string
        .iter()
        .map(|m| lsys.symbols().name(m.sym).to_string())
        .collect();
    let params = string.iter().flat_map(|m| m.params.to_vec()).collect();
    (names, params)
}

#[test]
fn a_development_stepped_by_uneven_steps_reaches_the_string_of_its_frames() {
    let lsys = Arc::new(LSystem::from_text("figure-1.lsys", FIGURE_1).unwrap());
    let options = DeriveOptions::default();

    // Frame by frame, every 0.5 up to 5.5, as `ontogeny derive` shows it.
    let mut frames = lsys.development(&options).unwrap();
    while frames.advance().unwrap() {}
    assert_eq!(frames.time(), 5.5);
    let mut events = frames.take_events();

    // Held by a loop that owns it, stepped by uneven Δt's to the same time.
    let mut stepped = Development::start(Arc::clone(&lsys), &options).unwrap();
    for dt in [0.3, 0.05, 1.45, 0.0, 2.2, 0.7] {
        stepped.advance_by(dt).unwrap();
    }
    stepped.advance_by(5.5 - stepped.now()).unwrap();
    assert_eq!(stepped.now(), 5.5);

    let (names, params) = state(&lsys, stepped.current());
    let (frame_names, frame_params) = state(&lsys, frames.current());
    assert_eq!(names, frame_names);
    assert_eq!(
        names,
        [
            "B", "C", "B", "C", "B", "B", "C", "B", "C", "B", "C", "B", "C"
        ]
    );
    assert_eq!(params.len(), frame_params.len());
    for (a, b) in params.iter().zip(&frame_params) {
        assert!((a - b).abs() < 1e-9, "{a} against {b}");
    }
    // The same events at the same moments.
    let mut stepped_events = stepped.take_events();
    for e in events.iter_mut().chain(stepped_events.iter_mut()) {
        e.t = (e.t * 1e6).round() / 1e6;
    }
    assert_eq!(stepped_events, events);
}

#[test]
fn a_development_step_below_zero_is_refused() {
    let lsys = Arc::new(LSystem::from_text("figure-1.lsys", FIGURE_1).unwrap());
    let mut development = Development::start(lsys, &DeriveOptions::default()).unwrap();
    let error = development.advance_by(-1.0).unwrap_err();
    assert_eq!(
        error.to_string(),
        "error: a development step must be 0 or more, not -1"
    );
    assert_eq!(development.now(), 0.0);
}
