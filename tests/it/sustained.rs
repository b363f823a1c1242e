//! `ontogeny runs sustained`: Chaumont et al. 3.5's check of whether champions go on walking
//! after the time they were evolved for.

use crate::util::{assert_bad_input, ontogeny_ok, scratch_dir, stdout, tiny_run};

#[test]
fn each_champion_walks_longer_and_is_said_to_have_stopped_or_not() {
    let dir = scratch_dir("sustained-runs");
    let run = dir.join("seed-1");
    tiny_run("graph", &run, &["--seed", "1"]);
    let said = stdout(&ontogeny_ok(&[
        "runs",
        "sustained",
        dir.to_str().unwrap(),
        "--seconds",
        "3",
        "--window",
        "1",
    ]));
    assert!(
        said.starts_with(
            "each champion walked 3 s; stopped: its root moved less than 0.1 m in the last 1 s"
        ),
        "{said}"
    );
    let row = said.lines().find(|l| l.contains("seed-1")).unwrap();
    let cells: Vec<&str> = row.split('\t').collect();
    assert_eq!(cells.len(), 9, "{row}");
    // Stopped exactly when its root moved less than 0.1 m in the last second (or it failed).
    let last: f64 = cells[6].parse().unwrap();
    let stopped = cells[7] == "yes";
    assert_eq!(stopped, cells[8] != "ok" || last < 0.1, "{row}");
    assert!(said.contains("stopped: "), "{said}");
    // The JSON form carries the same walk.
    let json: serde_json::Value = serde_json::from_str(&stdout(&ontogeny_ok(&[
        "runs",
        "sustained",
        run.to_str().unwrap(),
        "--seconds",
        "3",
        "--window",
        "1",
        "--json",
    ])))
    .unwrap();
    assert_eq!(json["settings"]["seconds"], 3.0);
    assert_eq!(json["walks"][0]["stopped"], stopped);
    assert_eq!(json["walks"][0]["status"], cells[8]);
}

#[test]
fn a_window_longer_than_the_walk_or_no_run_is_refused() {
    let dir = scratch_dir("sustained-bad");
    assert_bad_input(
        &[
            "runs",
            "sustained",
            dir.to_str().unwrap(),
            "--seconds",
            "5",
            "--window",
            "6",
        ],
        "--window must be in (0, --seconds = 5], not 6",
    );
    assert_bad_input(
        &["runs", "sustained", dir.to_str().unwrap()],
        "holds no run",
    );
}

#[test]
fn a_champion_the_run_stored_invalid_by_its_creature_limits_is_walked_invalid() {
    // Four walkers from a grammar of three parts in a row and 4 neurons, under
    // `max_neurons = 2` and `max_chain = 2`: the run stores every one of them invalid (the
    // seed and its mutants all break one key or the other), so its champion is invalid, and
    // `replay` says so. Its long walk must be invalid too, not a walk of the creature as if
    // the run had set no limits.
    let dir = scratch_dir("sustained-limits");
    let seed = dir.join("row.lsys");
    std::fs::write(
        &seed,
        "derivation length: 1\naxiom: P0(0, 0)\n\nP0(n0, n1) --> forward(1) revolute2 \
         forward(1) output(1) twist90 forward(1) output(1) touch\n",
    )
    .unwrap();
    let config = dir.join("limits.toml");
    std::fs::write(
        &config,
        format!(
            "encoding = \"lsystem\"\nseed = 3\ninit = \"{}\"\n[ga]\npopulation = 4\n\
             generations = 1\n[task]\ntask = \"walker\"\n[task.walker]\nseconds = 2\n\
             [limits]\nmax_neurons = 2\nmax_chain = 2\n",
            seed.display()
        ),
    )
    .unwrap();
    let run = dir.join("run");
    crate::util::evolve(&config, &run, &[]);
    let statuses: Vec<String> =
        ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite"))
            .unwrap()
            .individuals(0)
            .unwrap()
            .into_iter()
            .map(|i| i.status)
            .collect();
    assert!(statuses.iter().all(|s| s == "invalid"), "{statuses:?}");
    let json: serde_json::Value = serde_json::from_str(&stdout(&ontogeny_ok(&[
        "runs",
        "sustained",
        run.to_str().unwrap(),
        "--seconds",
        "3",
        "--window",
        "1",
        "--json",
    ])))
    .unwrap();
    let walk = &json["walks"][0];
    assert_eq!(walk["status"], "invalid", "{walk}");
    assert_eq!(walk["stopped"], true, "{walk}");
}
