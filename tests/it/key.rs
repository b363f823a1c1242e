//! The evaluation key (`ontogeny::evolve::key`): pinned for a fixed creature and task, so that
//! a change of its byte form, which would orphan every stored evaluation, is deliberate; and
//! changed by every leaf of the task specification and its simulator settings, so that no
//! setting can stop reaching the key and give one cached evaluation to two different tasks.

use ontogeny::creature::Creature;
use ontogeny::evolve::key::EvaluationKey;
use ontogeny::task::{TaskKind, TaskSpec};
use serde_json::Value;

/// The fixed creature: two parts on a hinge, built from commands.
fn creature() -> Creature {
    ontogeny::develop::creature_from_commands("forward(1) revolute2 forward(1)").unwrap()
}

#[test]
fn the_key_of_a_fixed_creature_and_task_is_pinned() {
    let c = creature();
    let keys: Vec<String> = TaskKind::ALL
        .iter()
        .map(|&kind| EvaluationKey::of(&c, &TaskSpec::new(kind)).to_hex())
        .collect();
    assert_eq!(
        keys,
        [
            "706031de35c2dfaf481d4c16cb0674fcfbe83d70d96e1e0b1c84fd2a9082910a",
            "13d36160947225552d602ca3177b50cc1b5a3f697232d396b131f53a0ac2ea18",
            "879499ad7c9d1f14c7c5ee661fe19711bd06237a89fbec1be6d5988ea4be0768",
            "601770ea3402902d0ec528be1888410fd5926dcec257f18f6675811c88e95ce5",
        ]
    );
}

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
            let refusal = serde_json::from_value::<TaskSpec>(probe)
                .map(|_| String::new())
                .unwrap_or_else(|e| e.to_string());
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

#[test]
fn every_setting_of_the_task_and_the_simulator_changes_the_key() {
    let c = creature();
    for kind in TaskKind::ALL {
        let task = TaskSpec::new(kind);
        let key = EvaluationKey::of(&c, &task);
        let spec = serde_json::to_value(&task).unwrap();
        let mut found = Vec::new();
        leaves(&spec, "", &mut found);
        let mut unchanged = Vec::new();
        for pointer in &found {
            let original = spec.pointer(pointer).unwrap().clone();
            // The first replacement the task reads back with this leaf changed.
            let changed = replacements(&spec, pointer).into_iter().find_map(|value| {
                let mut edited = spec.clone();
                *edited.pointer_mut(pointer).unwrap() = value;
                let read: TaskSpec = serde_json::from_value(edited).ok()?;
                let back = serde_json::to_value(&read).unwrap();
                (back.pointer(pointer) != Some(&original)).then_some(read)
            });
            match changed {
                Some(read) if EvaluationKey::of(&c, &read) != key => {}
                Some(_) => unchanged.push(format!("{pointer}: the key did not change")),
                None => unchanged.push(format!("{pointer}: no other value reads back")),
            }
        }
        assert!(
            unchanged.is_empty(),
            "{kind:?}: {unchanged:#?}\nin {spec:#}"
        );
        assert_eq!(found, PINNED_LEAVES, "{kind:?}: the leaves of {spec:#}");
    }
}

/// The leaves of every task's specification, in order. A setting added to the task or the
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
