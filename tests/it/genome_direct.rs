//! The `direct` genome (Hornby & Pollack 2001's non-generative baseline): hand-checked
//! operators, limits kept by every operator, the printed text (an axiom and nothing else)
//! grows the identical creature through the language and the command, and any grammar's
//! derived string seeds a genome.

use ontogeny::creature::{Creature, JointKind};
use ontogeny::encoding::command::Command as C;
use ontogeny::encoding::lsystem::{Arg, Item, is_driven_walker};
use ontogeny::encoding::{DirectGenome, DirectLimits, Genome, LSystemLimits, Rng};
use proptest::prelude::*;
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

fn cmd(c: C, v: f64) -> Item {
    Item::Command(c, Some(Arg::Const(v)))
}

fn f(l: f64) -> Item {
    cmd(C::Forward, l)
}

fn genome(modules: Vec<Item>) -> DirectGenome {
    DirectGenome {
        modules,
        projectile: None,
    }
}

/// The modules of a genome as the axiom writes them.
fn axiom(g: &DirectGenome) -> String {
    let text = g.to_text();
    let line = text.lines().find(|l| l.starts_with("axiom:")).unwrap();
    line["axiom: ".len()..].to_string()
}

/// The creature `ontogeny grow --max-modules --max-parts` makes of `text` with the limits.
fn grown(text: &str, limits: &DirectLimits) -> Creature {
    crate::util::grown_with_caps(text, limits.max_modules, limits.max_parts)
}

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("examples/{name}.lsys")).unwrap()
}

#[test]
fn the_limits_equal_the_lsystem_genomes() {
    let l = LSystemLimits::default();
    let d = DirectLimits::default();
    assert_eq!(d.max_modules, l.max_modules);
    assert_eq!(d.max_parts, l.max_parts);
    assert_eq!(d.random_length, l.max_successor);
    // Unknown keys are refused, missing keys take the defaults.
    let read: DirectLimits = serde_json::from_str(r#"{"max_parts": 20}"#).unwrap();
    assert_eq!((read.max_parts, read.max_modules), (20, l.max_modules));
    assert!(serde_json::from_str::<DirectLimits>(r#"{"max_commands": 20}"#).is_err());
}

#[test]
fn a_hand_made_genome_prints_as_an_axiom_and_grows_the_hand_calculated_chain() {
    let limits = DirectLimits::default();
    let g = genome(vec![
        f(1.0),
        Item::Command(C::Revolute2, None),
        f(0.5),
        cmd(C::Output, 1.0),
    ]);
    g.check(&limits).unwrap();
    let text = g.to_text();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        lines,
        ["axiom: forward(1) revolute2 forward(0.5) output(1)"]
    );
    // Two parts along x: the first centred at 0.5, the second at 1 + 0.25.
    let c = g.develop(&limits, 0).unwrap();
    let xs: Vec<f64> = c.parts.iter().map(|p| p.position.x).collect();
    assert_eq!(xs.len(), 2);
    for (x, want) in xs.iter().zip([0.5, 1.25]) {
        assert!((x - want).abs() < 1e-12, "{xs:?}");
    }
    assert_eq!(c.joints.len(), 1);
    assert_eq!(c.joints[0].kind, JointKind::Revolute);
    assert!(is_driven_walker(&c));
    assert_eq!(c, grown(&text, &limits));
    // Development has no randomness.
    assert_eq!(g.develop(&limits, 7), Ok(c));
}

#[test]
fn malformed_genomes_are_named_by_check_and_do_not_develop_silently() {
    let limits = DirectLimits::default();
    let bad = |g: DirectGenome, why: &str| {
        let e = g.check(&limits).unwrap_err();
        assert!(e.contains(why), "{e}");
    };
    bad(genome(vec![]), "0 modules, not 1 to 1000");
    bad(genome(vec![Item::Push, f(1.0)]), "not balanced");
    bad(genome(vec![Item::Call(0, vec![])]), "malformed");
    bad(
        genome(vec![Item::Command(C::Forward, Some(Arg::Plus(0, 1.0)))]),
        "malformed",
    );
    bad(genome(vec![cmd(C::Revolute1, 1.0)]), "malformed");
    bad(genome(vec![f(f64::NAN)]), "malformed");
    let tight = DirectLimits {
        max_modules: 2,
        ..DirectLimits::default()
    };
    let e = genome(vec![f(1.0); 3]).check(&tight).unwrap_err();
    assert!(e.contains("3 modules, not 1 to 2"), "{e}");
    assert!(genome(vec![]).develop(&limits, 0).is_err());
}

/// `forward(0.1) [ forward(0.2) ] forward(0.3)` and `left(1) forward(0.5) forward(0.6)
/// output(1)`.
fn parents() -> (DirectGenome, DirectGenome) {
    (
        genome(vec![f(0.1), Item::Push, f(0.2), Item::Pop, f(0.3)]),
        genome(vec![cmd(C::Left, 1.0), f(0.5), f(0.6), cmd(C::Output, 1.0)]),
    )
}

#[test]
fn one_point_crossover_joins_a_head_and_a_tail() {
    let (a, b) = parents();
    let limits = DirectLimits::default();
    let child = |i, j| axiom(&a.one_point(&b, i, j, &limits));
    // `forward(0.1) [` + `forward(0.5) forward(0.6) output(1)`: the open bracket goes.
    assert_eq!(
        child(2, 1),
        "forward(0.1) forward(0.5) forward(0.6) output(1)"
    );
    assert_eq!(
        child(4, 2),
        "forward(0.1) [ forward(0.2) ] forward(0.6) output(1)"
    );
    assert_eq!(child(5, 4), axiom(&a));
    assert_eq!(child(0, 0), axiom(&b));
    // Nothing of either: the child is a copy of the first parent.
    assert_eq!(child(0, 4), axiom(&a));
    // The tail is cut to the room the limit leaves: 3 of a, 3 of b, then `[` dropped.
    let six = DirectLimits {
        max_modules: 6,
        ..DirectLimits::default()
    };
    assert_eq!(
        axiom(&a.one_point(&b, 3, 0, &six)),
        "forward(0.1) forward(0.2) left(1) forward(0.5) forward(0.6)"
    );
}

#[test]
fn two_point_crossover_replaces_a_run_with_a_run() {
    let (a, b) = parents();
    let limits = DirectLimits::default();
    let child = |i, j| axiom(&a.two_point(&b, i, j, &limits));
    assert_eq!(
        child(1..4, 0..2),
        "forward(0.1) left(1) forward(0.5) forward(0.3)"
    );
    // An empty run of a: b's run is inserted, inside the branch.
    assert_eq!(
        child(3..3, 1..3),
        "forward(0.1) [ forward(0.2) forward(0.5) forward(0.6) ] forward(0.3)"
    );
    // An empty run of b: a's run is deleted (with the `]` it held, so the `[` goes too).
    assert_eq!(child(2..4, 2..2), "forward(0.1) forward(0.3)");
    // No room under the limit: b's run is cut to nothing.
    let five = DirectLimits {
        max_modules: 5,
        ..DirectLimits::default()
    };
    assert_eq!(axiom(&a.two_point(&b, 2..2, 0..4, &five)), axiom(&a));
}

#[test]
fn seeded_crossover_is_one_of_the_one_and_two_point_children() {
    let (a, b) = parents();
    let limits = DirectLimits::default();
    let (n, m) = (a.modules.len(), b.modules.len());
    let mut one_point = Vec::new();
    for i in 0..=n {
        for j in 0..=m {
            one_point.push(a.one_point(&b, i, j, &limits));
        }
    }
    let mut two_point = Vec::new();
    for i in 0..=n {
        for i2 in i..=n {
            for j in 0..=m {
                for j2 in j..=m {
                    two_point.push(a.two_point(&b, i..i2, j..j2, &limits));
                }
            }
        }
    }
    let (mut ones, mut only_twos) = (0, 0);
    for seed in 0..200 {
        let child = a.crossover(&b, &limits, &mut rng(seed)).unwrap();
        if one_point.contains(&child) {
            ones += 1;
        } else {
            assert!(two_point.contains(&child), "seed {seed}: {}", axiom(&child));
            only_twos += 1;
        }
    }
    assert!(ones > 30 && only_twos > 30, "{ones} {only_twos}");
    // Seed 3's child, for the record.
    assert_eq!(
        axiom(&a.crossover(&b, &limits, &mut rng(3)).unwrap()),
        SEED_3_CHILD
    );
}

const SEED_3_CHILD: &str = "forward(0.5) forward(0.6) output(1) forward(0.3)";

#[test]
fn replacing_commands_keeps_brackets_and_length() {
    let (a, _) = parents();
    let mut g = a.clone();
    g.replace_commands(0.0, &mut rng(1));
    assert_eq!(g, a);
    let mut changed = 0;
    for seed in 0..20 {
        let mut g = a.clone();
        g.replace_commands(1.0, &mut rng(seed));
        assert_eq!(g.modules.len(), 5);
        assert_eq!((&g.modules[1], &g.modules[3]), (&Item::Push, &Item::Pop));
        assert!(
            g.modules
                .iter()
                .all(|i| !matches!(i, Item::Call(..) | Item::Command(_, Some(Arg::Plus(..)))))
        );
        changed += (g.modules[0] != a.modules[0]) as usize;
    }
    assert!(changed >= 15, "{changed}");
}

#[test]
fn perturbing_arguments_moves_each_a_little_within_its_range() {
    let g = genome(vec![
        f(0.2),
        cmd(C::Left, 1.0),
        Item::Command(C::Twist90, None),
        cmd(C::Output, 2.0),
        cmd(C::Setfunc, 0.0),
    ]);
    for seed in 0..50 {
        let mut p = g.clone();
        p.perturb_arguments(1.0, &mut rng(seed));
        let args: Vec<Option<f64>> = p
            .modules
            .iter()
            .map(|i| match i {
                Item::Command(_, Some(Arg::Const(v))) => Some(*v),
                _ => None,
            })
            .collect();
        let commands: Vec<C> = p
            .modules
            .iter()
            .map(|i| match i {
                Item::Command(c, _) => *c,
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(
            commands,
            [C::Forward, C::Left, C::Twist90, C::Output, C::Setfunc]
        );
        // Lengths [0.2, 1.2]: up to 0.1 up. Turns: a step of 0.5 either way, kept in
        // [0.5, 1].
        // Weights [-2, 2]: up to 0.4 down. Functions: one step, kept in [0, 2].
        let [Some(l), Some(t), None, Some(w), Some(s)] = args[..] else {
            panic!("{args:?}")
        };
        assert!((0.2..=0.3 + 1e-9).contains(&l), "{l}");
        assert!(t == 0.5 || t == 1.0, "{t}");
        assert!((1.6 - 1e-9..=2.0).contains(&w), "{w}");
        assert!(s == 0.0 || s == 1.0, "{s}");
    }
}

#[test]
fn inserting_and_deleting_runs_changes_one_place_by_one_to_three_modules() {
    let g = genome((1..=5).map(|k| f(k as f64 / 10.0)).collect());
    let limits = DirectLimits::default();
    for seed in 0..50 {
        // Five modules: one site. The original is the child with one run taken out.
        let mut p = g.clone();
        p.insert_runs(&limits, 1.0, &mut rng(seed));
        let added = p.modules.len() - 5;
        assert!((1..=3).contains(&added), "{added}");
        assert!(
            (0..=5)
                .any(|k| p.modules[..k] == g.modules[..k]
                    && p.modules[k + added..] == g.modules[k..])
        );
        p.check(&limits).unwrap();
        let mut d = g.clone();
        d.delete_runs(1.0, &mut rng(seed));
        let gone = 5 - d.modules.len();
        assert!((1..=3).contains(&gone), "{gone}");
        assert!(
            (0..=5 - gone).any(
                |k| d.modules[..k] == g.modules[..k] && d.modules[k..] == g.modules[k + gone..]
            )
        );
    }
    // No room: nothing is inserted. One module: nothing is deleted.
    let full = DirectLimits {
        max_modules: 5,
        ..DirectLimits::default()
    };
    let mut p = g.clone();
    p.insert_runs(&full, 1.0, &mut rng(1));
    assert_eq!(p, g);
    let one = genome(vec![f(1.0)]);
    let mut p = one.clone();
    p.delete_runs(1.0, &mut rng(1));
    assert_eq!(p, one);
    // A deletion that leaves a bracket without its partner drops the bracket.
    for seed in 0..50 {
        let mut p = genome(vec![Item::Push, f(0.1), Item::Pop]);
        p.delete_runs(1.0, &mut rng(seed));
        p.check(&limits).unwrap();
    }
}

#[test]
fn mutation_rate_zero_changes_nothing_and_rate_one_changes_something() {
    let limits = DirectLimits::default();
    for seed in 0..50 {
        let g = DirectGenome::random(&limits, &mut rng(seed));
        assert_eq!(g.mutate(&limits, 0.0, &mut rng(seed)), g);
        assert_eq!(g.mutate(&limits, f64::NAN, &mut rng(seed)), g);
        assert_ne!(g.mutate(&limits, 1.0, &mut rng(seed)), g);
    }
}

#[test]
fn everything_is_determined_by_the_random_source() {
    let limits = DirectLimits::default();
    crate::util::assert_determined_by_the_random_source::<DirectGenome>(&limits);
    let (a, b) = parents();
    assert_eq!(a.graft(&b, &limits, &mut rng(5)), None);
}

#[test]
fn random_genomes_are_as_often_driven_walkers_as_lsystem_genomes() {
    // The README quotes these figures: over seeds 0-999 with the default limits, 71.3% of
    // random direct genomes are valid and 19.5% driven walkers (lsystem: 44.9% and 19.6%).
    let limits = DirectLimits::default();
    let (mut valid, mut driven) = (0, 0);
    for seed in 0..1000 {
        let g = DirectGenome::random(&limits, &mut rng(seed));
        assert!((1..=15).contains(&g.modules.len()));
        let c = g.develop(&limits, seed).unwrap();
        valid += c.is_valid() as usize;
        driven += is_driven_walker(&c) as usize;
    }
    assert_eq!((valid, driven), (713, 195));
}

#[test]
fn the_hornby_walker_seeds_a_genome_that_grows_the_same_creature() {
    let limits = DirectLimits::default();
    let text = example("hornby-walker");
    let g = DirectGenome::from_lsys(&text, &limits).unwrap();
    // The derived string without its control symbols P0, P1, P2.
    assert!(axiom(&g).starts_with(
        "width(0.6) thickness(0.2) forward(0.8) [ [ left(1) width(0.15) thickness(0.15) twist90"
    ));
    let c = g.develop(&limits, 0).unwrap();
    let from_file = grown(&text, &limits);
    assert_eq!(c, from_file);
    assert!(is_driven_walker(&c));
    assert_eq!(DirectGenome::from_lsys(&g.to_text(), &limits), Ok(g));
}

#[test]
fn grammars_whose_strings_the_genome_cannot_hold_are_refused_with_the_reason() {
    let limits = DirectLimits::default();
    let refused = |text: &str, reason: &str| {
        let e = DirectGenome::from_lsys(text, &limits).unwrap_err();
        assert!(
            e.0.starts_with("this file does not fit the direct genome"),
            "{e}"
        );
        assert!(e.0.contains(reason), "{e}");
    };
    refused(
        "axiom: forward(1) mleft(1)\n",
        "line 1, column 19: 'mleft' (first at module 2 of the derived string) is not a command the genome uses",
    );
    refused(&example("algae"), "has no building command");
    refused(&example("stochastic-plant"), "grew past 1000 modules");
    refused(
        "axiom: forward(1) chem(0)\n",
        "'chem' (first at module 2 of the derived string) is not a command",
    );
    refused(
        "axiom: { forward(1) }(3)\n",
        "'{' (first at module 1 of the derived string) is not a command the genome uses",
    );
    refused("axiom: forward(1) ]\n", "brackets of its derived string");
    // Every problem at once, each where the file writes it.
    refused(
        "derivation length: 1\naxiom: A\nA --> chem(0) forward(1) secrete(1)\n",
        "line 3, column 7: 'chem' (first at module 1 of the derived string) is not a command the genome uses (not used: repeat blocks, maturing m-commands but mforward, chem, secrete, target, release; of the textbook's symbols f, a bare !, turns by other than a multiple of 90°, and heading: up); line 3, column 26: 'secrete' (first at module 3",
    );
    // A file that does not compile keeps the language's located error: a syntax error, or a
    // built-in command given more parameters than it takes.
    let e = DirectGenome::from_lsys("axiom: A(1\n", &limits).unwrap_err();
    assert!(e.0.contains("file.lsys:1"), "{e}");
    for (text, message) in [
        ("axiom: forward(1, 2)\n", "'forward' is given 2 parameters"),
        ("axiom: revolute1(1)\n", "'revolute1' is given 1 parameter"),
    ] {
        let e = DirectGenome::from_lsys(text, &limits).unwrap_err();
        assert!(
            e.0.contains(&format!("error: {message}, but the built-in command takes"))
                && e.0.contains("file.lsys:1:8"),
            "{e}"
        );
    }
    // Control symbols build nothing and go; derived values are kept exactly.
    let g = DirectGenome::from_lsys(
        "derivation length: 2\naxiom: A(0.1)\nA(x) --> forward(x * 3) B A(x + 1)\n",
        &limits,
    )
    .unwrap();
    assert_eq!(g.modules, vec![f(0.1 * 3.0), f((0.1 + 1.0) * 3.0)]);
}

#[test]
fn the_printed_text_grows_and_evaluates_with_the_command() {
    let limits = DirectLimits::default();
    let g = DirectGenome::from_lsys(&example("hornby-walker"), &limits).unwrap();
    let dir = crate::util::scratch_dir("genome-direct-cli");
    let file = dir.join("genome.lsys");
    std::fs::write(&file, g.to_text()).unwrap();
    let developed = serde_json::to_value(g.develop(&limits, 0).unwrap()).unwrap();
    let caps = ["--max-parts", "50", "--max-modules", "1000"];
    assert_eq!(
        crate::util::grow_creature_json(&file, &dir.join("genome"), &caps),
        developed
    );
    // The same creature `ontogeny grow` makes of the example itself.
    let original = std::path::Path::new("examples/hornby-walker.lsys");
    assert_eq!(
        crate::util::grow_creature_json(original, &dir.join("original"), &[]),
        developed
    );
    // `eval` scores the text as it scores the example.
    let fitness = |path: &str| -> f64 {
        let o = crate::util::ontogeny_ok(&[
            "eval",
            path,
            "--task",
            "walker",
            "--seconds",
            "1",
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["fitness"].as_f64().unwrap()
    };
    assert_eq!(
        fitness(file.to_str().unwrap()),
        fitness("examples/hornby-walker.lsys")
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn limits_strategy() -> impl Strategy<Value = DirectLimits> {
    (0usize..40, 1usize..60, 0usize..50).prop_map(|(max_modules, max_parts, random_length)| {
        DirectLimits {
            max_modules,
            max_parts,
            random_length,
            max_neurons: None,
            max_chain: None,
            projectile: None,
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random genomes, and any chain of mutations and crossovers, stay within the limits,
    /// develop without panicking, and read back equal from their text.
    #[test]
    fn operators_never_leave_the_limits_and_text_round_trips(
        limits in limits_strategy(),
        seed in any::<u64>(),
        rate in 0.0f64..1.0,
    ) {
        let mut r = rng(seed);
        let mut g = DirectGenome::random(&limits, &mut r);
        for k in 0..30 {
            prop_assert_eq!(g.check(&limits), Ok(()));
            let _ = g.develop(&limits, seed);
            prop_assert_eq!(DirectGenome::from_lsys(&g.to_text(), &limits), Ok(g.clone()));
            let other = DirectGenome::random(&limits, &mut r);
            g = if k % 2 == 0 {
                g.mutate(&limits, rate, &mut r)
            } else {
                g.crossover(&other, &limits, &mut r).unwrap()
            };
        }
    }
}
