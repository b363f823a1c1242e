//! The evaluation key (`ontogeny::evolve::key`): pinned for a fixed creature and task, in both
//! versions, so that a change of its byte form, which would orphan every stored evaluation, is
//! deliberate; changed by every setting the task reads, so that no setting can stop reaching
//! the key and give one cached evaluation to two different tasks, and by no other, of a file
//! holding every task's table (version 2); and, in version 1, by every task's settings, as
//! runs made before version 2 keyed them from their stored tables.

use ontogeny::creature::Creature;
use ontogeny::evolve::key::{EvaluationKey, KeyVersion};
use ontogeny::task::{TaskKind, TaskSpec, TaskTables};
use serde_json::Value;

/// The fixed creature: two parts on a hinge, built from commands.
fn creature() -> Creature {
    ontogeny::develop::creature_from_commands("forward(1) revolute2 forward(1)").unwrap()
}

#[test]
fn the_key_of_a_fixed_creature_and_task_is_pinned() {
    let c = creature();
    let keys = |version: KeyVersion| -> Vec<String> {
        TaskKind::ALL
            .iter()
            .map(|&kind| EvaluationKey::of_version(&c, &TaskSpec::new(kind), version).to_hex())
            .collect()
    };
    // Version 1, the keys of runs made before keys had versions: the last two are the stand
    // and swim tasks, which no such run has.
    assert_eq!(
        keys(KeyVersion::V1)[..4],
        [
            "706031de35c2dfaf481d4c16cb0674fcfbe83d70d96e1e0b1c84fd2a9082910a",
            "13d36160947225552d602ca3177b50cc1b5a3f697232d396b131f53a0ac2ea18",
            "879499ad7c9d1f14c7c5ee661fe19711bd06237a89fbec1be6d5988ea4be0768",
            "601770ea3402902d0ec528be1888410fd5926dcec257f18f6675811c88e95ce5",
        ]
    );
    assert_eq!(keys(KeyVersion::V2), PINNED_V2);
}

#[test]
fn the_swim_key_changes_with_the_water_s_viscosity() {
    let c = creature();
    let in_water = |viscosity: f64| {
        let mut spec = TaskSpec::new(TaskKind::Swim);
        spec.world.medium = ontogeny::sim::Medium::Water { viscosity };
        EvaluationKey::of(&c, &spec)
    };
    assert_ne!(in_water(500.0), in_water(501.0));
}

/// The version-2 keys of the fixed creature with each task's defaults, in the registry's order.
const PINNED_V2: [&str; 6] = [
    "000f7ad5e3102e309e8f1c76a505ca1202336fc52ad8cb324965806bf7df3c60",
    "7eaf76b89c1b1d788cbfe19a2931a5edd0244967fc963e6b6a624bce5fe7acf2",
    "062cd63070f4274f98c1a46235bf92e6cf9144db8c8c322a067a88395afd235b",
    "9d760fa44c633c82e830d8ded339b04d7f68d26f5b9f2cdf74b378abcac1dc9e",
    "23845b72f0e7da12f0d3d9a5d2d62fac7f969e64870ab9de4402b1eb1b7c896b",
    "85946cf2745677c972efd466c8570f3eab2449871815bee219a79dc22ca43f7e",
];

/// Every leaf of `value` (a number, string, boolean or null that no object or array holds
/// inside it), by its path of keys and indices.
fn leaves(value: &Value, path: &str, found: &mut Vec<String>) {
    match value {
        Value::Object(map) => {
            for (key, inner) in map {
                leaves(inner, &format!("{path}/{key}"), found);
            }
        }
        Value::Array(items) if !items.is_empty() => {
            for (i, inner) in items.iter().enumerate() {
                leaves(inner, &format!("{path}/{i}"), found);
            }
        }
        _ => found.push(path.to_string()),
    }
}

/// Values to put in place of `leaf`: other numbers, the other boolean, the other names an
/// enumeration accepts (from the names in its refusal of a made-up one), and values of a few
/// shapes in place of null.
fn replacements(spec: &Value, pointer: &str) -> Vec<Value> {
    let leaf = spec.pointer(pointer).unwrap();
    match leaf {
        Value::Bool(b) => vec![Value::Bool(!b)],
        Value::Number(n) => {
            let mut values = Vec::new();
            if let Some(u) = n.as_u64() {
                values.extend([u + 1, u.saturating_sub(1)].map(Value::from));
            }
            let f = n.as_f64().unwrap();
            values.extend([f + 0.125, f * 2.0, f / 2.0, 0.5].map(Value::from));
            values
        }
        Value::String(_) => {
            let mut probe = spec.clone();
            *probe.pointer_mut(pointer).unwrap() = Value::from("no-such-name");
            let Err(refusal) = serde_json::from_value::<TaskSpec>(probe).map_err(|e| e.to_string())
            else {
                // Any string is taken (the walker's fitness: a formula or an expression).
                return vec![Value::from("no-such-name")];
            };
            // "unknown variant `no-such-name`, expected one of `a`, `b`, `c`"
            refusal
                .split_once("expected ")
                .map(|(_, names)| {
                    names
                        .split('`')
                        .skip(1)
                        .step_by(2)
                        .map(Value::from)
                        .collect()
                })
                .unwrap_or_default()
        }
        Value::Null => vec![
            Value::from(0.5),
            Value::from(3),
            serde_json::json!([1.0, 2.0, 3.0]),
            Value::Bool(true),
        ],
        Value::Array(_) | Value::Object(_) => Vec::new(),
    }
}

/// Whether the task `kind` reads the setting at `pointer` of its specification (as JSON):
/// the task's name, the simulator's settings and its own table (the catapult all of its
/// table but the target, which only aim reads).
fn reads(kind: TaskKind, pointer: &str) -> bool {
    let table = match kind {
        TaskKind::Aim => "catapult",
        other => other.name(),
    };
    pointer == "/task"
        || pointer.starts_with("/sim/")
        || (pointer.starts_with(&format!("/{table}/"))
            && !(kind == TaskKind::Catapult && pointer == "/catapult/target"))
}

/// A specification that reads back with the leaf at `pointer` of `spec` changed, if one does.
fn with_leaf_changed(spec: &Value, pointer: &str) -> Option<TaskSpec> {
    let original = spec.pointer(pointer).unwrap().clone();
    // The first replacement the task reads back with this leaf changed.
    replacements(spec, pointer).into_iter().find_map(|value| {
        let mut edited = spec.clone();
        *edited.pointer_mut(pointer).unwrap() = value;
        let read: TaskSpec = serde_json::from_value(edited).ok()?;
        let back = serde_json::to_value(&read).unwrap();
        (back.pointer(pointer) != Some(&original)).then_some(read)
    })
}

#[test]
fn every_setting_the_task_reads_changes_its_key() {
    let c = creature();
    let mut all = Vec::new();
    for &kind in TaskKind::ALL {
        let task = TaskSpec::new(kind);
        let key = EvaluationKey::of(&c, &task);
        let spec = serde_json::to_value(&task).unwrap();
        let mut found = Vec::new();
        leaves(&spec, "", &mut found);
        let mut wrong = Vec::new();
        for pointer in &found {
            match with_leaf_changed(&spec, pointer) {
                Some(read) if (EvaluationKey::of(&c, &read) != key) != reads(kind, pointer) => {
                    wrong.push(format!("{pointer}: read {}", reads(kind, pointer)));
                }
                Some(_) => {}
                None => wrong.push(format!("{pointer}: no other value reads back")),
            }
        }
        assert!(wrong.is_empty(), "{kind:?}: {wrong:#?}\nin {spec:#}");
        all.extend(found);
    }
    all.sort();
    all.dedup();
    assert_eq!(all, PINNED_LEAVES);
}

/// The `[task]` table of `kind` as the files of earlier releases hold it: its name, the
/// simulator's settings and every task's table, each at its defaults.
fn every_table(kind: TaskKind) -> Value {
    let mut file = serde_json::to_value(TaskSpec::new(kind)).unwrap();
    for &other in TaskKind::ALL {
        let table = other.table();
        let value = serde_json::to_value(TaskSpec::new(other)).unwrap()[table].clone();
        file.as_object_mut().unwrap().entry(table).or_insert(value);
    }
    file
}

/// `file` with the leaf at `pointer` changed to the first other value that reads back as
/// tables.
fn tables_with_leaf_changed(file: &Value, pointer: &str) -> TaskTables {
    let original = file.pointer(pointer).unwrap();
    replacements(file, pointer)
        .into_iter()
        .filter(|value| value != original)
        .find_map(|value| {
            let mut edited = file.clone();
            *edited.pointer_mut(pointer).unwrap() = value;
            serde_json::from_value(edited).ok()
        })
        .unwrap()
}

#[test]
fn a_file_holding_every_tasks_table_gives_the_key_of_the_task_it_names_alone() {
    let c = creature();
    for &kind in TaskKind::ALL {
        let file = every_table(kind);
        let read: TaskSpec = serde_json::from_value(file.clone()).unwrap();
        let key = EvaluationKey::of(&c, &read);
        assert_eq!(key, EvaluationKey::of(&c, &TaskSpec::new(kind)), "{kind:?}");
        let mut found = Vec::new();
        leaves(&file, "", &mut found);
        for pointer in found
            .iter()
            .filter(|p| !reads(kind, p) && *p != "/catapult/target")
        {
            let tables = tables_with_leaf_changed(&file, pointer);
            assert_eq!(
                EvaluationKey::of(&c, &tables.spec(kind)),
                key,
                "{kind:?}: {pointer}"
            );
        }
    }
}

#[test]
fn every_setting_of_every_task_in_a_stored_file_changed_a_version_1_key() {
    let c = creature();
    for &kind in &TaskKind::ALL[..4] {
        let file = every_table(kind);
        let tables: TaskTables = serde_json::from_value(file.clone()).unwrap();
        let key = EvaluationKey::of_tables(&c, &tables);
        assert_eq!(
            key,
            EvaluationKey::of_version(&c, &TaskSpec::new(kind), KeyVersion::V1),
            "{kind:?}"
        );
        let mut found = Vec::new();
        leaves(&file, "", &mut found);
        for pointer in found
            .iter()
            .filter(|p| !p.starts_with("/stand/") && !p.starts_with("/swim/"))
        {
            let changed = tables_with_leaf_changed(&file, pointer);
            assert_ne!(
                EvaluationKey::of_tables(&c, &changed),
                key,
                "{kind:?}: {pointer}"
            );
        }
    }
}

/// The leaves of every task's specification, in order, all tasks together. A setting added to the task or the
/// simulator is added here (and is then checked above to change the key); one that stops being
/// serialised, so that it could no longer change the key, fails the test.
const PINNED_LEAVES: &[&str] = &[
    "/catapult/max_height",
    "/catapult/max_seconds",
    "/catapult/projectile_density",
    "/catapult/projectile_size/0",
    "/catapult/projectile_size/1",
    "/catapult/projectile_size/2",
    "/catapult/release_delay",
    "/catapult/rest_duration",
    "/catapult/rest_speed",
    "/catapult/target",
    "/jump/max_height",
    "/jump/rest/distance",
    "/jump/rest/drift",
    "/jump/rest/duration",
    "/jump/rest/limit",
    "/jump/seconds",
    "/sim/actuator",
    "/sim/control_step",
    "/sim/drop_height",
    "/sim/energy_tolerance",
    "/sim/explosion_distance",
    "/sim/friction",
    "/sim/joints",
    "/sim/max_speed",
    "/sim/muscle_speed",
    "/sim/pgs_iterations",
    "/sim/rest_solver_iterations",
    "/sim/rest_substeps",
    "/sim/self_collision",
    "/sim/solver_iterations",
    "/sim/speed_limit",
    "/sim/strength",
    "/sim/strength_from",
    "/sim/substeps",
    "/stand/max_height",
    "/stand/rest/distance",
    "/stand/rest/drift",
    "/stand/rest/duration",
    "/stand/rest/limit",
    "/stand/seconds",
    "/swim/seconds",
    "/task",
    "/walker/activation",
    "/walker/fitness",
    "/walker/kappa",
    "/walker/max_height",
    "/walker/rest/distance",
    "/walker/rest/drift",
    "/walker/rest/duration",
    "/walker/rest/limit",
    "/walker/second_settle",
    "/walker/seconds",
];

#[test]
fn the_aim_task_s_target_sensor_and_a_creature_s_projectile_change_the_key() {
    use ontogeny::task::CatapultOptions;
    let c = creature();
    let with = |kind: TaskKind, change: &dyn Fn(&mut CatapultOptions)| {
        let mut spec = TaskSpec::new(kind);
        change(spec.task.get_mut::<CatapultOptions>().unwrap());
        EvaluationKey::of(&c, &spec)
    };
    let blind = |o: &mut CatapultOptions| o.target_sensor = false;
    let plain = |_: &mut CatapultOptions| {};
    // The aim task reads the switch; the catapult, which senses no target, does not.
    assert_ne!(with(TaskKind::Aim, &blind), with(TaskKind::Aim, &plain));
    assert_eq!(
        with(TaskKind::Catapult, &blind),
        with(TaskKind::Catapult, &plain)
    );
    // A creature with a projectile of its own is another creature to evaluate.
    let thrower = Creature {
        projectile: Some([0.3, 0.05, 0.3]),
        ..creature()
    };
    let spec = TaskSpec::new(TaskKind::Catapult);
    assert_ne!(
        EvaluationKey::of(&thrower, &spec),
        EvaluationKey::of(&c, &spec)
    );
}
