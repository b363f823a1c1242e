//! The `lsystem-continuous` genome (Matos & Arita 3.2): limits kept by construction, text
//! round trips, development through the language, reading hand-written files.

use crate::util::{ontogeny, scratch_dir};

use ontogeny::creature::{Actuator, Creature, Role};
use ontogeny::develop::{BuildOptions, grow};
use ontogeny::encoding::command::Command;
use ontogeny::encoding::continuous::{Grower, Rule, Token};
use ontogeny::encoding::{ContinuousGenome, ContinuousLimits, Genome, Rng};
use ontogeny::lsystem::{DeriveOptions, LSystem};
use proptest::prelude::*;
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// What evolution for walking needs: a valid creature of at least two parts with at least
/// one movable joint driven by an actuator neuron that some link feeds.
fn walker_ready(c: &Creature) -> bool {
    c.is_valid()
        && c.parts.len() >= 2
        && c.brain.neurons.iter().enumerate().any(|(i, n)| {
            matches!(n.role, Role::Actuator { actuator: Actuator::Joint { joint, .. } }
                if c.joints[joint].kind.dof() > 0)
                && c.brain.links.iter().any(|l| l.to == i && l.weight != 0.0)
        })
}

/// The last frame of `ontogeny::develop::grow` on the genome's text, with the limits'
/// module and part limits: the path a hand-written file takes.
fn grown_from_text(text: &str, limits: &ContinuousLimits) -> Creature {
    let lsys = LSystem::from_text("genome.lsys", text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let options = DeriveOptions {
        max_modules: limits.max_modules,
        ..DeriveOptions::default()
    };
    let build = BuildOptions {
        max_parts: limits.max_parts,
        ..BuildOptions::default()
    };
    grow(&lsys, &options, None, &build)
        .unwrap_or_else(|e| panic!("{e}"))
        .pop()
        .unwrap()
        .creature
}

fn json(c: &Creature) -> serde_json::Value {
    serde_json::to_value(c).unwrap()
}

#[test]
fn genome_to_text_to_creature_is_the_creature_develop_gives() {
    let limits = ContinuousLimits::default();
    let mut r = rng(7);
    let mut checked = 0;
    for seed in 0..60 {
        let mut g = ContinuousGenome::random(&limits, &mut rng(seed));
        if seed % 2 == 1 {
            g = g.mutate(&limits, 0.2, &mut r);
        }
        let text = g.to_text();
        // The text reads back as the same genome...
        assert_eq!(
            ContinuousGenome::from_lsys(&text, &limits).unwrap(),
            g,
            "{text}"
        );
        // ...and grows into the same creature as `develop`.
        if let Ok(developed) = g.develop(&limits, 0) {
            let grown = grown_from_text(&text, &limits);
            assert_eq!(developed, grown, "{text}");
            assert_eq!(json(&developed), json(&grown));
            checked += 1;
        }
    }
    assert!(checked >= 55, "only {checked} of 60 genomes developed");
}

#[test]
fn the_printed_file_grows_and_evaluates_with_the_cli_into_the_same_creature() {
    let limits = ContinuousLimits::default();
    let (g, developed) = (0..)
        .map(|seed| ContinuousGenome::random(&limits, &mut rng(seed)))
        .find_map(|g| {
            let c = g.develop(&limits, 0).ok()?;
            walker_ready(&c).then_some((g, c))
        })
        .unwrap();
    let dir = scratch_dir("genome-continuous-cli");
    let file = dir.join("genome.lsys");
    std::fs::write(&file, g.to_text()).unwrap();
    let file = file.to_str().unwrap();
    let out = dir.join("grown");
    let o = ontogeny(&[
        "grow",
        file,
        "--out",
        out.to_str().unwrap(),
        "--max-parts",
        "50",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("creature.json")).unwrap();
    // Both sides go through the same text-to-JSON parser (serde_json reads some floats a
    // unit in the last place off, the same way for the same text).
    let grown: serde_json::Value = serde_json::from_str(&text).unwrap();
    let ours: serde_json::Value =
        serde_json::from_str(&serde_json::to_string(&developed).unwrap()).unwrap();
    assert_eq!(grown, ours);
    let o = ontogeny(&[
        "eval",
        file,
        "--task",
        "walker",
        "--seconds",
        "0.5",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_hand_written_walker_fits_and_develops_like_its_file() {
    let limits = ContinuousLimits::default();
    let text = std::fs::read_to_string("examples/continuous-walker.lsys").unwrap();
    let g = ContinuousGenome::from_lsys(&text, &limits).unwrap();
    assert_eq!(g.rules.len(), 4);
    assert_eq!(g.axiom.len(), 9);
    let mforward = g.rule(Grower::Maturing(Command::Forward)).unwrap();
    assert_eq!((mforward.threshold, mforward.rate), (0.4, 0.4));
    let from_file = grown_from_text(&text, &limits);
    let developed = g.develop(&limits, 0).unwrap();
    assert_eq!(developed, from_file);
    // Two body segments, four legs of two parts: 10 parts; 4 hips and 4 knees, all driven.
    assert_eq!(developed.parts.len(), 10);
    assert!(walker_ready(&developed));
    let movable = developed.joints.iter().filter(|j| j.kind.dof() > 0).count();
    assert_eq!(movable, 8);
    let actuators = developed
        .brain
        .neurons
        .iter()
        .filter(|n| matches!(n.role, Role::Actuator { .. }))
        .count();
    assert_eq!(actuators, 8);
    assert!(
        developed.parts.iter().all(|p| !p.growing),
        "fully grown at t = 3"
    );
}

#[test]
fn shipped_examples_that_do_not_fit_are_refused_with_the_reason() {
    let limits = ContinuousLimits::default();
    let cases = [
        ("examples/quadruped.lsys", "no 'time:'"),
        ("examples/dl-figure1.lsys", "iterative"),
        ("examples/plastic.lsys", "must be written mforward(0)"),
        ("examples/snake.lsys", "not a token of the genome"),
        ("examples/algae.lsys", "no 'time:'"),
    ];
    for (path, why) in cases {
        let text = std::fs::read_to_string(path).unwrap();
        let e = ContinuousGenome::from_lsys(&text, &limits).unwrap_err();
        assert!(
            e.0.contains("does not fit the lsystem-continuous genome"),
            "{path}: {e}"
        );
        assert!(e.0.contains(why), "{path}: {e}");
    }
}

#[test]
fn files_outside_the_template_or_the_limits_are_refused() {
    let limits = ContinuousLimits::default();
    let head = "time: 4\naxiom: forward(0.5) mforward(0)\n";
    let refuse = |rules: &str, why: &str| {
        let e = ContinuousGenome::from_lsys(&format!("{head}{rules}"), &limits).unwrap_err();
        assert!(e.0.contains(why), "{rules}: {e}");
    };
    // Only one of the template's two rules.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 1\n",
        "template's two rules",
    );
    // Thresholds that differ.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 0.5\nmforward(x) : x >= 0.9 --> forward(x)\n",
        "same threshold",
    );
    // A successor that does not start with the matured twin.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 0.5\nmforward(x) : x >= 1 --> left(1)\n",
        "twin, forward(x)",
    );
    // Maturing faster than min_duration (1): 1 / 2 = 0.5.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 2\nmforward(x) : x >= 1 --> forward(x)\n",
        "min_duration",
    );
    // A part longer than max_threshold.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 0.5\nmforward(x) : x >= 1 --> forward(x) forward(3)\n",
        "outside its range",
    );
    // A control token beyond those allowed (3: A, B, C).
    refuse(
        "D(x) : x < 1 --> solve dx/dt = 0.5\nD(x) : x >= 1 --> forward(1)\n",
        "not a maturing symbol",
    );
    // Unbalanced brackets.
    refuse(
        "mforward(x) : x < 1 --> solve dx/dt = 0.5\nmforward(x) : x >= 1 --> forward(x) [ left(1)\n",
        "without its ']'",
    );
    // A syntax error is reported as the language reports it.
    let e = ContinuousGenome::from_lsys("axiom: (", &limits).unwrap_err();
    assert!(e.0.contains("init.lsys:1:"), "{e}");
    // The same rules fit when written as the template asks.
    let ok = "mforward(x) : x >= 1 --> forward(x) [ left(1) ]\nmforward(x) : x < 1 --> solve dx/dt = 0.5\n";
    let g = ContinuousGenome::from_lsys(&format!("{head}{ok}"), &limits).unwrap();
    assert_eq!(
        g.rules,
        vec![Rule {
            grower: Grower::Maturing(Command::Forward),
            threshold: 1.0,
            rate: 0.5,
            successor: vec![
                Token::Push,
                Token::Command(Command::Left, Some(1.0)),
                Token::Pop
            ],
            plastic: None,
        }]
    );
}

#[test]
fn operators_are_deterministic_given_the_rng() {
    let limits = ContinuousLimits::default();
    let chain = |seed| {
        let mut r = rng(seed);
        let a = ContinuousGenome::random(&limits, &mut r);
        let b = ContinuousGenome::random(&limits, &mut r);
        let c = a.crossover(&b, &limits, &mut r).unwrap();
        c.mutate(&limits, 0.1, &mut r).to_text()
    };
    assert_eq!(chain(5), chain(5));
    assert_ne!(chain(5), chain(6));
}

#[test]
fn mutation_rate_zero_changes_nothing_and_rate_one_changes_every_token() {
    let limits = ContinuousLimits::default();
    let mut r = rng(2);
    let g = ContinuousGenome::random(&limits, &mut r);
    assert_eq!(g.mutate(&limits, 0.0, &mut r), g);
    let m = g.mutate(&limits, 1.0, &mut r);
    assert_ne!(m, g);
    m.check_limits(&limits).unwrap();
    assert!(
        g.graft(&m, &limits, &mut r).is_none(),
        "no grafting in the paper"
    );
}

#[test]
fn developmental_errors_are_errors_not_panics() {
    let limits = ContinuousLimits::default();
    // A genome that does not fit its limits (read from elsewhere) is refused...
    let mut g = ContinuousGenome::from_lsys(
        &std::fs::read_to_string("examples/continuous-walker.lsys").unwrap(),
        &limits,
    )
    .unwrap();
    g.axiom[0] = Token::Command(Command::Width, Some(f64::NAN));
    let e = g.develop(&limits, 0).unwrap_err();
    assert!(e.0.contains("width(NaN) is outside its range"), "{e}");
    let mut slow = g.clone();
    slow.axiom[0] = Token::Command(Command::Width, Some(0.5));
    slow.dt = 1e-6;
    let e = slow.develop(&limits, 0).unwrap_err();
    assert!(e.0.contains("more than 1000 frames"), "{e}");
    // ...and its text does not compile: a non-finite number prints as an unknown name.
    let e = LSystem::from_text("g", &g.to_text()).unwrap_err();
    assert!(e.to_string().contains("NaN"), "{e}");
    // Growth past max_modules stops development with the language's message.
    let small = ContinuousLimits {
        max_modules: 20,
        ..limits.clone()
    };
    g.axiom[0] = Token::Command(Command::Width, Some(0.5));
    let e = g.develop(&small, 0).unwrap_err();
    assert!(e.0.contains("grew past 20 modules"), "{e}");
    // Too many parts makes the creature invalid (as `--max-parts` does).
    let few = ContinuousLimits {
        max_parts: 5,
        ..limits
    };
    assert!(!g.develop(&few, 0).unwrap().is_valid());
}

#[test]
fn of_random_genomes_from_seeds_0_to_999_619_develop_into_walkers_and_847_are_valid() {
    // The figures docs/reference/genomes.md quotes: 61.9 % walker-ready, 84.7 % valid, none
    // fails to develop, the median creature has 5 parts. (benches/develop.rs times this.)
    let limits = ContinuousLimits::default();
    let (mut ready, mut valid, mut errors) = (0, 0, 0);
    let mut parts = Vec::new();
    for seed in 0..1000u64 {
        match ContinuousGenome::random(&limits, &mut rng(seed)).develop(&limits, 0) {
            Ok(c) => {
                valid += usize::from(c.is_valid());
                ready += usize::from(walker_ready(&c));
                parts.push(c.parts.len());
            }
            Err(_) => errors += 1,
        }
    }
    parts.sort();
    assert_eq!(
        (ready, valid, errors, parts[parts.len() / 2]),
        (619, 847, 0, 5)
    );
}

fn limits_strategy() -> impl Strategy<Value = ContinuousLimits> {
    (1usize..8, 0usize..5, 1usize..14, 0usize..14, 0usize..4).prop_map(
        |(max_rules, control_tokens, max_axiom, max_successor, max_growers)| ContinuousLimits {
            max_rules,
            control_tokens,
            max_axiom,
            max_successor,
            max_growers,
            ..ContinuousLimits::default()
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random genomes, and 30 chained mutations and crossovers at random rates, never exceed
    /// the limits (whatever the limits).
    #[test]
    fn operators_never_exceed_the_limits(
        limits in limits_strategy(),
        seed in any::<u64>(),
        rates in proptest::collection::vec(0.0f64..1.0, 30),
    ) {
        let mut r = rng(seed);
        let mut a = ContinuousGenome::random(&limits, &mut r);
        let mut b = ContinuousGenome::random(&limits, &mut r);
        prop_assert!(a.check_limits(&limits).is_ok(), "{:?}", a.check_limits(&limits));
        for rate in rates {
            let child = a.crossover(&b, &limits, &mut r).unwrap();
            prop_assert!(child.check_limits(&limits).is_ok(), "{:?}", child.check_limits(&limits));
            b = a.mutate(&limits, rate, &mut r);
            prop_assert!(b.check_limits(&limits).is_ok(), "{:?}", b.check_limits(&limits));
            a = child.mutate(&limits, rate, &mut r);
            prop_assert!(a.check_limits(&limits).is_ok(), "{:?}", a.check_limits(&limits));
        }
    }
}
