//! Continuous development does not depend on the observation step dt, to the end: the shipped
//! continuous examples grow the same creature at dt from 1 down to 1e-4, an event at the final
//! time is processed whatever the round-off, parts that are only round-off long are buds, and
//! the last frame is at the final time even when dt does not divide it.

use std::path::PathBuf;

use ontogeny::creature::Creature;
use ontogeny::develop::{BuildOptions, build};
use ontogeny::lsystem::{DeriveOptions, LSystem, ModuleString, Timing};

const DTS: [f64; 7] = [1.0, 0.5, 0.25, 0.1, 0.01, 0.001, 1e-4];

/// The final string, its time and the creature it builds.
struct End {
    t: f64,
    frames: u64,
    string: ModuleString,
    creature: Creature,
}

fn grow_to_the_end(lsys: &LSystem, options: &DeriveOptions) -> End {
    let mut dev = lsys.development(options).unwrap_or_else(|e| panic!("{e}"));
    while dev.advance().unwrap_or_else(|e| panic!("{e}")) {}
    let t = dev.time();
    let shown = lsys
        .interpret(dev.current(), t, options)
        .unwrap_or_else(|e| panic!("{e}"));
    End {
        t,
        frames: dev.frame_number(),
        string: dev.current().clone(),
        creature: build(
            &shown,
            lsys.symbols(),
            dev.environment(),
            Some(t),
            &BuildOptions::default(),
        ),
    }
}

/// Panics with `what` unless `a` and `b` are the same creature: the same parts (size and
/// position within 1e-6, growing or not), the same joints (kind, parts, growing or not), the
/// same numbers of neurons and links.
fn assert_same_creature(a: &Creature, b: &Creature, what: &str) {
    assert_eq!(a.parts.len(), b.parts.len(), "{what}: part count");
    for (k, (p, q)) in a.parts.iter().zip(&b.parts).enumerate() {
        assert!(
            (p.size - q.size).norm() < 1e-6,
            "{what}: part {k} size {} vs {}",
            p.size,
            q.size
        );
        assert!(
            (p.position - q.position).norm() < 1e-6,
            "{what}: part {k} position {} vs {}",
            p.position,
            q.position
        );
        assert_eq!(p.growing, q.growing, "{what}: part {k} growing");
    }
    assert_eq!(a.joints.len(), b.joints.len(), "{what}: joint count");
    for (k, (j, i)) in a.joints.iter().zip(&b.joints).enumerate() {
        assert_eq!(j.kind, i.kind, "{what}: joint {k} kind");
        assert_eq!(
            (j.parent, j.child),
            (i.parent, i.child),
            "{what}: joint {k}"
        );
        assert_eq!(j.growing, i.growing, "{what}: joint {k} growing");
    }
    assert_eq!(
        a.brain.neurons.len(),
        b.brain.neurons.len(),
        "{what}: neuron count"
    );
    assert_eq!(
        a.brain.links.len(),
        b.brain.links.len(),
        "{what}: link count"
    );
}

/// Panics unless the strings have the same modules with parameters within 1e-6.
fn assert_same_string(lsys: &LSystem, a: &ModuleString, b: &ModuleString, what: &str) {
    let (sa, sb) = (lsys.display(a), lsys.display(b));
    assert_eq!(a.len(), b.len(), "{what}: {sa} vs {sb}");
    for i in 0..a.len() {
        assert_eq!(a.sym(i), b.sym(i), "{what}: {sa} vs {sb}");
        for (x, y) in a.params(i).iter().zip(b.params(i)) {
            assert!((x - y).abs() < 1e-6, "{what}: {sa} vs {sb}");
        }
    }
}

fn continuous_examples() -> Vec<(PathBuf, LSystem)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir("examples").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "lsys") {
            let lsys = LSystem::from_path(&path).unwrap_or_else(|e| panic!("{e}"));
            if lsys.is_continuous() {
                out.push((path, lsys));
            }
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

#[test]
fn every_continuous_example_grows_the_same_creature_at_every_dt() {
    let examples = continuous_examples();
    let names: Vec<_> = examples
        .iter()
        .map(|(p, _)| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    // The test must not pass vacuously if the examples move.
    assert!(names.len() >= 3, "{names:?}");
    for name in ["plastic.lsys", "snake.lsys", "dl-figure1.lsys"] {
        assert!(names.iter().any(|n| n == name), "{name} in {names:?}");
    }
    for (path, lsys) in &examples {
        // Every environment the file declares, and the same slots all set to 1 (plastic.lsys:
        // the straight limb and the branching tree).
        let mut envs = vec![Vec::new()];
        let slots = lsys.environment().len();
        if slots > 0 {
            envs.push((0..slots).map(|i| (i, 1.0)).collect());
        }
        for env in envs {
            let options = |dt: f64| DeriveOptions {
                dt: Some(dt),
                env: env.clone(),
                // `timing: iterative` (dl-figure1.lsys) depends on dt by design.
                timing: Some(Timing::Exact),
                ..DeriveOptions::default()
            };
            let reference = grow_to_the_end(lsys, &options(DTS[0]));
            let time = lsys.time().unwrap();
            for dt in DTS {
                let what = format!("{} env {env:?} dt {dt}", path.display());
                let end = grow_to_the_end(lsys, &options(dt));
                assert_eq!(end.t, time, "{what}: the last frame is at the final time");
                assert_eq!(end.frames, (time / dt).round() as u64, "{what}");
                assert_same_string(lsys, &end.string, &reference.string, &what);
                assert_same_creature(&end.creature, &reference.creature, &what);
            }
        }
    }
}

#[test]
fn the_examples_final_creatures_by_hand() {
    // plastic.lsys grows one segment of length l per time unit: at t = 4 the fourth has just
    // matured and a bud follows it (poor: 4 rigid segments of 1 along x; rich: 1 + 2 + 4 + 8
    // segments of 1, 0.7, 0.49, 0.343), whatever dt.
    let plastic = LSystem::from_path("examples/plastic.lsys".as_ref()).unwrap();
    for dt in [1.0, 0.001, 1e-4] {
        let options = |rich: f64| DeriveOptions {
            dt: Some(dt),
            env: vec![(0, rich)],
            ..DeriveOptions::default()
        };
        let poor = grow_to_the_end(&plastic, &options(0.0)).creature;
        assert_eq!(poor.parts.len(), 4, "dt {dt}");
        for (k, p) in poor.parts.iter().enumerate() {
            assert!((p.position.x - (k as f64 + 0.5)).abs() < 1e-9, "dt {dt}");
            assert!((p.size.x - 1.0).abs() < 1e-9, "dt {dt}");
            assert!(!p.growing, "dt {dt}: part {k} has matured");
        }
        let rich = grow_to_the_end(&plastic, &options(1.0)).creature;
        assert_eq!(rich.parts.len(), 15, "dt {dt}");
        let mut lengths: Vec<f64> = rich.parts.iter().map(|p| p.size.x).collect();
        lengths.sort_by(f64::total_cmp);
        let mut expected: Vec<f64> = [(1.0, 1), (0.7, 2), (0.49, 4), (0.343, 8)]
            .iter()
            .flat_map(|&(l, n)| std::iter::repeat_n(l, n))
            .collect();
        expected.sort_by(f64::total_cmp);
        for (l, e) in lengths.iter().zip(&expected) {
            assert!((l - e).abs() < 1e-9, "dt {dt}: {lengths:?}");
        }
    }
}

#[test]
fn an_event_at_the_final_time_is_processed() {
    // X reaches 1 at t = 1 + 1e-12, within round-off of the final time: it belongs to the last
    // frame. At t = 1 + 1e-6 it is a real event after the end, and is not processed.
    for (limit, expected) in [("1 + 1e-12", "Y"), ("1 + 1e-6", "X")] {
        let text =
            format!("time: 1\naxiom: X(0)\nX(x) : x < {limit} --> solve dx/dt = 1\nX(x) --> Y\n");
        let lsys = LSystem::from_text("t.lsys", &text).unwrap();
        for dt in [1.0, 0.1, 1e-3, 1e-4] {
            let options = DeriveOptions {
                dt: Some(dt),
                ..DeriveOptions::default()
            };
            let end = grow_to_the_end(&lsys, &options);
            let shown = lsys.display(&end.string);
            assert!(
                shown.starts_with(expected),
                "limit {limit}, dt {dt}: {shown}"
            );
            assert_eq!(end.t, 1.0);
        }
    }
}

#[test]
fn the_last_frame_is_at_the_final_time_when_dt_does_not_divide_it() {
    let text = "time: 1\naxiom: X(0)\nX(x) : x < 10 --> solve dx/dt = 1\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    for (dt, times) in [
        (0.3, vec![0.0, 0.3, 0.6, 0.9, 1.0]),
        (0.4, vec![0.0, 0.4, 0.8, 1.0]),
        (1.0 / 3.0, vec![0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0]),
        (2.0, vec![0.0, 1.0]),
    ] {
        let options = DeriveOptions {
            dt: Some(dt),
            ..DeriveOptions::default()
        };
        let mut dev = lsys.development(&options).unwrap();
        assert_eq!(dev.frame_count() as usize, times.len() - 1, "dt {dt}");
        let mut seen = vec![(dev.time(), dev.current().params(0)[0])];
        while dev.advance().unwrap() {
            seen.push((dev.time(), dev.current().params(0)[0]));
        }
        assert_eq!(seen.len(), times.len(), "dt {dt}: {seen:?}");
        for ((t, x), want) in seen.iter().zip(&times) {
            assert!((t - want).abs() < 1e-12, "dt {dt}: {seen:?}");
            // dx/dt = 1 from 0: x is the time.
            assert!((x - want).abs() < 1e-9, "dt {dt}: {seen:?}");
        }
    }
    // time: 3, dt: 0.3 — 3 / 0.3 = 10.000000000000002 in floating point: 10 steps, not 11.
    let options = DeriveOptions {
        time: Some(3.0),
        dt: Some(0.3),
        ..DeriveOptions::default()
    };
    assert_eq!(lsys.development(&options).unwrap().frame_count(), 10);
}

#[test]
fn a_bud_born_just_before_the_final_time_is_not_built() {
    // X flips at t = 1 - d and becomes a bud growing at rate 1: at t = 1 it is d long. A
    // round-off length (d = 1e-10) is still a bud; d = 1e-5 is a part 1e-5 long.
    for (d, parts) in [("1e-10", 0), ("1e-5", 1)] {
        let text = format!(
            "time: 1\naxiom: X(0)\nX(x) : x < 1 - {d} --> solve dx/dt = 1\n\
             X(x) --> mforward(0)\nmforward(l) --> solve dl/dt = 1\n"
        );
        let lsys = LSystem::from_text("t.lsys", &text).unwrap();
        for dt in [1.0, 0.01] {
            let options = DeriveOptions {
                dt: Some(dt),
                ..DeriveOptions::default()
            };
            let end = grow_to_the_end(&lsys, &options);
            assert_eq!(
                end.creature.parts.len(),
                parts,
                "d {d}, dt {dt}: {}",
                lsys.display(&end.string)
            );
            if parts == 1 {
                assert!((end.creature.parts[0].size.x - 1e-5).abs() < 1e-9);
                assert!(end.creature.parts[0].growing);
            }
        }
    }
}
