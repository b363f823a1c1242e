//! The `lsystem` genome (Hornby & Pollack 2001): operators stay within the limits, the
//! printed text grows the identical creature through the language and the command, and
//! hand-written files that fit the form are read back.

use ontogeny::creature::{Creature, JointKind};
use ontogeny::develop::{BuildOptions, grow};
use ontogeny::encoding::lsystem::{
    Arg, Compare, Condition, Item, Pair, Production, is_driven_walker,
};
use ontogeny::encoding::{Genome, LSystemGenome, LSystemLimits, Rng};
use ontogeny::lsystem::{DeriveOptions, LSystem};
use proptest::prelude::*;
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// The last creature `develop::grow` makes from `text`, with the limits' module and part
/// caps (what `ontogeny grow --max-modules --max-parts` does).
fn grown(text: &str, limits: &LSystemLimits) -> Creature {
    let lsys = LSystem::from_text("t.lsys", text).expect("the text compiles");
    let options = DeriveOptions {
        max_modules: limits.max_modules,
        ..DeriveOptions::default()
    };
    let build = BuildOptions {
        max_parts: limits.max_parts,
        ..BuildOptions::default()
    };
    grow(&lsys, &options, None, &build)
        .expect("the text grows")
        .pop()
        .expect("a frame")
        .creature
}

/// `P0(n0, n1) : n0 > 0 --> forward(1) revolute2 P0(n0 - 1, n1)`,
/// `P0(n0, n1) --> forward(0.5) output(1)`, from `P0(2, 0)` for 3 steps.
fn chain() -> LSystemGenome {
    let c = |command, v: Option<f64>| Item::Command(command, v.map(Arg::Const));
    use ontogeny::encoding::command::Command as C;
    LSystemGenome {
        start: vec![2.0, 0.0],
        derivation_length: 3,
        productions: vec![Production {
            pairs: vec![
                Pair {
                    condition: Some(Condition {
                        param: 0,
                        compare: Compare::Greater,
                        value: 0.0,
                        read: false,
                    }),
                    successor: vec![
                        c(C::Forward, Some(1.0)),
                        c(C::Revolute2, None),
                        Item::Call(0, vec![Arg::Plus(0, -1.0), Arg::Plus(1, 0.0)]),
                    ],
                },
                Pair {
                    condition: None,
                    successor: vec![c(C::Forward, Some(0.5)), c(C::Output, Some(1.0))],
                },
            ],
            read: None,
        }],
        environment: Vec::new(),
        projectile: None,
    }
}

#[test]
fn a_hand_made_genome_prints_as_the_language_and_grows_the_hand_calculated_chain() {
    let g = chain();
    let limits = LSystemLimits::default();
    g.check(&limits).unwrap();
    let text = g.to_text();
    let rules: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        rules,
        [
            "derivation length: 3",
            "axiom: P0(2, 0)",
            "",
            "P0(n0, n1) : n0 > 0 --> forward(1) revolute2 P0(n0 - 1, n1)",
            "P0(n0, n1) --> forward(0.5) output(1)",
        ]
    );
    // Steps: P0(2,0) -> F R P0(1,0) -> F R F R P0(0,0) -> F R F R forward(0.5) output(1).
    let c = g.develop(&limits, 0).unwrap();
    assert_eq!(c.parts.len(), 3);
    let xs: Vec<f64> = c.parts.iter().map(|p| p.position.x).collect();
    for (x, want) in xs.iter().zip([0.5, 1.5, 2.25]) {
        assert!((x - want).abs() < 1e-12, "{xs:?}");
    }
    assert!((c.parts[2].size.x - 0.5).abs() < 1e-12);
    assert_eq!(c.joints.len(), 2);
    assert!(c.joints.iter().all(|j| j.kind == JointKind::Revolute));
    assert!(c.is_valid() && is_driven_walker(&c));
    // The same creature from the text through the language.
    assert_eq!(c, grown(&text, &limits));
    // One step fewer: the output is not there yet, so nothing drives a joint.
    let short = LSystemGenome {
        derivation_length: 2,
        ..g
    };
    let c = short.develop(&limits, 0).unwrap();
    assert_eq!(c.parts.len(), 2);
    assert!(c.is_valid() && !is_driven_walker(&c));
}

#[test]
fn random_genomes_develop_into_the_creature_their_text_grows_and_read_back_equal() {
    let limits = LSystemLimits::default();
    let mut compared = 0;
    for seed in 0..200 {
        let g = LSystemGenome::random(&limits, &mut rng(seed));
        g.check(&limits).unwrap();
        let text = g.to_text();
        assert_eq!(
            LSystemGenome::from_lsys(&text, &limits),
            Ok(g.clone()),
            "{text}"
        );
        if let Ok(c) = g.develop(&limits, seed) {
            // serde JSON equality as well as `==`: what the run store keeps.
            let d = grown(&text, &limits);
            assert_eq!(c, d, "{text}");
            assert_eq!(
                serde_json::to_value(&c).unwrap(),
                serde_json::to_value(&d).unwrap()
            );
            compared += 1;
        }
    }
    assert!(compared > 150, "only {compared} developed");
}

#[test]
fn mutants_and_children_read_back_equal_and_grow_the_same() {
    let limits = LSystemLimits::default();
    let mut r = rng(7);
    let mut g = LSystemGenome::random(&limits, &mut r);
    for k in 0..100 {
        let other = LSystemGenome::random(&limits, &mut r);
        g = if k % 2 == 0 {
            g.mutate(&limits, 0.1, &mut r)
        } else {
            g.crossover(&other, &limits, &mut r).unwrap()
        };
        let text = g.to_text();
        assert_eq!(LSystemGenome::from_lsys(&text, &limits), Ok(g.clone()));
        if let Ok(c) = g.develop(&limits, 0) {
            assert_eq!(c, grown(&text, &limits));
        }
    }
}

#[test]
fn everything_is_determined_by_the_random_source() {
    let limits = LSystemLimits::default();
    let a = LSystemGenome::random(&limits, &mut rng(42));
    let b = LSystemGenome::random(&limits, &mut rng(42));
    assert_eq!(a, b);
    assert_ne!(a, LSystemGenome::random(&limits, &mut rng(43)));
    let other = LSystemGenome::random(&limits, &mut rng(1));
    assert_eq!(
        a.mutate(&limits, 0.2, &mut rng(5)),
        b.mutate(&limits, 0.2, &mut rng(5))
    );
    assert_eq!(
        a.crossover(&other, &limits, &mut rng(5)),
        b.crossover(&other, &limits, &mut rng(5))
    );
    assert_eq!(a.develop(&limits, 3), b.develop(&limits, 3));
    assert_eq!(a.graft(&other, &limits, &mut rng(5)), None);
}

#[test]
fn mutation_rate_zero_changes_nothing_and_rate_one_changes_something() {
    let limits = LSystemLimits::default();
    let mut r = rng(9);
    for _ in 0..50 {
        let g = LSystemGenome::random(&limits, &mut r);
        assert_eq!(g.mutate(&limits, 0.0, &mut r), g);
        assert_eq!(g.mutate(&limits, f64::NAN, &mut r), g);
        assert_ne!(g.mutate(&limits, 1.0, &mut r), g);
    }
}

#[test]
fn runaway_growth_is_cut_by_the_module_limit_with_an_error() {
    // Every step doubles the string: 2^12 copies are past the 1000-module limit.
    let text = "derivation length: 6\naxiom: P0(0, 0)\n\nP0(n0, n1) --> P0(n0, n1) P0(n0, n1) P0(n0, n1) P0(n0, n1) P0(n0, n1) P0(n0, n1) P0(n0, n1) forward(1)\n";
    let limits = LSystemLimits::default();
    let g = LSystemGenome::from_lsys(text, &limits).unwrap();
    let e = g.develop(&limits, 0).unwrap_err();
    assert!(e.0.contains("grew past 1000 modules"), "{e}");
}

#[test]
fn over_1000_seeds_196_random_genomes_are_driven_walkers() {
    // Valid, at least 2 parts, and a joint driven by an output neuron with an input. The
    // README quotes this figure: 196 of 1000 with the default limits.
    let limits = LSystemLimits::default();
    let walkers = (0..1000)
        .filter(|&seed| {
            let g = LSystemGenome::random(&limits, &mut rng(seed));
            g.develop(&limits, seed).is_ok_and(|c| is_driven_walker(&c))
        })
        .count();
    assert_eq!(walkers, 196);
}

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("examples/{name}.lsys")).unwrap()
}

#[test]
fn the_shipped_quadruped_fits_and_develops_into_the_same_creature() {
    let limits = LSystemLimits::default();
    let text = example("quadruped");
    let g = LSystemGenome::from_lsys(&text, &limits).unwrap();
    // Body, Legs, Leg: three productions, padded to two parameters.
    assert_eq!(g.productions.len(), 3);
    assert_eq!(g.start, vec![0.0, 0.0]);
    let c = g.develop(&limits, 0).unwrap();
    assert_eq!(c, grown(&text, &limits));
    assert_eq!(c.parts.len(), 11);
    assert!(is_driven_walker(&c));
    // And its mutants stay readable and within the limits.
    let m = g.mutate(&limits, 0.3, &mut rng(1));
    m.check(&limits).unwrap();
}

#[test]
fn the_hornby_walker_example_fits_and_walks_on_paper() {
    let limits = LSystemLimits::default();
    let text = example("hornby-walker");
    let g = LSystemGenome::from_lsys(&text, &limits).unwrap();
    let c = g.develop(&limits, 0).unwrap();
    assert_eq!(c, grown(&text, &limits));
    assert!(is_driven_walker(&c), "{:?}", c.problems);
    // Printing and reading it back keeps it.
    assert_eq!(LSystemGenome::from_lsys(&g.to_text(), &limits), Ok(g));
}

#[test]
fn every_shipped_example_that_builds_seeds_a_genome_and_the_rest_say_every_reason() {
    let limits = LSystemLimits::default();
    // Kept as productions (the algae with a derivation length widened to 7; the thrower's
    // axiom as a first production, one step more), or as the string they derive.
    for (name, productions, derivation_length) in [
        ("algae", 2, 7),
        ("thrower", 1, 1),
        ("quadruped", 3, 3),
        ("snake", 1, 1),
        ("continuous-walker", 1, 1),
        ("syntax-tour", 1, 1),
    ] {
        let seed = LSystemGenome::seed_from_lsys("file.lsys", &example(name), &limits).unwrap();
        assert_eq!(seed.genome.productions.len(), productions, "{name}");
        assert_eq!(seed.genome.derivation_length, derivation_length, "{name}");
        seed.genome.check(&seed.limits).unwrap();
        if name != "algae" {
            // The same creature as the file grows.
            let c = seed.genome.develop(&seed.limits, 0).unwrap();
            assert_eq!(c, grown(&example(name), &seed.limits), "{name}");
        }
    }
    let algae = LSystemGenome::seed_from_lsys("file.lsys", &example("algae"), &limits).unwrap();
    assert_eq!(algae.limits.derivation_length, 7);
    assert_eq!(
        algae.notes,
        [
            "the run's limits are widened to fit the seed (derivation_length 6 → 7); its mutants keep within them"
        ]
    );
    // Neither its rules nor its derived string: every reason, each with its place.
    let e = LSystemGenome::from_lsys(&example("parametric"), &limits).unwrap_err();
    assert_eq!(
        e.0,
        "this file does not fit the lsystem genome: its rules cannot be the genome's:\n  \
         line 6, column 31: the argument 'x + y' is not a number, a parameter, or a parameter plus, minus or times a number\n  \
         line 7, column 29: the argument 'x / y' is not a number, a parameter, or a parameter plus, minus or times a number\n\
         nor can the string it derives:\n  its derived string has no building command"
    );
}

#[test]
fn a_grammar_is_rewritten_into_the_genomes_forms_and_its_limits_widened_to_fit() {
    let limits = LSystemLimits::default();
    let seed = |body: &str| {
        let text = format!("derivation length: 2\naxiom: A(1)\n{body}\n");
        LSystemGenome::seed_from_lsys("file.lsys", &text, &limits).unwrap()
    };
    let forward = ontogeny::encoding::command::Command::Forward;
    // `-x` is `x * -1`, `0.5 + x` is `x + 0.5`, a constant expression its value.
    let s = seed("A(x) --> forward(-x) forward(0.5 + x) forward(2 * 0.25) A(x)");
    assert_eq!(
        s.genome.productions[0].pairs[0].successor[..3],
        [
            Item::Command(forward, Some(Arg::Times(0, -1.0))),
            Item::Command(forward, Some(Arg::Plus(0, 0.5))),
            Item::Command(forward, Some(Arg::Const(0.5))),
        ]
    );
    assert!(s.notes.is_empty(), "{:?}", s.notes);
    // 16 items and 4 pairs: the limits grow to fit, and say so.
    let s = seed(&format!("A(x) --> {}", ["forward(1)"; 16].join(" ")));
    assert_eq!(s.limits.max_successor, 16);
    assert_eq!(
        s.notes,
        [
            "the run's limits are widened to fit the seed (max_successor 15 → 16); its mutants keep within them"
        ]
    );
    let s = seed(
        "A(x) : x > 1 --> A(x)\nA(x) : x > 2 --> A(x)\nA(x) : x > 3 --> A(x)\nA(x) --> forward(x)",
    );
    assert_eq!(
        (s.limits.max_pairs, s.genome.productions[0].pairs.len()),
        (4, 4)
    );
    // A form the genome has no equivalent of: the string it derives, one production.
    for body in [
        "A(x) --> forward(x / 2)",
        "A(x) : x * 2 > 1 --> forward(1)",
        "A(x) > B --> forward(1)\nA(x) --> forward(2)",
    ] {
        let s = seed(body);
        assert_eq!(s.genome.derivation_length, 1, "{body}");
        assert!(
            s.notes[0].starts_with("its rules cannot be the genome's (line 3, column "),
            "{body}: {:?}",
            s.notes
        );
    }
    // What neither can hold is listed all at once, where the file writes it.
    let text = "derivation length: 1\naxiom: A(1)\nA(x) --> forward(1) chem(0) [ forward(1)\nB --> mforward(0)\n";
    let e = LSystemGenome::from_lsys(text, &limits).unwrap_err();
    assert_eq!(
        e.0,
        "this file does not fit the lsystem genome: its rules cannot be the genome's:\n  \
         line 3, column 21: 'chem' reads or writes the environment, and the file has none ('environment:')\n  \
         line 3, column 10: the successor's brackets are not balanced\n  \
         line 4, column 7: 'mforward' is not a command the genome uses (not used: maturing m-commands but mforward, target, release; of the textbook's symbols f, a bare !, turns by other than a multiple of 90°, and heading: up)\n\
         nor can the string it derives:\n  \
         line 3, column 21: 'chem' (first at module 2 of the derived string) is not a command the genome uses (not used: repeat blocks, maturing m-commands but mforward, chem, secrete, target, release; of the textbook's symbols f, a bare !, turns by other than a multiple of 90°, and heading: up)\n  \
         the brackets of its derived string are not balanced"
    );
    let e = LSystemGenome::from_lsys("axiom: A(1\n", &limits).unwrap_err();
    assert!(e.0.contains("file.lsys:1"), "{e}");
    // A condition written the other way round reads as its mirror image.
    let g = LSystemGenome::from_lsys(
        "derivation length: 1\naxiom: A(1)\nA(x) : 2 < x --> forward(x * 0.5)\n",
        &limits,
    )
    .unwrap();
    assert_eq!(
        g.productions[0].pairs[0].condition,
        Some(Condition {
            param: 0,
            compare: Compare::Greater,
            value: 2.0,
            read: false,
        })
    );
    assert_eq!(
        g.productions[0].pairs[0].successor,
        vec![Item::Command(
            ontogeny::encoding::command::Command::Forward,
            Some(Arg::Times(0, 0.5))
        )]
    );
}

#[test]
fn the_printed_text_grows_and_evaluates_with_the_command() {
    let limits = LSystemLimits::default();
    let g = chain();
    let dir = crate::util::scratch_dir("genome-lsystem-cli");
    let file = dir.join("genome.lsys");
    std::fs::write(&file, g.to_text()).unwrap();
    let out = dir.join("out");
    let run = crate::util::ontogeny_ok;
    run(&[
        "grow",
        file.to_str().unwrap(),
        "--max-parts",
        "50",
        "--max-modules",
        "1000",
        "--out",
        out.to_str().unwrap(),
    ]);
    let json = std::fs::read_to_string(out.join("creature.json")).unwrap();
    let from_cli: serde_json::Value = serde_json::from_str(&json).unwrap();
    let developed = serde_json::to_value(g.develop(&limits, 0).unwrap()).unwrap();
    assert_eq!(from_cli, developed);
    let o = run(&[
        "eval",
        file.to_str().unwrap(),
        "--task",
        "walker",
        "--seconds",
        "1",
        "--json",
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("fitness"));
    std::fs::remove_dir_all(&dir).ok();
}

fn limits_strategy() -> impl Strategy<Value = LSystemLimits> {
    (1usize..6, 1usize..4, 0usize..4, 0usize..20, 0u64..8).prop_map(
        |(max_productions, max_pairs, params, max_successor, derivation_length)| LSystemLimits {
            max_productions,
            max_pairs,
            params,
            max_successor,
            derivation_length,
            ..LSystemLimits::default()
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random genomes, and any chain of mutations and crossovers, stay within the limits.
    #[test]
    fn operators_never_leave_the_limits(
        limits in limits_strategy(),
        seed in any::<u64>(),
        rate in 0.0f64..1.0,
    ) {
        let mut r = rng(seed);
        let mut g = LSystemGenome::random(&limits, &mut r);
        prop_assert_eq!(g.check(&limits), Ok(()));
        for k in 0..40 {
            let other = LSystemGenome::random(&limits, &mut r);
            g = match k % 3 {
                0 => g.mutate(&limits, rate, &mut r),
                1 => g.crossover(&other, &limits, &mut r).unwrap(),
                _ => other.crossover(&g, &limits, &mut r).unwrap().mutate(&limits, 1.0, &mut r),
            };
            prop_assert_eq!(g.check(&limits), Ok(()), "{}", g.to_text());
        }
        // And the result still compiles and prints back to itself.
        prop_assert_eq!(LSystemGenome::from_lsys(&g.to_text(), &limits), Ok(g.clone()));
    }
}

#[test]
fn a_grammar_with_named_constants_reads_as_the_genome_of_their_values() {
    let limits = LSystemLimits::default();
    let named = "define L = 0.5\ndefine N = 2\nderivation length: 3\naxiom: A(N)\n\
                 A(n) : n > L --> forward(L) revolute1 A(n)\n";
    let written = "derivation length: 3\naxiom: A(2)\n\
                   A(n) : n > 0.5 --> forward(0.5) revolute1 A(n)\n";
    let g = LSystemGenome::from_lsys(named, &limits).unwrap();
    assert_eq!(Ok(g), LSystemGenome::from_lsys(written, &limits));
    // A rule's own parameter hides a constant of its name.
    let hidden = "define n = 9\nderivation length: 3\naxiom: A(2)\n\
                  A(n) : n > 0.5 --> forward(n) A(n)\n";
    let plain = "derivation length: 3\naxiom: A(2)\nA(n) : n > 0.5 --> forward(n) A(n)\n";
    assert_eq!(
        LSystemGenome::from_lsys(hidden, &limits),
        LSystemGenome::from_lsys(plain, &limits)
    );
}
