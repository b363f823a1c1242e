//! Continuous developmental time (dL-systems, Matos & Arita section 3.1) and open L-systems
//! (section 3.3), against the paper's listing and hand calculation.

use crate::util::squash;
use ontogeny::environment::Environment;
use ontogeny::lang::DiagnosticKind;
use ontogeny::lsystem::{DeriveOptions, LSystem, ModuleString, Timing};

const FIGURE_1: &str = "\
time: 3
axiom: B(1) A(0, 0)
B(x) : x < 4 --> solve dx/dt = 1
B(x) : x >= 4 --> A(2, 2) B(1)
A(x, y) : y < 2 --> solve dx/dt = 2, dy/dt = 1
A(x, y) : y >= 2 --> B(x) C(2)
";

/// One developed frame: time, symbols and parameters.
#[derive(Debug, Clone)]
struct Frame {
    t: f64,
    text: String,
    syms: Vec<String>,
    params: Vec<Vec<f64>>,
    env: Vec<f64>,
}

fn frame_of(lsys: &LSystem, t: f64, s: &ModuleString, env: &Environment) -> Frame {
    Frame {
        t,
        text: squash(&lsys.display(s)),
        syms: s
            .iter()
            .map(|m| lsys.symbols().name(m.sym).to_string())
            .collect(),
        params: s.iter().map(|m| m.params.to_vec()).collect(),
        env: env.values().to_vec(),
    }
}

fn develop(lsys: &LSystem, options: &DeriveOptions) -> Vec<Frame> {
    let mut dev = lsys.development(options).unwrap_or_else(|e| panic!("{e}"));
    let mut frames = vec![frame_of(lsys, dev.time(), dev.current(), dev.environment())];
    while dev.advance().unwrap_or_else(|e| panic!("{e}")) {
        frames.push(frame_of(lsys, dev.time(), dev.current(), dev.environment()));
    }
    frames
}

fn options(dt: f64, timing: Timing) -> DeriveOptions {
    DeriveOptions {
        dt: Some(dt),
        timing: Some(timing),
        ..DeriveOptions::default()
    }
}

fn texts(frames: &[Frame]) -> Vec<String> {
    frames.iter().map(|f| f.text.clone()).collect()
}

#[test]
fn iterative_timing_reproduces_the_papers_listing_for_figure_1() {
    let lsys = LSystem::from_text("fig1.lsys", FIGURE_1).unwrap();
    let frames = develop(&lsys, &options(1.0, Timing::Iterative));
    assert_eq!(
        texts(&frames)[..3],
        ["B(1)A(0,0)", "B(2)A(2,1)", "B(3)B(4)C(2)"]
    );
    let frames = develop(&lsys, &options(0.5, Timing::Iterative));
    assert_eq!(
        texts(&frames)[..3],
        ["B(1)A(0,0)", "B(1.5)A(1,0.5)", "B(2)A(2,1)"]
    );
}

#[test]
fn exact_timing_settles_at_events_by_hand_calculation() {
    // At t = 2, A(4,2) becomes B(4) C(2); B(4) at once becomes A(2,2) B(1), and A(2,2) at once
    // becomes B(2) C(2). At t = 3 the first B reaches 4 and becomes A(2,2) B(1) -> B(2) C(2) B(1).
    let lsys = LSystem::from_text("fig1.lsys", FIGURE_1).unwrap();
    let frames = develop(&lsys, &options(1.0, Timing::Exact));
    assert_eq!(
        texts(&frames),
        [
            "B(1)A(0,0)",
            "B(2)A(2,1)",
            "B(3)B(2)C(2)B(1)C(2)",
            "B(2)C(2)B(1)B(3)C(2)B(2)C(2)"
        ]
    );
}

#[test]
fn exact_timing_does_not_depend_on_dt() {
    let lsys = LSystem::from_text("fig1.lsys", FIGURE_1).unwrap();
    let reference = develop(&lsys, &options(0.1, Timing::Exact));
    for dt in [1.0, 0.5, 0.3, 0.7, 0.25, 0.9] {
        let frames = develop(&lsys, &options(dt, Timing::Exact));
        for f in &frames {
            let Some(r) = reference.iter().find(|r| (r.t - f.t).abs() < 1e-9) else {
                continue;
            };
            assert_eq!(f.syms, r.syms, "dt {dt}, t {}", f.t);
            for (a, b) in f.params.iter().flatten().zip(r.params.iter().flatten()) {
                assert!(
                    (a - b).abs() < 1e-6,
                    "dt {dt}, t {}: {} vs {}",
                    f.t,
                    f.text,
                    r.text
                );
            }
        }
        // Frames land on k * dt, including dt that do not divide the event times; the last is
        // at the final time, after a shorter step when dt does not divide it (0.7, 0.9).
        let (last, before) = frames.split_last().unwrap();
        assert_eq!(last.t, 3.0);
        for (k, f) in before.iter().enumerate() {
            assert!(
                (f.t - k as f64 * dt).abs() < 1e-12,
                "dt {dt}: frame {k} at {}",
                f.t
            );
        }
        assert!(3.0 - before.last().unwrap().t <= dt + 1e-12);
        let r = reference.last().unwrap();
        assert_eq!(last.syms, r.syms, "dt {dt}: {} vs {}", last.text, r.text);
    }
}

#[test]
fn an_axiom_that_satisfies_a_discrete_guard_is_rewritten_at_t_0() {
    let text = "time: 1\naxiom: B(5)\nB(x) : x < 4 --> solve dx/dt = 1\nB(x) : x >= 4 --> A B(0)\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    let exact = develop(&lsys, &options(1.0, Timing::Exact));
    assert_eq!(texts(&exact), ["AB(0)", "AB(1)"]);
    let iterative = develop(&lsys, &options(1.0, Timing::Iterative));
    assert_eq!(texts(&iterative), ["B(5)", "AB(1)"]);
}

#[test]
fn nonlinear_ode_event_is_located_at_ln_4() {
    let text = "time: 2\naxiom: X(1)\nX(x) : x < 4 --> solve dx/dt = x\nX(x) : x >= 4 --> Y(x)\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    for dt in [1.0, 0.3, 0.7] {
        let mut dev = lsys.development(&options(dt, Timing::Exact)).unwrap();
        let mut events = Vec::new();
        while dev.advance().unwrap() {
            events.extend(dev.take_events());
        }
        assert_eq!(events.len(), 1, "{events:?}");
        let ln4 = 4f64.ln();
        assert!(
            (events[0].t - ln4).abs() < 1e-9,
            "dt {dt}: event at {} vs ln 4 = {ln4}",
            events[0].t
        );
        assert_eq!(events[0].rule_line, Some(4));
        let y = dev.current().params(0)[0];
        assert!((y - 4.0).abs() < 1e-8, "{y}");
    }
}

#[test]
fn timed_observation_independence_abop_chapter_6() {
    // Timed modules are the case dage/dt = 1: D(D(x, 1.2), 1.3) = D(x, 2.5).
    let text = "\
time: 2.5
axiom: A(0)
A(age) : age < 1 --> solve dage/dt = 1
A(age) : age >= 1 --> I(0) [ B(0) ] A(age - 1)
B(age) : age < 0.7 --> solve dage/dt = 1
B(age) : age >= 0.7 --> L(0)
I(age) : age < 10 --> solve dage/dt = 1
L(age) : age < 10 --> solve dage/dt = 1
";
    let lsys = LSystem::from_text("timed.lsys", text).unwrap();
    let whole = lsys
        .development(&DeriveOptions {
            time: Some(2.5),
            dt: Some(2.5),
            ..DeriveOptions::default()
        })
        .unwrap();
    let mut whole = whole;
    while whole.advance().unwrap() {}
    let first = {
        let mut d = lsys
            .development(&DeriveOptions {
                time: Some(1.2),
                dt: Some(1.2),
                ..DeriveOptions::default()
            })
            .unwrap();
        while d.advance().unwrap() {}
        (d.current().clone(), d.environment().clone())
    };
    let mut second = lsys
        .development_from(
            first.0,
            1.2,
            first.1,
            &DeriveOptions {
                time: Some(1.3),
                dt: Some(1.3),
                ..DeriveOptions::default()
            },
        )
        .unwrap();
    while second.advance().unwrap() {}
    assert!((second.time() - 2.5).abs() < 1e-12);
    let a = frame_of(&lsys, 2.5, whole.current(), whole.environment());
    let b = frame_of(&lsys, 2.5, second.current(), second.environment());
    assert_eq!(a.syms, b.syms);
    for (x, y) in a.params.iter().flatten().zip(b.params.iter().flatten()) {
        assert!((x - y).abs() < 1e-9, "{} vs {}", a.text, b.text);
    }
    assert_eq!(a.text, "I(1.5)[L(0.8)]I(0.5)[B(0.5)]A(0.5)");
}

#[test]
fn environment_reads_and_writes_follow_string_order() {
    let text =
        "environment: 0 0\naxiom: ?E(0, 0, 7) ?E(1, 0, 0) ?E(0, 0, 9) ?E(1, 0, 0) ?E(1, 1, 5)\n";
    let lsys = LSystem::from_text("env.lsys", text).unwrap();
    let d = lsys.derivation(&DeriveOptions::default()).unwrap();
    let reads: Vec<f64> = d.current().iter().map(|m| m.params[2]).collect();
    assert_eq!(reads, [7.0, 7.0, 9.0, 9.0, 0.0]);
    assert_eq!(d.environment().values(), &[9.0, 0.0]);
}

#[test]
fn rules_read_the_environment_through_context_and_write_it() {
    let text = "\
environment: 0 0.5 0 0
axiom: A(1) ?E(1, 1, 0) S
A(x) > ?E(1, 1, c) : c > 0.3 --> forward(x) A(x)
S --> ?E(0, 2, 0.8) S
";
    let lsys = LSystem::from_text("env.lsys", text).unwrap();
    let mut d = lsys.derivation(&DeriveOptions::default()).unwrap();
    // The axiom's ?E read env[1] = 0.5 before the first step.
    assert_eq!(squash(&lsys.display(d.current())), "A(1)?E(1,1,0.5)S");
    d.step().unwrap();
    assert_eq!(
        squash(&lsys.display(d.current())),
        "forward(1)A(1)?E(1,1,0.5)?E(0,2,0.8)S"
    );
    assert_eq!(d.environment().values(), &[0.0, 0.5, 0.8, 0.0]);

    // Another environment, another development.
    let poor = DeriveOptions {
        env: vec![(1, 0.1)],
        ..DeriveOptions::default()
    };
    let mut d = lsys.derivation(&poor).unwrap();
    d.step().unwrap();
    assert_eq!(
        squash(&lsys.display(d.current())),
        "A(1)?E(1,1,0.1)?E(0,2,0.8)S"
    );
}

#[test]
fn an_environment_index_outside_the_array_names_the_rule() {
    let text = "environment: 0 0\naxiom: A(5)\nA(x) --> ?E(0, x, 1)\n";
    let lsys = LSystem::from_text("env.lsys", text).unwrap();
    let mut d = lsys.derivation(&DeriveOptions::default()).unwrap();
    let err = d.step().unwrap_err();
    assert!(err.to_string().contains("env.lsys:3:1"), "{err}");
    assert!(err.to_string().contains("outside the environment"), "{err}");
    // A constant index is checked before deriving.
    let err = LSystem::from_text("env.lsys", "environment: 0\naxiom: ?E(0, 3, 1)\n").unwrap_err();
    assert!(err.to_string().contains("env.lsys:2:14"), "{err}");
    // --env outside the array.
    let lsys = LSystem::from_text("env.lsys", "environment: 0\naxiom: A\n").unwrap();
    let bad = DeriveOptions {
        env: vec![(4, 1.0)],
        ..DeriveOptions::default()
    };
    assert!(lsys.derivation(&bad).is_err());
}

#[test]
fn the_plastic_example_grows_differently_in_two_environments() {
    let lsys = LSystem::from_path(std::path::Path::new("examples/plastic.lsys")).unwrap();
    let grow = |value: f64| {
        let frames = develop(
            &lsys,
            &DeriveOptions {
                env: vec![(0, value)],
                ..DeriveOptions::default()
            },
        );
        frames.last().unwrap().clone()
    };
    let poor = grow(0.0);
    let rich = grow(1.0);
    assert_ne!(poor.syms, rich.syms);
    let count = |f: &Frame| f.syms.iter().filter(|s| *s == "forward").count();
    assert_eq!(count(&poor), 4, "{}", poor.text);
    assert!(count(&rich) > 2 * count(&poor), "{}", rich.text);
    assert!(rich.syms.iter().any(|s| s == "["), "the rich one branches");
    assert_eq!(poor.env[0], 0.0);
}

#[test]
fn bad_continuous_input_is_reported() {
    let error = |text: &str, options: &DeriveOptions| {
        let lsys = match LSystem::from_text("bad.lsys", text) {
            Ok(l) => l,
            Err(e) => return e,
        };
        let mut dev = match lsys.development(options) {
            Ok(d) => d,
            Err(e) => return e,
        };
        loop {
            match dev.advance() {
                Ok(true) => {}
                Ok(false) => panic!("should have failed: {text}"),
                Err(e) => return e,
            }
        }
    };
    let none = DeriveOptions::default();
    // An ODE that gives NaN: the time is in the message.
    let e = error(
        "time: 2\naxiom: A(1)\nA(x) : x < 5 --> solve dx/dt = sqrt(2 - x)\n",
        &none,
    );
    assert_eq!(e.kind, DiagnosticKind::Runtime);
    assert!(
        e.to_string().contains("NaN") && e.to_string().contains("at t ="),
        "{e}"
    );
    assert!(e.to_string().contains("bad.lsys:3:"), "{e}");
    // d?/dt naming something that is not a parameter.
    let e = error("time: 1\naxiom: A(1)\nA(x) --> solve dq/dt = 1\n", &none);
    assert!(
        e.to_string()
            .contains("'q' is not a parameter of the predecessor A(x)"),
        "{e}"
    );
    assert!(e.to_string().contains("bad.lsys:3:16"), "{e}");
    // solve on a predecessor without parameters.
    let e = error("time: 1\naxiom: A\nA --> solve dx/dt = 1\n", &none);
    assert!(e.to_string().contains("has none"), "{e}");
    // dt <= 0 in the file and on the command line.
    let e = error("time: 1\ndt: 0\naxiom: A\n", &none);
    assert!(
        e.to_string().contains("bad.lsys:2:5") && e.to_string().contains("dt must be"),
        "{e}"
    );
    let e = error(
        "time: 1\naxiom: A\n",
        &DeriveOptions {
            dt: Some(-1.0),
            ..DeriveOptions::default()
        },
    );
    assert!(e.to_string().contains("dt must be more than 0"), "{e}");
    // Runaway growth.
    let e = error(
        "time: 20\naxiom: A(0)\nA(x) : x < 0.1 --> solve dx/dt = 1\nA(x) : x >= 0.1 --> A(0) A(0)\n",
        &DeriveOptions {
            max_modules: 1000,
            ..DeriveOptions::default()
        },
    );
    assert!(e.to_string().contains("grew past 1000 modules"), "{e}");
    assert!(e.to_string().contains("bad.lsys:4:1"), "{e}");
    // A discrete rule that never stops firing at one instant.
    let e = error("time: 1\naxiom: A(1)\nA(x) : x > 0 --> A(x + 1)\n", &none);
    assert!(
        e.to_string().contains("more than 1000 rewriting passes"),
        "{e}"
    );
    assert!(e.to_string().contains("bad.lsys:3:1"), "{e}");
    // solve in discrete mode.
    let lsys = LSystem::from_text("bad.lsys", "axiom: A(1)\nA(x) --> solve dx/dt = 1\n").unwrap();
    let mut d = lsys.derivation(&none).unwrap();
    let e = d.step().unwrap_err();
    assert!(e.to_string().contains("'solve' rule matched"), "{e}");
    // Random functions are not allowed in ODEs.
    let e = error(
        "time: 1\naxiom: A(1)\nA(x) --> solve dx/dt = uniform(0, 1)\n",
        &none,
    );
    assert!(e.to_string().contains("random functions cannot"), "{e}");
}

#[test]
fn a_rule_change_without_a_rewrite_is_one_event() {
    // Found by fuzzing: the module stops matching its solve rule (or moves to another solve
    // rule) at y = 1, which rewrites nothing; that must be one event, not an endless storm.
    let text = "time: 3\naxiom: A(0)\nA(y) : y < 1 --> solve dy/dt = 0.7\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    let frames = develop(&lsys, &options(1.0, Timing::Exact));
    assert!(
        (frames[3].params[0][0] - 1.0).abs() < 1e-9,
        "{}",
        frames[3].text
    );
    let text =
        "time: 3\naxiom: A(0)\nA(y) : y < 1 --> solve dy/dt = 0.7\nA(y) --> solve dy/dt = 5\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    for timing in [Timing::Exact, Timing::Iterative] {
        let frames = develop(&lsys, &options(1.0, timing));
        // y reaches 1 at t = 1/0.7, then grows at 5 to t = 3.
        let expected = 1.0 + 5.0 * (3.0 - 1.0 / 0.7);
        assert!(
            (frames[3].params[0][0] - expected).abs() < 1e-6,
            "{}",
            frames[3].text
        );
    }
}

#[test]
fn an_environment_read_at_an_event_settles_at_that_instant() {
    // A reaches 1 at t = 0.6 and writes env[0] = 1; the read ?E then sees 1 at once, and G is
    // born at 0.6 whatever dt is.
    let text = "\
time: 3
environment: 0
axiom: ?E(1, 0, 0) A(0.4)
A(x) : x < 1 --> solve dx/dt = 1
A(x) : x >= 1 --> ?E(0, 0, 1)
?E(1, 0, c) : c > 0.5 --> G(0)
G(x) : x < 10 --> solve dx/dt = 1
";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    for dt in [1.0, 0.25, 0.1] {
        let frames = develop(&lsys, &options(dt, Timing::Exact));
        let last = frames.last().unwrap();
        assert_eq!(last.syms, ["G", "?E"], "dt {dt}: {}", last.text);
        assert!(
            (last.params[0][0] - 2.4).abs() < 1e-9,
            "dt {dt}: {}",
            last.text
        );
    }
}

#[test]
fn constant_unconditional_rules_fire_in_continuous_time() {
    let lsys = LSystem::from_text("t.lsys", "time: 1\naxiom: A\nA --> B\n").unwrap();
    assert_eq!(
        texts(&develop(&lsys, &options(1.0, Timing::Exact))),
        ["B", "B"]
    );
    let lsys = LSystem::from_text("t.lsys", "time: 1\naxiom: A\nA --> B\n").unwrap();
    assert_eq!(
        texts(&develop(&lsys, &options(1.0, Timing::Iterative))),
        ["A", "B"]
    );
    // A rule that fires forever at one instant is an error naming it.
    let lsys = LSystem::from_text("t.lsys", "time: 1\naxiom: B\nB --> C\nC --> B\n").unwrap();
    let err = match lsys.development(&options(1.0, Timing::Exact)) {
        Ok(_) => panic!("should not settle"),
        Err(e) => e,
    };
    assert!(
        err.to_string().contains("more than 1000 rewriting passes"),
        "{err}"
    );
    // Whether an unrelated module is rewritten makes no difference.
    let text =
        "time: 2\naxiom: A(0) X\nA(x) : x < 1 --> solve dx/dt = 1\nA(x) --> F A(0)\nX --> Y\n";
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    let frames = develop(&lsys, &options(1.0, Timing::Exact));
    assert_eq!(texts(&frames), ["A(0)Y", "FA(0)Y", "FFA(0)Y"]);
}

/// The error developing `text` to its end gives, as shown to a person.
fn development_error(text: &str) -> String {
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    lsys.for_each_frame(&DeriveOptions::default(), None, |_| {
        Ok::<(), ontogeny::lang::Diagnostic>(())
    })
    .unwrap_err()
    .to_string()
}

#[test]
fn a_guard_that_flips_back_and_forth_stops_after_100000_events_in_one_step() {
    // The module matures every microsecond of a one-unit step.
    let shown = development_error(
        "time: 1\ndt: 1\naxiom: X(0)\nX(x) : x < 1 --> solve dx/dt = 1000000\nX(x) : x >= 1 --> X(0)\n",
    );
    assert!(
        shown.contains(
            "more than 100000 events in one observation step (do guards flip back and forth?) \
             while developing at t = 0.1000010000"
        ),
        "{shown}"
    );
    assert!(shown.contains("t.lsys:4:1"), "{shown}");
}

#[test]
fn an_ode_that_blows_up_could_not_be_integrated_at_its_rule() {
    // dx/dt = x², x(0) = 1: x = 1 / (1 - t) is infinite at t = 1.
    let shown = development_error("time: 2\ndt: 2\naxiom: X(1)\nX(x) --> solve dx/dt = x * x\n");
    assert!(
        shown.contains("the ODEs could not be integrated: Stopped at x = 0.99999"),
        "{shown}"
    );
    assert!(shown.contains("Step size underflow"), "{shown}");
    assert!(shown.contains("t.lsys:4:1"), "{shown}");
}

/// The events of developing `text` (time and the string after them), and its last string.
fn events_and_last(text: &str) -> (Vec<f64>, String) {
    let lsys = LSystem::from_text("t.lsys", text).unwrap();
    let mut events = Vec::new();
    let mut last = String::new();
    lsys.for_each_frame(&DeriveOptions::default(), None, |f| {
        events.extend(f.events.iter().map(|e| e.t));
        last = lsys.display(f.string);
        Ok::<(), ontogeny::lang::Diagnostic>(())
    })
    .unwrap();
    (events, last)
}

#[test]
fn a_guard_that_holds_only_inside_one_step_is_found_at_its_crossing() {
    // x = e^t − 1 enters (0.3, 0.6) at t = ln 1.3 and would leave it at ln 1.6, both within
    // the one observation step: the event is found where the guard flips, and rewrites X.
    let (events, last) = events_and_last(
        "time: 1\ndt: 1\naxiom: X(0)\nX(x) : x > 0.3 && x < 0.6 --> Y(x)\nX(x) --> solve dx/dt = x + 1\n",
    );
    assert_eq!(events.len(), 1);
    assert!((events[0] - 1.3f64.ln()).abs() < 1e-12, "{events:?}");
    assert_eq!(last, "Y(0.3)");
}
