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
