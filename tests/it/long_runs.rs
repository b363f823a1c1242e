//! Long runs: recordings keep at most `MAX_RECORDED_FRAMES` evenly spaced frames, written
//! compactly; evaluations and derivations tell a progress callback how far they are; the
//! command line shows no progress when standard error is not a terminal.

use crate::util::{grown, ontogeny_reading};

use nalgebra::{UnitQuaternion, Vector3};
use ontogeny::creature::Creature;
use ontogeny::sim::SimOptions;
use ontogeny::task::{
    self, CatapultOptions, JumpOptions, MAX_RECORDED_FRAMES, RecordedFrame, Status, TaskKind,
    TaskOptions, TaskSpec, WalkerOptions, recording_interval,
};

fn passive_pair() -> Creature {
    ontogeny::develop::creature_from_commands("forward(1) revolute2 forward(1)").unwrap()
}

#[test]
fn the_recording_interval_by_hand() {
    assert_eq!(MAX_RECORDED_FRAMES, 12_000);
    assert_eq!(recording_interval(0), 1);
    assert_eq!(recording_interval(12_000), 1);
    // 12,001 steps: every other one (steps 1, 3, ..., 12,001: 6,001 frames).
    assert_eq!(recording_interval(12_001), 2);
    // ⌈23,998 / 11,999⌉ = 2 keeps 11,999 steps and the last: 12,000.
    assert_eq!(recording_interval(23_998), 2);
    assert_eq!(recording_interval(23_999), 3);
}

#[test]
fn the_longest_runs_by_hand() {
    let dt = 1.0 / 60.0;
    // Two waits for rest of at most 600 + 1 steps, 60 steps (1 s) of activation, 1200 of
    // walking.
    assert_eq!(WalkerOptions::default().max_steps(dt), 2 * 601 + 60 + 1200);
    // Every step of the default walker is recorded.
    assert_eq!(
        recording_interval(WalkerOptions::default().max_steps(dt)),
        1
    );
    // An hour's walk: 217,262 steps, one in ⌈217,262 / 11,999⌉ = 19 kept.
    let hour = WalkerOptions {
        seconds: 3600.0,
        ..WalkerOptions::default()
    };
    assert_eq!(hour.max_steps(dt), 2 * 601 + 60 + 216_000);
    assert_eq!(recording_interval(hour.max_steps(dt)), 19);
    assert_eq!(JumpOptions::default().max_steps(dt), 601 + 600);
    assert_eq!(CatapultOptions::default().max_steps(dt), 3600);
    // At 1/10 s: 2 × 101 + 10 + 36,000 = 36,212.
    assert_eq!(hour.max_steps(0.1), 36_212);
    // A duration out of range (refused by the task) does not overflow the count.
    let endless = WalkerOptions {
        seconds: f64::INFINITY,
        ..WalkerOptions::default()
    };
    assert_eq!(endless.max_steps(dt), usize::MAX);
}

#[test]
fn a_short_run_keeps_every_step() {
    let sim = SimOptions::default();
    let options = WalkerOptions {
        seconds: 2.0,
        ..WalkerOptions::default()
    };
    let e = task::walker(&passive_pair(), &sim, &options, true);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let end = e.terms["measured_from"] + 2.0;
    let steps = (end / sim.control_step).round() as usize;
    assert_eq!(e.recording.len(), steps);
    for (i, frame) in e.recording.iter().enumerate() {
        assert!(
            (frame.t - (i + 1) as f64 * sim.control_step).abs() < 1e-9,
            "{i}: {}",
            frame.t
        );
    }
}

#[test]
fn a_long_run_keeps_at_most_the_bound_evenly_spaced_first_and_last_included() {
    // An hour's walk at 1/10 s per step (36,000 steps of walking and the waits for rest):
    // one step in 4 is kept.
    let sim = SimOptions {
        control_step: 0.1,
        ..SimOptions::default()
    };
    let options = WalkerOptions {
        seconds: 3600.0,
        ..WalkerOptions::default()
    };
    let interval = recording_interval(options.max_steps(sim.control_step));
    assert_eq!(interval, 4);
    let e = task::walker(&passive_pair(), &sim, &options, true);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    let frames = &e.recording;
    assert!(frames.len() <= MAX_RECORDED_FRAMES, "{}", frames.len());
    // The steps taken: to the end of the measured walk.
    let end = e.terms["measured_from"] + 3600.0;
    let steps = (end / sim.control_step).round() as usize;
    assert_eq!(
        frames.len(),
        steps.div_ceil(interval) + usize::from(!(steps - 1).is_multiple_of(interval))
    );
    // The first step, then every 4th, evenly 0.4 s apart; the last step closes the recording.
    assert!((frames[0].t - 0.1).abs() < 1e-9, "{}", frames[0].t);
    let spacing = interval as f64 * sim.control_step;
    let (last, evenly) = frames.split_last().unwrap();
    for pair in evenly.windows(2) {
        assert!(
            (pair[1].t - pair[0].t - spacing).abs() < 1e-6,
            "{} {}",
            pair[0].t,
            pair[1].t
        );
    }
    assert!((last.t - end).abs() < 1e-6, "{} {end}", last.t);
    let gap = last.t - evenly.last().unwrap().t;
    assert!(gap > 0.0 && gap < spacing + 1e-6, "{gap}");
}

#[test]
fn progress_grows_by_thousandths_to_one_and_changes_nothing() {
    let sim = SimOptions::default();
    let c = grown("examples/snake.lsys");
    let options = WalkerOptions {
        seconds: 2.0,
        ..WalkerOptions::default()
    };
    let mut told = Vec::new();
    let walk = TaskSpec {
        task: TaskOptions::Walker(options.clone()),
        ..TaskSpec::new(TaskKind::Walker)
    };
    let watched = walk.evaluate_with_progress(&c, false, &mut |f| told.push(f));
    let plain = task::walker(&c, &sim, &options, false);
    assert_eq!(watched, plain);
    assert_eq!(*told.last().unwrap(), 1.0);
    assert!(told.windows(2).all(|w| w[0] < w[1]), "{told:?}");
    assert!(told[0] >= 0.0);
    assert_eq!(told.iter().filter(|&&f| f == 1.0).count(), 1);
    // 2 s of walking are 120 of the run's 2 × 601 + 9 + 120 steps at most: the walk alone
    // tells at least 80 fractions.
    assert!(told.len() > 80, "{}", told.len());

    // The catapult ends when the projectile rests: 1 then.
    let mut told = Vec::new();
    let thrower = grown("examples/thrower.lsys");
    let e = TaskSpec::new(TaskKind::Catapult)
        .evaluate_with_progress(&thrower, false, &mut |f| told.push(f));
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    assert_eq!(*told.last().unwrap(), 1.0);
    assert!(told.windows(2).all(|w| w[0] < w[1]));

    // A rejected creature is not simulated, and is done at once.
    let mut told = Vec::new();
    let empty = Creature::default();
    let e =
        TaskSpec::new(TaskKind::Jump).evaluate_with_progress(&empty, false, &mut |f| told.push(f));
    assert_eq!(e.status, Status::Invalid);
    assert_eq!(told, [1.0]);
}

#[test]
fn growth_tells_the_fraction_of_frames_built() {
    let lsys = crate::util::lsystem("axiom: A\nderivation length: 4\nA --> forward(1) A\n");
    let mut told = Vec::new();
    let frames = ontogeny::develop::grow_with_progress(
        &lsys,
        &Default::default(),
        None,
        &Default::default(),
        &mut |f| told.push(f),
    )
    .unwrap();
    assert_eq!(frames.len(), 5);
    assert_eq!(told, [0.0, 0.25, 0.5, 0.75, 1.0]);
    // Continuous time: frames at 0, 0.3, 0.6, 0.9 and the final time 1.
    let lsys = crate::util::lsystem("axiom: A(0)\ntime: 1\ndt: 0.3\nA(x) --> solve dx/dt = 1\n");
    let mut fractions = Vec::new();
    lsys.for_each_frame(&Default::default(), None, |frame| {
        fractions.push(frame.fraction());
        Ok::<(), ontogeny::lang::Diagnostic>(())
    })
    .unwrap();
    assert_eq!(fractions, [0.0, 0.25, 0.5, 0.75, 1.0]);
}

#[test]
fn poses_are_written_at_f32_precision() {
    let frame = RecordedFrame {
        t: 0.1,
        phase: Some(ontogeny::task::Phase::Measuring),
        parts: vec![(
            // 0.3 as rapier's f32 computes it, widened to f64.
            Vector3::new(0.1, 0.3f32 as f64, -1.5),
            UnitQuaternion::identity(),
        )],
        projectile: Some(Vector3::new(2.0, 0.1f32 as f64, 0.0)),
        projectile_size: None,
        objects: Vec::new(),
        growth: Vec::new(),
    };
    let text = serde_json::to_string(&frame).unwrap();
    assert_eq!(
        text,
        r#"{"t":0.1,"phase":"measuring","parts":[[[0.1,0.3,-1.5],[0.0,0.0,0.0,1.0]]],"projectile":[2.0,0.1,0.0]}"#
    );
    // Read back, it is the frame to f32 precision.
    let back: RecordedFrame = serde_json::from_str(&text).unwrap();
    assert!((back.parts[0].0.y - frame.parts[0].0.y).abs() < 1e-7);
    assert_eq!(back.parts[0].1, frame.parts[0].1);
}

#[test]
fn an_hours_recording_off_a_terminal_says_its_rate_and_shows_no_progress() {
    let dir = crate::util::scratch_dir("long-runs-hour").join("recording");
    // An hour's jump at 1/10 s per step: at most 101 + 36,000 steps, one in 4 recorded.
    let out = ontogeny_reading(
        &[
            "eval",
            "-",
            "--task",
            "jump",
            "--seconds",
            "3600",
            "--time-step",
            "0.1",
            "--record",
            dir.to_str().unwrap(),
        ],
        b"axiom: forward(1) revolute2 forward(1)\n",
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "recording.json keeps one step in 4 (a frame every 0.400 s), to stay under 12000 frames"
        ),
        "{stderr}"
    );
    // Standard error is a pipe: notes only, no progress bar.
    assert!(
        !stderr.contains('\r') && !stderr.contains('%') && !stderr.contains('█'),
        "{stderr:?}"
    );
    assert!(
        stderr
            .lines()
            .all(|l| l.starts_with("note: ") || l.starts_with("wrote ")),
        "{stderr}"
    );
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("recording.json")).unwrap())
            .unwrap();
    let frames = recording["frames"].as_array().unwrap();
    assert!(
        frames.len() <= MAX_RECORDED_FRAMES && frames.len() > 9000,
        "{}",
        frames.len()
    );
    let last = frames.last().unwrap()["t"].as_f64().unwrap();
    assert!(last > 3600.0, "{last}");
    // (tests/it/cli.rs replays a recording written the same way.)
    std::fs::remove_dir_all(&dir).unwrap();
}
