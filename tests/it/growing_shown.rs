//! Showing a creature that grows while it walks: the recording holds the parts as they
//! appear and grow, `replay` and `behaviour.gif` draw them, and a recording made before bodies
//! could grow still reads.

use std::path::{Path, PathBuf};

use ontogeny::task::{BodyChange, Recording};

use crate::util::{ontogeny, scratch_dir, stderr, succeeded};

const EXAMPLE: &str = "examples/grow-while-walking.lsys";
const OLD: &str = "tests/fixtures/old-recording";

/// `eval --record` of the example growing during a 3 s walk, into a fresh scratch folder
/// named after `name`, with the flags `extra`; the folder and what the command printed.
fn record_growing(name: &str, extra: &[&str]) -> (PathBuf, std::process::Output) {
    let dir = scratch_dir(&format!("growing-shown-{name}")).join("rec");
    let mut args = vec![
        "eval",
        EXAMPLE,
        "--develop",
        "during",
        "--seconds",
        "3",
        "--record",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = ontogeny(&args);
    succeeded(&out);
    (dir, out)
}

/// [`record_growing`] with no more flags; the folder.
pub(crate) fn growing_recording(name: &str) -> PathBuf {
    let (dir, out) = record_growing(name, &[]);
    assert!(stderr(&out).contains("behaviour.gif"), "{}", stderr(&out));
    dir
}

fn read(dir: &Path) -> Recording<'static> {
    serde_json::from_str(&std::fs::read_to_string(dir.join("recording.json")).unwrap()).unwrap()
}

/// A copy of the old recording in a fresh scratch folder named after `name`.
pub(crate) fn old_recording(name: &str) -> PathBuf {
    let dir = scratch_dir(&format!("growing-shown-old-{name}")).join("rec");
    std::fs::create_dir_all(&dir).unwrap();
    for file in ["recording.json", ".ontogeny-recording"] {
        std::fs::copy(Path::new(OLD).join(file), dir.join(file)).unwrap();
    }
    dir
}

#[test]
fn a_growing_walk_records_its_parts_as_they_appear_and_grow_and_reads_back() {
    let dir = growing_recording("round-trip");
    let text = std::fs::read_to_string(dir.join("recording.json")).unwrap();
    let recording = read(&dir);
    assert!(recording.grows());
    assert_eq!(recording.check_growth(), Ok(()));
    // Dropped as three segments; twelve leg parts appear during the walk (four legs of a
    // shoulder, a hip and a lower leg).
    assert_eq!(recording.creature.parts.len(), 3);
    let counts: Vec<usize> = recording.samples.iter().map(|s| s.parts.len()).collect();
    assert_eq!(counts.first(), Some(&3));
    assert_eq!(counts.last(), Some(&15));
    assert!(counts.windows(2).all(|w| w[0] <= w[1]));
    let appeared: Vec<usize> = recording
        .samples
        .iter()
        .flat_map(|s| &s.growth)
        .filter_map(|c| match c {
            BodyChange::Appears { part, joint, .. } => {
                assert_eq!(joint.child, part.0);
                Some(part.0)
            }
            _ => None,
        })
        .collect();
    assert_eq!(appeared, (3..15).collect::<Vec<_>>());
    // Each part appears in the first sample that poses it.
    for (i, sample) in recording.samples.iter().enumerate().skip(1) {
        let new = sample
            .growth
            .iter()
            .filter(|c| matches!(c, BodyChange::Appears { .. }))
            .count();
        assert_eq!(
            recording.samples[i - 1].parts.len() + new,
            sample.parts.len()
        );
    }
    // The shoulders (parts 3 and 4, then 9 and 10) appear whole, 0.2 m long; the hips and
    // lower legs lengthen as the grammar says, 0.4 a unit of developmental time up to
    // 0.35 m: the activation's second and the 3 s walk take development to t = 4, past the
    // end of both pairs' growth (t = 2.375 and 2.875, a little later where a leg pressed on
    // the ground stopped growing for a step).
    let mut bodies = recording.bodies();
    let last = bodies.at(recording.samples.len() - 1).clone();
    assert_eq!(last.parts.len(), 15);
    assert_eq!(last.joints.len(), 14);
    for (id, leg) in last.parts.iter().enumerate().skip(3) {
        let length = if [3, 4, 9, 10].contains(&id) {
            0.2
        } else {
            0.35
        };
        assert!(
            (leg.size.x - length).abs() < 1e-9,
            "part {id}: {}",
            leg.size
        );
    }
    // The first sample of the first pair's hips and lower legs shows them one step long:
    // 0.4 × 1/60 m.
    let first = recording
        .samples
        .iter()
        .position(|s| s.parts.len() == 9)
        .unwrap();
    for id in 5..9 {
        assert!((bodies.at(first).parts[id].size.x - 0.4 / 60.0).abs() < 1e-9);
    }
    assert_eq!(bodies.at(0).parts.len(), 3);
    // Written again, the same text: nothing is lost in the round trip.
    assert_eq!(serde_json::to_string(&recording).unwrap(), text);
}

#[test]
fn replay_draws_a_growing_recording_and_a_recording_made_before_bodies_grew() {
    for dir in [growing_recording("replay"), old_recording("replay")] {
        std::fs::remove_file(dir.join("behaviour.gif")).ok();
        let out = ontogeny(&["replay", dir.to_str().unwrap()]);
        succeeded(&out);
        let gif = std::fs::read(dir.join("behaviour.gif")).unwrap();
        assert!(gif.starts_with(b"GIF89a"));
    }
    // The old recording reads as it was: no growth, its creature's two parts in every frame.
    let old = read(&old_recording("read"));
    assert!(!old.grows());
    assert!(old.samples.iter().all(|s| s.parts.len() == 2));
    assert_eq!(old.samples.len(), 72);
}

#[test]
fn a_recording_whose_growth_names_a_part_out_of_turn_is_refused_with_exit_code_2() {
    let dir = growing_recording("bad");
    let path = dir.join("recording.json");
    let text = std::fs::read_to_string(&path).unwrap();
    // The first part to appear says it is part 16.
    let bad = text.replacen(r#"{"appears":{"part":3,"#, r#"{"appears":{"part":16,"#, 1);
    assert_ne!(bad, text);
    std::fs::write(&path, bad).unwrap();
    let out = ontogeny(&["replay", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let said = stderr(&out);
    assert!(
        said.contains("not a usable growth: frame ")
            && said.contains("part 16 appears, but the next part is 3"),
        "{said}"
    );
}

/// `xml` with every number in its attributes rounded to 9 decimals.
fn rounded(xml: &str) -> String {
    xml.split('"')
        .map(|field| {
            field
                .split(' ')
                .map(|w| match w.parse::<f64>() {
                    Ok(x) => format!("{x:.9}"),
                    Err(_) => w.to_string(),
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("\"")
}

#[test]
fn export_writes_the_creature_at_a_developmental_time_as_a_walk_would_drop_it() {
    // The creature a walk with develop_t0 = 2 drops: three segments, the first pair of legs
    // half grown and the second pair's shoulders, sprouted at t = 2.
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let lsys = std::sync::Arc::new(ontogeny::lsystem::LSystem::from_text(EXAMPLE, &text).unwrap());
    let growing = ontogeny::task::Growing::start(
        lsys,
        &ontogeny::lsystem::DeriveOptions::default(),
        &ontogeny::develop::BuildOptions::default(),
        1.0,
        Some(2.0),
    )
    .unwrap();
    assert_eq!(growing.creature().parts.len(), 11);
    let expected = ontogeny::export::to_mjcf_in(
        growing.creature(),
        &ontogeny::sim::SimOptions::default(),
        "grow-while-walking",
        &ontogeny::sim::WorldSpec::default(),
    )
    .unwrap();
    let out = ontogeny(&["export", EXAMPLE, "--time", "2"]);
    // The same model, to the round-off of integrating development in other steps.
    assert_eq!(rounded(&succeeded(&out)), rounded(&expected));
    // Each of the four shoulders, and each hip and lower leg of the first pair, half grown at
    // t = 2, is 0.2 m long (its half-size 0.1 m) and 0.15 m across.
    assert_eq!(
        rounded(&expected)
            .matches("size=\"0.100000000 0.075000000 0.075000000\"")
            .count(),
        8
    );
    assert!(
        stderr(&out).contains(
            "note: MJCF has no growth: the model is the creature at developmental time 2 \
             (choose another moment with --time T); in MuJoCo it does not grow"
        ),
        "{}",
        stderr(&out)
    );
    // A grammar in discrete steps says nothing of growth.
    let out = ontogeny(&["export", "examples/quadruped.lsys"]);
    succeeded(&out);
    assert!(!stderr(&out).contains("growth"), "{}", stderr(&out));
}

#[test]
fn a_growing_walk_records_the_neurons_and_links_its_terms_count() {
    let (dir, out) = record_growing("brain", &["--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let recording = read(&dir);
    assert_eq!(recording.check_growth(), Ok(()));
    let changes: Vec<&BodyChange> = recording.samples.iter().flat_map(|s| &s.growth).collect();
    let neurons: Vec<usize> = changes
        .iter()
        .filter_map(|c| match c {
            BodyChange::Neuron { neuron, .. } => Some(*neuron),
            _ => None,
        })
        .collect();
    let links = changes
        .iter()
        .filter(|c| matches!(c, BodyChange::Link { .. }))
        .count();
    // Each hip and lower leg brings its output neuron and the link that feeds it (a
    // shoulder, fused to the body, drives nothing).
    assert_eq!(json["terms"]["grown_neurons"], 8.0);
    assert_eq!(json["terms"]["grown_links"], 8.0);
    let dropped = recording.creature.brain.neurons.len();
    assert_eq!(neurons, (dropped..dropped + 8).collect::<Vec<_>>());
    assert_eq!(links, 8);
    let last = recording.bodies().at(recording.samples.len() - 1).clone();
    assert_eq!(last.brain.neurons.len(), dropped + 8);
    assert_eq!(
        last.brain.links.len(),
        recording.creature.brain.links.len() + 8
    );
    assert_eq!(last.check_consistency(), Ok(()));
}
