//! Every `[limits]` key of every encoding checked against its documented range when a
//! configuration is read: a value out of range exits with code 2 and a message that names
//! the key, the range, and the file, line and column where the file sets it.

use ontogeny::encoding::{CheckedLimits, LSystemGenome, LSystemLimits};
use ontogeny::evolve::ga::{GaSettings, Preset};
use ontogeny::lang::Source;
use ontogeny::run::config::{RunConfig, read_run_config};
use ontogeny::task::{TaskKind, TaskSpec};

use crate::util::{evolve_config, refused, scratch_dir};

/// Every key's value just outside its range, low and high where it has both, with the
/// message that names it: (encoding, key = value, the message after `[limits] `).
const OUT_OF_RANGE: &[(&str, &str, &str)] = &[
    (
        "lsystem",
        "max_productions = 0",
        "max_productions must be 1 to 64, not 0",
    ),
    (
        "lsystem",
        "max_productions = 65",
        "max_productions must be 1 to 64, not 65",
    ),
    (
        "lsystem",
        "max_pairs = 0",
        "max_pairs must be 1 to 16, not 0",
    ),
    (
        "lsystem",
        "max_pairs = 17",
        "max_pairs must be 1 to 16, not 17",
    ),
    (
        "lsystem",
        "params = 1000",
        "params must be 0 to 8, not 1000",
    ),
    (
        "lsystem",
        "max_successor = 0",
        "max_successor must be 1 to 256, not 0",
    ),
    (
        "lsystem",
        "max_successor = 100000000",
        "max_successor must be 1 to 256, not 100000000",
    ),
    (
        "lsystem",
        "derivation_length = 1000000000",
        "derivation_length must be 0 to 64, not 1000000000",
    ),
    (
        "lsystem",
        "max_modules = 0",
        "max_modules must be 1 to 100000, not 0",
    ),
    (
        "lsystem",
        "max_modules = 100001",
        "max_modules must be 1 to 100000, not 100001",
    ),
    (
        "lsystem",
        "max_parts = 0",
        "max_parts must be 1 to 1000, not 0",
    ),
    (
        "lsystem",
        "max_parts = 1001",
        "max_parts must be 1 to 1000, not 1001",
    ),
    (
        "lsystem-continuous",
        "max_rules = 0",
        "max_rules must be 1 to 64, not 0",
    ),
    (
        "lsystem-continuous",
        "max_rules = 65",
        "max_rules must be 1 to 64, not 65",
    ),
    (
        "lsystem-continuous",
        "control_tokens = 27",
        "control_tokens must be 0 to 26, not 27",
    ),
    (
        "lsystem-continuous",
        "max_axiom = 0",
        "max_axiom must be 1 to 256, not 0",
    ),
    (
        "lsystem-continuous",
        "max_axiom = 257",
        "max_axiom must be 1 to 256, not 257",
    ),
    (
        "lsystem-continuous",
        "max_successor = 257",
        "max_successor must be 0 to 256, not 257",
    ),
    (
        "lsystem-continuous",
        "max_growers = 9",
        "max_growers must be 0 to 8, not 9",
    ),
    (
        "lsystem-continuous",
        "time = 0",
        "time must be in (0, 1000], not 0",
    ),
    (
        "lsystem-continuous",
        "time = 1e9",
        "time must be in (0, 1000], not 1000000000",
    ),
    (
        "lsystem-continuous",
        "time = nan",
        "time must be in (0, 1000], not NaN",
    ),
    (
        "lsystem-continuous",
        "dt = 1e-9",
        "dt must be in [0.0004, 4], not 0.000000001",
    ),
    (
        "lsystem-continuous",
        "dt = 5",
        "dt must be in [0.0004, 4], not 5",
    ),
    (
        "lsystem-continuous",
        "min_threshold = 0",
        "min_threshold must be in (0, 10], not 0",
    ),
    (
        "lsystem-continuous",
        "max_threshold = 11",
        "max_threshold must be in [0.2, 10], not 11",
    ),
    (
        "lsystem-continuous",
        "max_threshold = 0.1",
        "max_threshold must be in [0.2, 10], not 0.1",
    ),
    (
        "lsystem-continuous",
        "min_duration = 0.001",
        "min_duration must be in [0.01, 1000], not 0.001",
    ),
    (
        "lsystem-continuous",
        "max_duration = 0.5",
        "max_duration must be in [1, 1000], not 0.5",
    ),
    (
        "lsystem-continuous",
        "max_duration = inf",
        "max_duration must be in [1, 1000], not inf",
    ),
    (
        "lsystem-continuous",
        "max_parts = 1",
        "max_parts must be 2 to 1000, not 1",
    ),
    (
        "lsystem-continuous",
        "max_modules = 11",
        "max_modules must be 12 to 100000, not 11",
    ),
    (
        "lsystem-continuous",
        "max_modules = 100001",
        "max_modules must be 12 to 100000, not 100001",
    ),
    (
        "direct",
        "max_modules = 0",
        "max_modules must be 1 to 100000, not 0",
    ),
    (
        "direct",
        "max_modules = 100001",
        "max_modules must be 1 to 100000, not 100001",
    ),
    (
        "direct",
        "max_parts = 0",
        "max_parts must be 1 to 1000, not 0",
    ),
    (
        "direct",
        "random_length = 0",
        "random_length must be 1 to 1000, not 0",
    ),
    (
        "direct",
        "random_length = 1001",
        "random_length must be 1 to 1000, not 1001",
    ),
    (
        "graph",
        "max_nodes = 0",
        "max_nodes must be 1 to 100, not 0",
    ),
    (
        "graph",
        "max_nodes = 101",
        "max_nodes must be 1 to 100, not 101",
    ),
    (
        "graph",
        "max_parts = 0",
        "max_parts must be 1 to 1000, not 0",
    ),
    (
        "graph",
        "max_parts = 1001",
        "max_parts must be 1 to 1000, not 1001",
    ),
    (
        "graph",
        "max_connections = 17",
        "max_connections must be 0 to 16, not 17",
    ),
    (
        "graph",
        "max_recursion = 0",
        "max_recursion must be 1 to 16, not 0",
    ),
    (
        "graph",
        "max_recursion = 17",
        "max_recursion must be 1 to 16, not 17",
    ),
    (
        "graph",
        "max_local_neurons = 17",
        "max_local_neurons must be 0 to 16, not 17",
    ),
    (
        "graph",
        "max_global_neurons = 17",
        "max_global_neurons must be 0 to 16, not 17",
    ),
    (
        "graph",
        "max_inputs = 9",
        "max_inputs must be 0 to 8, not 9",
    ),
    (
        "graph",
        "regenerate_tries = 0",
        "regenerate_tries must be 1 to 100, not 0",
    ),
    (
        "graph",
        "regenerate_tries = 101",
        "regenerate_tries must be 1 to 100, not 101",
    ),
    (
        "lsystem",
        "max_neurons = 0",
        "max_neurons must be 1 to 10000, not 0",
    ),
    (
        "lsystem",
        "max_neurons = 10001",
        "max_neurons must be 1 to 10000, not 10001",
    ),
    (
        "lsystem",
        "max_chain = 0",
        "max_chain must be 1 to 1000, not 0",
    ),
    (
        "lsystem",
        "max_chain = 1001",
        "max_chain must be 1 to 1000, not 1001",
    ),
    (
        "lsystem-continuous",
        "max_neurons = 0",
        "max_neurons must be 1 to 10000, not 0",
    ),
    (
        "lsystem-continuous",
        "max_neurons = 10001",
        "max_neurons must be 1 to 10000, not 10001",
    ),
    (
        "lsystem-continuous",
        "max_chain = 0",
        "max_chain must be 1 to 1000, not 0",
    ),
    (
        "lsystem-continuous",
        "max_chain = 1001",
        "max_chain must be 1 to 1000, not 1001",
    ),
    (
        "direct",
        "max_neurons = 0",
        "max_neurons must be 1 to 10000, not 0",
    ),
    (
        "direct",
        "max_neurons = 10001",
        "max_neurons must be 1 to 10000, not 10001",
    ),
    (
        "direct",
        "max_chain = 0",
        "max_chain must be 1 to 1000, not 0",
    ),
    (
        "direct",
        "max_chain = 1001",
        "max_chain must be 1 to 1000, not 1001",
    ),
    (
        "graph",
        "max_neurons = 0",
        "max_neurons must be 1 to 10000, not 0",
    ),
    (
        "graph",
        "max_neurons = 10001",
        "max_neurons must be 1 to 10000, not 10001",
    ),
    (
        "graph",
        "max_chain = 0",
        "max_chain must be 1 to 1000, not 0",
    ),
    (
        "graph",
        "max_chain = 1001",
        "max_chain must be 1 to 1000, not 1001",
    ),
];

/// A one-generation config of `encoding` whose `[limits]` table (line 6) holds `line`.
fn config_with_limit(encoding: &str, line: &str) -> String {
    format!("encoding = \"{encoding}\"\n[ga]\npopulation = 4\ngenerations = 1\n[limits]\n{line}\n")
}

#[test]
fn every_limit_out_of_its_range_exits_2_naming_the_file_line_and_key() {
    let dir = scratch_dir("limits-out-of-range");
    for (i, (encoding, line, message)) in OUT_OF_RANGE.iter().enumerate() {
        let config = dir.join(format!("c{i}.toml"));
        std::fs::write(&config, config_with_limit(encoding, line)).unwrap();
        let run = dir.join(format!("run{i}"));
        let output = evolve_config(&config, &run);
        let column = line.find('=').unwrap() + 3;
        let said = refused(&output, &format!("[limits] {message}"));
        let place = format!("{}:6:{column}", config.display());
        assert!(
            said.contains(&place),
            "{encoding} {line}: {place} not in {said}"
        );
        assert!(!run.exists(), "{encoding} {line}: the run was started");
    }
}

#[test]
fn every_limits_key_of_every_encoding_has_a_range_checked() {
    // Each encoding's keys, as its default limits serialise them, all appear in the table.
    let keys =
        |value: toml::Value| -> Vec<String> { value.as_table().unwrap().keys().cloned().collect() };
    let encodings = [
        (
            "lsystem",
            keys(toml::Value::try_from(LSystemLimits::default()).unwrap()),
        ),
        (
            "lsystem-continuous",
            keys(toml::Value::try_from(ontogeny::encoding::ContinuousLimits::default()).unwrap()),
        ),
        (
            "direct",
            keys(toml::Value::try_from(ontogeny::encoding::DirectLimits::default()).unwrap()),
        ),
        (
            "graph",
            keys(toml::Value::try_from(ontogeny::encoding::GraphLimits::default()).unwrap()),
        ),
    ];
    for (encoding, keys) in encodings {
        for key in keys {
            // joint_kinds is a name: serde refuses any but its two.
            if key == "joint_kinds" {
                continue;
            }
            assert!(
                OUT_OF_RANGE
                    .iter()
                    .any(|(e, line, _)| *e == encoding && line.starts_with(&format!("{key} ="))),
                "{encoding}'s {key} has no out-of-range case"
            );
        }
    }
}

#[test]
fn a_run_directory_config_with_a_limit_out_of_range_is_refused_at_the_key() {
    let config = RunConfig {
        encoding: "lsystem".to_string(),
        seed: 1,
        init: None,
        verify_best: true,
        cache: true,
        ga: GaSettings::preset(Preset::Chaumont),
        task: TaskSpec::new(TaskKind::Walker),
        limits: LSystemLimits::default(),
    };
    let text = config
        .to_toml()
        .unwrap()
        .replace("params = 2", "params = 1000");
    let line = text.lines().position(|l| l == "params = 1000").unwrap() + 1;
    let source = Source::new("run/config.toml", text);
    let error = read_run_config::<<LSystemGenome as ontogeny::encoding::Genome>::Limits>(&source)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("[limits] params must be 0 to 8, not 1000"),
        "{error}"
    );
    assert!(
        error.contains(&format!("run/config.toml:{line}:10")),
        "{error}"
    );
    assert_eq!(LSystemLimits::default().check_ranges(), Ok(()));
}
