//! The Python package's type stubs (`python/ontogeny/__init__.pyi`) against the library:
//! the task names, the task keywords and the walker's fitness formulas they spell are the
//! registry's, the simulator's keys they list the table of knobs'.

use ontogeny::sim::KNOBS;
use ontogeny::task::{TASKS, Task, WalkerFitness, WalkerTask, tasks_reading};

/// The stubs' text.
fn stubs() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/python/ontogeny/__init__.pyi"
    ))
    .unwrap()
}

/// The quoted names of the stubs' `ALIAS = Literal[...]`.
fn literal(stubs: &str, alias: &str) -> Vec<String> {
    let start = stubs
        .find(&format!("\n{alias} = Literal["))
        .unwrap_or_else(|| panic!("no {alias} = Literal[...] in the stubs"));
    let body = &stubs[start..];
    let body = &body[body.find('[').unwrap() + 1..body.find(']').unwrap()];
    body.split(',')
        .map(|name| name.trim().trim_matches('"').to_string())
        .filter(|name| !name.is_empty())
        .collect()
}

#[test]
fn the_stubs_name_the_registrys_tasks_and_the_walkers_formulas() {
    let stubs = stubs();
    let tasks: Vec<&str> = TASKS.iter().map(|t| t.name).collect();
    assert_eq!(literal(&stubs, "_Task"), tasks);
    assert_eq!(literal(&stubs, "_Fitness"), WalkerTask::FITNESS_VARIANTS);
    assert_eq!(
        WalkerFitness::ALL.map(WalkerFitness::name),
        WalkerTask::FITNESS_VARIANTS
    );
    // `evaluate` and `evaluate_many` take a task and a formula of those, or an expression.
    assert_eq!(stubs.matches("    task: _Task = \"walker\",").count(), 2);
    assert_eq!(
        stubs
            .matches("    fitness: Optional[Union[_Fitness, str]] = None,")
            .count(),
        2
    );
    assert!(stubs.contains("\nTASKS: Dict[str, str]\n"));
}

#[test]
fn the_stubs_take_and_name_the_registrys_task_keywords() {
    let stubs = stubs();
    let mut keywords: Vec<&str> = Vec::new();
    for task in TASKS {
        for keyword in task.keywords {
            if !keywords.contains(keyword) {
                keywords.push(keyword);
            }
        }
    }
    assert_eq!(keywords, ["seconds", "fitness", "target"]);
    // `evaluate` and `evaluate_many` take each.
    for keyword in &keywords {
        assert_eq!(
            stubs
                .matches(&format!("\n    {keyword}: Optional["))
                .count(),
            2,
            "{keyword}"
        );
    }
    // `evaluate`'s documentation names the tasks that read each, in the registry's words.
    let named: Vec<String> = keywords
        .iter()
        .map(|k| format!("``{k}`` ({})", tasks_reading(k)))
        .collect();
    let listed = format!("keywords: {}; one the task", named.join(", "));
    let flat = stubs.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(flat.contains(&listed), "no {listed:?} in the stubs");
}

#[test]
fn the_stubs_list_every_knob_s_key_in_the_table_s_order() {
    let stubs = stubs();
    let start = stubs
        .find("\n_Sim = Dict[str, Union[float, int, str, bool]]\n\"\"\"")
        .expect("no _Sim = Dict[...] in the stubs");
    let doc = &stubs[start..];
    let doc = &doc[doc.find("\"\"\"").unwrap() + 3..];
    let doc = &doc[..doc.find("\"\"\"").unwrap()];
    // The ``quoted`` words: the table, the named setting, then each key with its older name.
    let quoted: Vec<&str> = doc.split("``").skip(1).step_by(2).collect();
    let mut keys = vec!["[task.sim]", "setting"];
    for knob in KNOBS {
        keys.push(knob.key);
        keys.extend(knob.older_key);
    }
    assert_eq!(quoted, keys);
    // `evaluate` and `evaluate_many` take them.
    assert_eq!(stubs.matches("    sim: Optional[_Sim] = None,").count(), 2);
}
