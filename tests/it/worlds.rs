//! Worlds besides flat ground (`[task.world]`): a box on a slope rests or slides as the
//! ground's friction and its patches say, a walker over steps, distance on a slope and over
//! steps as the root's horizontal displacement, the rest test and the explosion guard on rough
//! ground, the rough ground's determinism, a rolling ball's path, and every example world run
//! through `evolve`.

use ontogeny::creature::{Creature, PartId};
use ontogeny::develop::creature_from_commands;
use ontogeny::sim::{GRAVITY, SimOptions, World, WorldSpec};
use ontogeny::task::{TaskKind, TaskSpec};

use crate::util::{grown, ontogeny_ok, scratch_dir};

fn world_spec(text: &str) -> WorldSpec {
    toml::from_str(text).unwrap()
}

/// A box 1 m long and 0.25 m wide and high: it slides rather than rolls.
fn plank() -> Creature {
    creature_from_commands("forward(1)").unwrap()
}

fn run(world: &mut World, seconds: f64) {
    let steps = (seconds * 60.0).round() as usize;
    for _ in 0..steps {
        world.step(false).unwrap();
    }
}

/// A plank on a 30° slope rising towards +x, the ground's friction `mu` (used as is against
/// any part: the rule `[task.world] friction` fixes), dropped from 1 mm.
fn plank_on_slope(mu: f64) -> World {
    let spec = world_spec(&format!(
        "slope = {{ degrees = 30 }}\nfriction = {{ coefficient = {mu} }}"
    ));
    let options = SimOptions {
        drop_height: 0.001,
        ..SimOptions::default()
    };
    World::in_world(&plank(), &options, &spec).unwrap()
}

#[test]
fn a_box_on_a_30_degree_slope_rests_at_friction_1_2_tan_30() {
    let tan = 30f64.to_radians().tan();
    let mut world = plank_on_slope(1.2 * tan);
    run(&mut world, 1.0);
    let settled = world.part_position(PartId(0));
    run(&mut world, 2.0);
    let moved = (world.part_position(PartId(0)) - settled).norm();
    assert!(moved < 1e-3, "moved {moved} m in 2 s");
}

#[test]
fn a_box_on_a_30_degree_slope_slides_at_friction_0_8_tan_30_as_coulomb_says() {
    // Down the slope at a = g (sin θ − μ cos θ) = g sin θ (1 − 0.8) = 0.981 m/s²: the second
    // difference of its positions 0.5 s apart is a × 0.25 s².
    let theta = 30f64.to_radians();
    let mu = 0.8 * theta.tan();
    let mut world = plank_on_slope(mu);
    run(&mut world, 0.5);
    let mut along = Vec::new();
    for _ in 0..3 {
        let p = world.part_position(PartId(0));
        along.push(-(p.x * theta.cos() + p.y * theta.sin()));
        run(&mut world, 0.5);
    }
    let a = (along[2] - 2.0 * along[1] + along[0]) / 0.25;
    let by_hand = GRAVITY * (theta.sin() - mu * theta.cos());
    assert!((by_hand - 0.981).abs() < 1e-3);
    assert!(
        (a - by_hand).abs() < 0.05 * by_hand,
        "a = {a} m/s², by hand {by_hand}"
    );
    // Straight down the slope: sideways, under 5% of the way slid (the plank lands on an
    // edge and turns a little as it settles onto the slope).
    let p = world.part_position(PartId(0));
    let slid = -(p.x * theta.cos() + p.y * theta.sin()) - along[0];
    assert!(slid > 0.5, "slid {slid} m");
    assert!(
        p.z.abs() < 0.05 * slid,
        "strayed {} m sideways in {slid} m",
        p.z
    );
}

#[test]
fn a_box_on_a_slope_slides_on_a_low_friction_patch_and_rests_off_it() {
    // The ground holds the plank (1.2 tan 30°); a patch of 0.8 tan 30° lets it slide. The
    // plank starts at the origin: on the patch round it, or off the patch far along z.
    let tan = 30f64.to_radians().tan();
    let slid_on = |patch_z: [f64; 2]| {
        let spec = world_spec(&format!(
            "slope = {{ degrees = 30 }}\nfriction = {{ coefficient = {}, patches = [\
             {{ x = [-50, 50], z = [{}, {}], coefficient = {} }}] }}",
            1.2 * tan,
            patch_z[0],
            patch_z[1],
            0.8 * tan
        ));
        spec.check().unwrap();
        let options = SimOptions {
            drop_height: 0.001,
            ..SimOptions::default()
        };
        let mut world = World::in_world(&plank(), &options, &spec).unwrap();
        run(&mut world, 1.0);
        let settled = world.part_position(PartId(0));
        run(&mut world, 1.0);
        (world.part_position(PartId(0)) - settled).norm()
    };
    let on = slid_on([-50.0, 50.0]);
    let off = slid_on([20.0, 50.0]);
    // On the patch it slides at 0.981 m/s²: more than 0.4 m in the second second.
    assert!(on > 0.4, "slid {on} m on the patch");
    assert!(off < 1e-3, "slid {off} m off the patch");
}

/// The walker's task in `world` (the text of a `[task.world]` table), walks of `seconds`,
/// checked.
fn walker_in(world: &str, seconds: f64) -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    spec.task
        .get_mut::<ontogeny::task::WalkerOptions>()
        .unwrap()
        .seconds = seconds;
    spec.world = world_spec(world);
    spec.check().unwrap();
    spec
}

/// The walker's evaluation of `examples/quadruped.lsys` in `world`, 3 s walks, recorded or
/// not.
fn walker_over(world: &str, record: bool) -> ontogeny::task::Evaluation {
    walker_in(world, 3.0).evaluate(&grown("examples/quadruped.lsys"), record)
}

#[test]
fn distance_on_a_slope_and_over_steps_is_the_root_s_horizontal_displacement() {
    for world in [
        "slope = { degrees = 10, direction = 180 }",
        "steps = { height = 0.04, depth = 0.2, count = 10, start = 0.3, way = \"down\" }",
    ] {
        let e = walker_over(world, true);
        assert_eq!(
            e.status,
            ontogeny::task::Status::Ok,
            "{world}: {:?}",
            e.message
        );
        // The root part's centre where the measured walk starts and where it ends.
        let from_t = e.terms["measured_from"];
        let from = e
            .recording
            .iter()
            .find(|s| (s.t - from_t).abs() < 1e-9)
            .unwrap_or_else(|| panic!("{world}: no sample at {from_t} s"))
            .parts[0]
            .0;
        let to = e.recording.last().unwrap().parts[0].0;
        let d = to - from;
        let horizontal = d.x.hypot(d.z);
        // Positions are recorded at f32 precision.
        assert!(
            (e.terms["D_w"] - horizontal).abs() < 1e-5,
            "{world}: D_w {} against {horizontal}",
            e.terms["D_w"]
        );
        // The root climbed or fell on the way, so the distance in space is longer.
        assert!(d.y.abs() > 0.005, "{world}: the root moved {} m up", d.y);
        assert!(d.norm() > horizontal + 1e-5, "{world}");
    }
}

#[test]
fn on_rough_ground_a_resting_creature_passes_and_an_exploding_one_is_caught() {
    let mut spec = walker_in(
        "rough = { amplitude = 0.05, wavelength = 0.5, seed = 3, size = 8 }",
        0.5,
    );
    let snake = grown("examples/snake.lsys");
    let calm = spec.evaluate(&snake, false);
    assert_eq!(
        calm.status,
        ontogeny::task::Status::Ok,
        "{:?}",
        calm.message
    );
    spec.sim.actuator = ontogeny::sim::ActuatorModel::Velocity;
    spec.sim.strength = 1e9;
    spec.sim.max_speed = 1e6;
    let wild = spec.evaluate(&snake, false);
    assert_eq!(wild.status, ontogeny::task::Status::Exploded, "{wild:?}");
    assert_eq!(wild.fitness, ontogeny::task::FAILURE_FITNESS);
}

#[test]
fn a_walker_over_steps_goes_a_horizontal_distance_other_than_on_flat_ground() {
    let flat = walker_over("", false);
    let steps = walker_over(
        "steps = { height = 0.04, depth = 0.2, count = 10, start = 0.3, way = \"down\" }",
        false,
    );
    assert_eq!(
        flat.status,
        ontogeny::task::Status::Ok,
        "{:?}",
        flat.message
    );
    assert_eq!(
        steps.status,
        ontogeny::task::Status::Ok,
        "{:?}",
        steps.message
    );
    assert!(steps.terms["D_w"] > 0.0);
    assert_ne!(steps.terms["D_w"], flat.terms["D_w"]);
}

#[test]
fn one_seed_makes_one_rough_ground_and_one_evaluation_another_seed_another() {
    let rough = |seed| {
        walker_over(
            &format!("rough = {{ amplitude = 0.05, wavelength = 0.5, seed = {seed}, size = 8 }}"),
            false,
        )
    };
    let (a, b, c) = (rough(1), rough(1), rough(2));
    assert_eq!(a.fitness.to_bits(), b.fitness.to_bits());
    assert_eq!(a.terms, b.terms);
    assert_ne!(a.fitness, c.fitness);
}

#[test]
fn a_ball_let_go_on_flat_ground_rolls_straight_along_its_velocity() {
    // A ball of radius r = 0.2 m let go sliding at v0 = 2 m/s along (0.6, 0, 0.8), friction
    // μ = 1 against the ground: friction slows it and spins it up until it rolls, at
    // t1 = 2 v0 / (7 μ g), having gone v0 t1 − μ g t1² / 2; then it rolls at 5 v0 / 7
    // (rolling friction, which rapier does not model, aside). We assert its distance after
    // 1 s within 2% of that, and that it strays less than 1 mm from its line.
    let spec = world_spec(
        "friction = { coefficient = 1 }\n\
         objects = [{ size = 0.2, mass = 5, position = [3, 0.2, 3], velocity = [1.2, 0, 1.6] }]",
    );
    let mut world = World::in_world(&plank(), &SimOptions::default(), &spec).unwrap();
    run(&mut world, 0.5);
    assert_eq!(
        world.object_positions()[0],
        [3.0, 0.2f32 as f64, 3.0],
        "held until let go (rapier holds f32)"
    );
    world.release_objects();
    run(&mut world, 1.0);
    let [x, y, z] = world.object_positions()[0];
    let (dx, dz) = (x - 3.0, z - 3.0);
    let (v0, g) = (2.0, GRAVITY);
    let t1 = 2.0 * v0 / (7.0 * g);
    let by_hand = v0 * t1 - 0.5 * g * t1 * t1 + 5.0 / 7.0 * v0 * (1.0 - t1);
    let gone = dx.hypot(dz);
    assert!(
        (gone - by_hand).abs() < 0.02 * by_hand,
        "{gone} m, by hand {by_hand} m"
    );
    assert!(
        (dx * 0.8 - dz * 0.6).abs() < 1e-3,
        "off its line: ({dx}, {dz})"
    );
    assert!((y - 0.2).abs() < 1e-3);
}

#[test]
fn every_example_world_evolves_a_generation() {
    for name in [
        "slope",
        "steps",
        "rough",
        "obstacles",
        "object",
        "friction-patch",
    ] {
        let out = scratch_dir(&format!("world-{name}"));
        let config = format!("examples/world-{name}.toml");
        ontogeny_ok(&[
            "evolve",
            "--config",
            &config,
            "--gens",
            "1",
            "--pop",
            "4",
            "--out",
            out.join("run").to_str().unwrap(),
        ]);
    }
}
