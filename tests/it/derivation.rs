//! Derivations checked against The Algorithmic Beauty of Plants (ABOP) and hand calculation.

use crate::util::{derive, derive_with, lsystem, squash};
use ontogeny::develop::{BuildOptions, Shortcut, grow, grow_last};
use ontogeny::lsystem::DeriveOptions;

#[test]
fn algae_lengths_follow_fibonacci() {
    let steps = derive("axiom: a\na --> ab\nb --> a\n", 20);
    let (mut a, mut b) = (1usize, 2usize);
    for s in &steps {
        assert_eq!(s.len(), a);
        (a, b) = (b, a + b);
    }
    assert_eq!(steps[4], "abaababa");
}

#[test]
fn quadratic_koch_island_has_four_times_eight_to_the_n_segments() {
    let steps = derive("axiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\n", 3);
    for (n, s) in steps.iter().enumerate() {
        let f = s.chars().filter(|&c| c == 'F').count();
        assert_eq!(f, 4 * 8usize.pow(n as u32), "step {n}");
    }
    assert_eq!(
        steps[1],
        "F-F+F+FF-F-F+F-F-F+F+FF-F-F+F-F-F+F+FF-F-F+F-F-F+F+FF-F-F+F"
    );
}

const PARAMETRIC: &str = "\
axiom: B(2) A(4, 4)
A(x, y) : y <= 3 --> A(x * 2, x + y)
A(x, y) : y > 3  --> B(x) A(x / y, 0)
B(x) : x < 1  --> C
B(x) : x >= 1 --> B(x - 1)
";

#[test]
fn parametric_example_of_abop_section_1_10() {
    let steps = derive(PARAMETRIC, 4);
    assert_eq!(
        steps,
        [
            "B(2)A(4,4)",
            "B(1)B(4)A(1,0)",
            "B(0)B(3)A(2,1)",
            "CB(2)A(4,3)",
            "CB(1)A(8,7)"
        ]
    );
}

#[test]
fn the_issue_syntax_tour_parses_and_derives_the_parametric_steps() {
    let text = std::fs::read_to_string("examples/syntax-tour.lsys").unwrap();
    let steps = derive(&text, 4);
    assert_eq!(steps[4], "CB(1)A(8,7)");
}

#[test]
fn acropetal_signal_moves_from_base_to_tips() {
    // ABOP figure 1.31a.
    let text = "ignore: + - F\naxiom: Fb[+Fa]Fa[-Fa]Fa[+Fa]Fa\nb < a --> b\n";
    let steps = derive(text, 3);
    assert_eq!(steps[1], "Fb[+Fb]Fb[-Fa]Fa[+Fa]Fa");
    assert_eq!(steps[2], "Fb[+Fb]Fb[-Fb]Fb[+Fa]Fa");
    assert_eq!(steps[3], "Fb[+Fb]Fb[-Fb]Fb[+Fb]Fb");
}

#[test]
fn basipetal_signal_moves_down_the_main_axis() {
    // ABOP figure 1.31b: the right context skips branches, so the signal runs down the
    // main axis; apices of branches end their branch and see nothing.
    let text = "ignore: + - F\naxiom: Fa[+Fa]Fa[-Fa]Fa[+Fa]Fb\na > b --> b\n";
    let steps = derive(text, 3);
    assert_eq!(steps[1], "Fa[+Fa]Fa[-Fa]Fb[+Fa]Fb");
    assert_eq!(steps[2], "Fa[+Fa]Fb[-Fa]Fb[+Fa]Fb");
    assert_eq!(steps[3], "Fb[+Fa]Fb[-Fa]Fb[+Fa]Fb");
}

#[test]
fn branch_aware_context_rewrites_only_s() {
    // ABOP section 1.8: BC < S > G[H]M on ABC[DE][SG[HI[JK]L]MNO].
    let rule = "BC < S > G[H]M --> Z\n";
    let steps = derive(&format!("axiom: ABC[DE][SG[HI[JK]L]MNO]\n{rule}"), 1);
    assert_eq!(steps[1], "ABC[DE][ZG[HI[JK]L]MNO]");
    // Without M after the branch, the right context fails.
    let steps = derive(&format!("axiom: ABC[DE][SG[HI[JK]L]NO]\n{rule}"), 1);
    assert_eq!(steps[1], "ABC[DE][SG[HI[JK]L]NO]");
    // With C inside the skipped branch instead, the left context fails.
    let steps = derive(&format!("axiom: AB[C][SG[H]M]\n{rule}"), 1);
    assert_eq!(steps[1], "AB[C][SG[H]M]");
}

#[test]
fn context_modules_bind_their_parameters() {
    let text = "axiom: L(1) S(5) R\nL(u) < S(x) > R : x > u --> S(x + u)\n";
    assert_eq!(derive(text, 2)[1..], ["L(1)S(6)R", "L(1)S(7)R"]);
    let text = "axiom: L(9) S(5) R\nL(u) < S(x) > R : x > u --> S(x + u)\n";
    assert_eq!(derive(text, 1)[1], "L(9)S(5)R");
    let text = "axiom: A(1) B(2) C(3)\nA(a) < B(b) > C(c) --> B(a * 100 + b * 10 + c)\n";
    assert_eq!(derive(text, 1)[1], "A(1)B(123)C(3)");
}

#[test]
fn ignored_modules_are_skipped_on_both_sides() {
    let rules = "b < a --> b\na > c --> c\n";
    let with = derive(&format!("ignore: + -\naxiom: b+-a-+a+c\n{rules}"), 1);
    assert_eq!(with[1], "b+-b-+c+c");
    let without = derive(&format!("axiom: b+-a-+a+c\n{rules}"), 1);
    assert_eq!(without[1], "b+-a-+a+c");
}

#[test]
fn right_context_stops_at_the_end_of_its_branch() {
    let steps = derive("axiom: [A]B\nA > B --> X\n", 1);
    assert_eq!(steps[1], "[A]B");
    let steps = derive("axiom: A[C]B\nA > B --> X\n", 1);
    assert_eq!(steps[1], "X[C]B", "lateral branches are skipped");
    let steps = derive("axiom: A[C]B\nA > [C] B --> X\n", 1);
    assert_eq!(steps[1], "X[C]B", "a branch asked for is entered");
}

#[test]
fn first_matching_rule_wins_and_unmatched_modules_are_copied() {
    let text = "axiom: A(1) A(5) Q\nA(x) : x > 3 --> B\nA(x) --> C\nA(x) --> D\n";
    assert_eq!(derive(text, 1)[1], "CBQ");
}

#[test]
fn rewriting_is_parallel() {
    // Each module sees the old string: a --> b and b --> a swap, they do not cascade.
    assert_eq!(derive("axiom: ab\na --> b\nb --> a\n", 1)[1], "ba");
}

#[test]
fn stochastic_rules_repeat_with_the_same_seed() {
    let text = "axiom: F\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.33\nF --> F : 0.34\n";
    let opts = |seed| DeriveOptions {
        seed: Some(seed),
        ..DeriveOptions::default()
    };
    let a = derive_with(text, 5, &opts(11));
    let b = derive_with(text, 5, &opts(11));
    assert_eq!(a, b);
    let c = derive_with(text, 5, &opts(12));
    assert_ne!(a[5], c[5], "another seed gives another plant");
    // The file's seed is used when none is given.
    let with_seed_line = format!("seed: 11\n{text}");
    assert_eq!(derive(&with_seed_line, 5), a);
}

#[test]
fn stochastic_weights_are_respected_over_many_draws() {
    let axiom = "F".repeat(20_000);
    // Weights need not sum to one: they are normalised among the matching rules.
    let text = format!("axiom: {axiom}\nF --> A : 0.1\nF --> B : 0.3\n");
    let s = &derive(&text, 1)[1];
    let a = s.chars().filter(|&c| c == 'A').count() as f64;
    let expected = 20_000.0 * 0.25;
    let sd = (20_000.0f64 * 0.25 * 0.75).sqrt();
    assert!(
        (a - expected).abs() < 4.0 * sd,
        "{a} A's, expected {expected} ± {sd}"
    );
}

#[test]
fn stochastic_choice_is_among_rules_whose_guards_hold() {
    let text =
        "axiom: A(1) A(5)\nA(x) : x < 3 --> L : 0.5\nA(x) : x >= 3 --> R : 0.5\nA(x) --> N : 0.5\n";
    for seed in 0..20 {
        let s = &derive_with(
            text,
            1,
            &DeriveOptions {
                seed: Some(seed),
                ..DeriveOptions::default()
            },
        )[1];
        let first = &s[..1];
        let second = &s[1..];
        assert!(first == "L" || first == "N", "{s}");
        assert!(second == "R" || second == "N", "{s}");
    }
}

#[test]
fn interpretation_rules_rewrite_for_the_builder_only() {
    let text = "axiom: A\nA --> AB\ninterpretation:\nB --> forward(2) revolute1\n";
    let lsys = lsystem(text);
    let options = DeriveOptions::default();
    let mut d = lsys.derivation(&options).unwrap();
    d.step().unwrap();
    d.step().unwrap();
    assert_eq!(
        lsys.display(d.current()),
        "ABB",
        "derivation never sees interpretation"
    );
    let shown = lsys.interpret(d.current(), 2.0, &options).unwrap();
    assert_eq!(
        squash(&lsys.display(&shown)),
        "Aforward(2)revolute1forward(2)revolute1"
    );
}

#[test]
fn constants_and_functions_evaluate_as_written() {
    let text = "\
define G = 1.5
define H = G * 2
axiom: X(0)
X(z) --> Y(H, 2 + 3 * 4 ^ 2, -2 ^ 2, 2 ^ 3 ^ 2, 7 % 3, min(4, 2, 3), clamp(9, 0, 5), round(2.5), log(1000), ln(e), atan2(1, 1) * 4 / pi)
";
    assert_eq!(derive(text, 1)[1], "Y(3,50,-4,512,1,2,5,3,3,1,1)");
    let text = "axiom: X(0)\nX(z) --> Y(1 < 2, 2 <= 1, 1 == 1, 1 != 1, !0, 1 && 0, 0 || 2, sqrt(16), abs(-3), floor(-1.5), ceil(1.2))\n";
    assert_eq!(derive(text, 1)[1], "Y(1,0,1,0,1,0,1,4,3,-2,2)");
}

#[test]
fn and_or_short_circuit() {
    // The right side would divide by zero if evaluated.
    let text = "axiom: A(0)\nA(x) : x != 0 && 1 / x > 0 --> B\nA(x) : x == 0 || 1 / x > 0 --> C\n";
    assert_eq!(derive(text, 1)[1], "C");
}

#[test]
fn time_is_the_step_number_in_discrete_mode() {
    let text = "axiom: A(0)\nA(x) --> A(t)\n";
    assert_eq!(derive(text, 3)[3], "A(2)");
}

#[test]
fn random_functions_are_seeded_and_in_range() {
    let text = "axiom: A(0)\nA(x) --> A(uniform(2, 3)) N(normal(10, 0.001))\n";
    let a = derive(text, 1);
    assert_eq!(a, derive(text, 1));
    let lsys = lsystem(text);
    let mut d = lsys.derivation(&DeriveOptions::default()).unwrap();
    let s = d.step().unwrap();
    let u = s.params(0)[0];
    let n = s.params(1)[0];
    assert!((2.0..3.0).contains(&u), "{u}");
    assert!((n - 10.0).abs() < 0.01, "{n}");
}

#[test]
fn every_shipped_example_parses_and_derives() {
    for entry in std::fs::read_dir("examples").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "lsys") {
            let lsys = ontogeny::lsystem::LSystem::from_path(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let options = DeriveOptions::default();
            if lsys.is_continuous() {
                let mut dev = lsys
                    .development(&options)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                while dev
                    .advance()
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
                {}
                continue;
            }
            let mut d = lsys.derivation(&options).unwrap();
            for _ in 0..lsys.derivation_length().unwrap_or(1) {
                d.step()
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            }
        }
    }
}

#[test]
fn numbers_in_patterns_must_match() {
    let text = "axiom: A(1) A(2) B(0) C(1, 5) C(2, 5)\nA(1) --> X\nB(z) > C(2, y) --> B(y)\n";
    assert_eq!(derive(text, 1)[1], "XA(2)B(0)C(1,5)C(2,5)");
    let text = "axiom: B(0) C(2, 5)\nB(z) > C(2, y) --> B(y)\nA(-1.5) --> Y\n";
    assert_eq!(derive(text, 1)[1], "B(5)C(2,5)");
}

// ---- derivations cut short where their result is decided, and bounded by a budget ----

/// A grammar that grows one part a step, for a million steps: quadratic work if derived.
const ONE_PART_A_STEP: &str = "axiom: A\nderivation length: 1000000\nA --> forward(0.1) A\n";

/// A grammar whose every step leaves the axiom as it is, for a billion steps.
const STILL: &str = "axiom: A\nderivation length: 1000000000\nA --> A\n";

/// The steps `for_each_frame_until` shows, cut short, with the step each last frame's fixed point began.
fn frames_shown(text: &str, steps: Option<u64>) -> Vec<(u64, String, Option<u64>)> {
    let lsys = lsystem(text);
    let mut shown = Vec::new();
    lsys.for_each_frame_until(&DeriveOptions::default(), steps, |f| {
        shown.push((f.step, lsys.display(f.string), f.fixed_since));
        Ok::<bool, ontogeny::lang::Diagnostic>(true)
    })
    .unwrap();
    shown
}

#[test]
fn a_string_that_a_step_leaves_as_it_was_is_a_fixed_point_at_step_1() {
    assert_eq!(
        frames_shown(STILL, None),
        [
            (0, "A".to_string(), None),
            (1, "A".to_string(), None),
            (1_000_000_000, "A".to_string(), Some(1)),
        ]
    );
    // A string that settles later is a fixed point at the step that changed nothing.
    let shown = frames_shown("axiom: A(0)\nA(x) : x < 3 --> A(x + 1)\n", Some(50));
    let steps: Vec<u64> = shown.iter().map(|s| s.0).collect();
    assert_eq!(steps, [0, 1, 2, 3, 4, 50]);
    assert_eq!(shown[5], (50, "A(3)".to_string(), Some(4)));
}

#[test]
fn a_step_that_reads_the_time_or_chance_is_never_taken_for_a_fixed_point() {
    // Unchanged at steps 1 to 3, then B: a fixed point at step 1 would have kept A.
    let shown = frames_shown("axiom: A\nA : t >= 3 --> B\n", Some(6));
    assert_eq!(shown.len(), 7);
    assert_eq!(shown[6], (6, "B".to_string(), None));
    // A stochastic rule that may keep its module is never a fixed point either.
    let shown = frames_shown("axiom: A\nA --> A : 0.5\nA --> A : 0.5\n", Some(20));
    assert_eq!(shown.len(), 21);
}

#[test]
fn derive_says_where_the_fixed_point_is_and_prints_the_last_step() {
    let dir = crate::util::scratch_dir("derivation-fixed-point");
    let file = dir.join("still.lsys");
    std::fs::write(&file, STILL).unwrap();
    let out = crate::util::ontogeny_ok(&["derive", file.to_str().unwrap(), "--last"]);
    assert_eq!(crate::util::stdout(&out), "1000000000: A\n");
    assert!(
        crate::util::stderr(&out).contains(
            "note: fixed point at step 1: steps 2 to 1000000000 give the same string, so they \
             were not derived"
        ),
        "{}",
        crate::util::stderr(&out)
    );
}

#[test]
fn growing_one_part_a_step_stops_at_the_part_limit_at_step_201() {
    let lsys = lsystem(ONE_PART_A_STEP);
    let build_options = BuildOptions::default();
    let last = grow_last(
        &lsys,
        &DeriveOptions::default(),
        None,
        &build_options,
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(
        last.shortcut,
        Some(Shortcut::PartLimit {
            step: 201,
            limit: 200
        })
    );
    // The last frame is the millionth step's, invalid at its 201st part.
    assert_eq!((last.frame.step, last.frame.t), (1_000_000, 1e6));
    assert_eq!(last.frame.creature.parts.len(), 201);
    assert!(!last.frame.creature.is_valid());
}

#[test]
fn the_creature_the_part_limit_decides_is_the_one_every_step_builds() {
    // Each step grows the main axis and a new branch, whose growth ends two steps later.
    let text = "axiom: A\nA --> forward(0.1) [ left B(2) ] A\n\
                B(n) : n > 0 --> forward(0.2) B(n - 1)\nB(n) : n <= 0 --> leaf\n";
    let lsys = lsystem(text);
    let build_options = BuildOptions {
        max_parts: 30,
        ..BuildOptions::default()
    };
    let options = DeriveOptions::default();
    let last = grow_last(&lsys, &options, Some(40), &build_options, &mut |_| {}).unwrap();
    let every = grow(&lsys, &options, Some(40), &build_options).unwrap();
    assert!(
        matches!(last.shortcut, Some(Shortcut::PartLimit { limit: 30, step }) if step < 40),
        "{:?}",
        last.shortcut
    );
    assert_eq!(Some(&last.frame), every.last());
}

#[test]
fn eval_notes_the_part_limit_step_and_grows_no_further() {
    let dir = crate::util::scratch_dir("derivation-part-limit");
    let file = dir.join("line.lsys");
    std::fs::write(&file, ONE_PART_A_STEP).unwrap();
    let out = crate::util::ontogeny_ok(&["eval", file.to_str().unwrap(), "--task", "walker"]);
    assert!(
        crate::util::stderr(&out).contains(
            "note: more than 200 parts (--max-parts) at step 201, which no later step can undo"
        ),
        "{}",
        crate::util::stderr(&out)
    );
    assert!(
        crate::util::stdout(&out).contains("(invalid)"),
        "{}",
        crate::util::stdout(&out)
    );
}

#[test]
fn the_work_budget_stops_a_derivation_at_the_step_that_would_pass_it() {
    // Step n reads the n modules before it: 44 steps read 990, the 45th would pass 1000.
    let lsys = lsystem(ONE_PART_A_STEP);
    let options = DeriveOptions {
        max_work: 1000,
        ..DeriveOptions::default()
    };
    let e = lsys
        .for_each_frame(&options, None, |_| Ok::<(), ontogeny::lang::Diagnostic>(()))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "at step 45 (a string of 45 modules), the derivation would rewrite more than 1000 \
             modules in all (modules × steps, the work budget): raise it with --max-work"
        ),
        "{e}"
    );
    let dir = crate::util::scratch_dir("derivation-budget");
    let file = dir.join("line.lsys");
    std::fs::write(&file, ONE_PART_A_STEP).unwrap();
    crate::util::assert_bad_input(
        &[
            "derive",
            file.to_str().unwrap(),
            "--last",
            "--max-work",
            "1000",
        ],
        "at step 45 (a string of 45 modules)",
    );
}
