//! Repeat blocks in the `lsystem` genome (Hornby & Pollack's `{ block }(n)`): the `[limits]`
//! key `max_repeat` at 0 leaves the operators as they were; above it, random genomes and
//! mutation make, change and remove blocks within the limits, the text reads back equal, a
//! block builds what a hand count gives, and blocks that would make development run away
//! make the creature invalid, never a panic or a hang.

use crate::util::{assert_bad_input, operators_fingerprint, scratch_dir};

use ontogeny::encoding::lsystem::Item;
use ontogeny::encoding::{Genome, LSystemGenome, LSystemLimits, Rng};
use rand::SeedableRng;

fn rng(seed: u64) -> Rng {
    Rng::seed_from_u64(seed)
}

/// The default limits with repeat blocks of counts up to `most`.
fn repeating(most: usize) -> LSystemLimits {
    LSystemLimits {
        max_repeat: most,
        ..LSystemLimits::default()
    }
}

/// The counts of the genome's repeat blocks, in order.
fn counts(g: &LSystemGenome) -> Vec<usize> {
    g.productions
        .iter()
        .flat_map(|p| p.pairs.iter())
        .flat_map(|pair| pair.successor.iter())
        .filter_map(|item| match item {
            Item::RepeatClose(n) => Some(*n),
            _ => None,
        })
        .collect()
}

/// A genome text of one production `P0` rewritten once into `successor`.
fn one_step(successor: &str) -> String {
    format!("derivation length: 1\naxiom: P0(0, 0)\n\nP0(n0, n1) --> {successor}\n")
}

#[test]
fn without_repeat_blocks_the_operators_draw_what_they_drew_before() {
    // The fingerprint pinned before the genome had repeat blocks (it is also the default's,
    // in `genome_plastic_lsystem`): the key at 0 must reproduce it to the bit.
    assert_eq!(
        operators_fingerprint::<LSystemGenome>(&repeating(0)),
        "f2d30153db4574827ef54bd535a1688a75ec4565a6c90df0f77fb8492e96337a"
    );
    let mut r = rng(3);
    for _ in 0..200 {
        let g = LSystemGenome::random(&repeating(0), &mut r);
        assert!(counts(&g).is_empty());
        assert!(!g.to_text().contains('{'));
    }
}

#[test]
fn random_genomes_hold_repeat_blocks_at_a_measured_rate() {
    let limits = repeating(4);
    let mut r = rng(11);
    let n = 1000;
    let mut with_blocks = 0;
    let mut all_counts = Vec::new();
    for _ in 0..n {
        let g = LSystemGenome::random(&limits, &mut r);
        assert_eq!(g.check(&limits), Ok(()));
        let c = counts(&g);
        with_blocks += usize::from(!c.is_empty());
        all_counts.extend(c);
    }
    // A random run draws a block with chance 0.06 wherever three items or more are left;
    // a random genome has on average 4.5 productions of 2 pairs of about 8 items, so some
    // some tens of draws where a block may start, and most genomes hold one (measured: 82.4%
    // of these 1000). The band only says "most, not all".
    let rate = with_blocks as f64 / n as f64;
    assert!((0.7..0.95).contains(&rate), "{rate}");
    // Counts are drawn uniformly from 2 to 4.
    for k in 2..=4 {
        let share = all_counts.iter().filter(|&&c| c == k).count() as f64 / all_counts.len() as f64;
        assert!((share - 1.0 / 3.0).abs() < 0.05, "count {k}: {share}");
    }
    assert!(all_counts.iter().all(|c| (2..=4).contains(c)));
}

#[test]
fn mutation_and_crossover_keep_counts_in_range_and_the_text_reads_back_equal() {
    let limits = repeating(4);
    let mut r = rng(7);
    let mut seen_counts = [false; 5];
    let (mut grew, mut shrank) = (false, false);
    for seed in 0..20 {
        let mut r2 = rng(seed);
        let mut a = LSystemGenome::random(&limits, &mut r2);
        let b = LSystemGenome::random(&limits, &mut r2);
        for _ in 0..50 {
            let before = counts(&a).len();
            a = a.mutate(&limits, 0.3, &mut r);
            let after = counts(&a).len();
            grew |= after > before;
            shrank |= after < before;
            a = a.crossover(&b, &limits, &mut r).unwrap();
            if let Some(m) = a.mirroring_crossover(&b, &limits, &mut r) {
                a = m;
            }
            assert_eq!(a.check(&limits), Ok(()), "{}", a.to_text());
            for c in counts(&a) {
                assert!((2..=4).contains(&c), "{c}");
                seen_counts[c] = true;
            }
            let back = LSystemGenome::read_text(&a.to_text(), &limits).unwrap();
            assert_eq!(back, a);
        }
    }
    assert_eq!(seen_counts, [false, false, true, true, true]);
    assert!(grew && shrank, "mutation both adds and removes blocks");
}

#[test]
fn a_repeat_block_builds_what_a_hand_count_gives() {
    let limits = repeating(4);
    // Three passes of one part: three parts in a row, as the string written out builds.
    let g = LSystemGenome::read_text(&one_step("{ forward(0.5) }(3)"), &limits).unwrap();
    assert_eq!(
        g.to_text().lines().last(),
        Some("P0(n0, n1) --> { forward(0.5) }(3)")
    );
    let c = g.develop(&limits, 0).unwrap();
    assert!(c.is_valid(), "{:?}", c.problems);
    assert_eq!(c.parts.len(), 3);
    let written =
        LSystemGenome::read_text(&one_step("forward(0.5) forward(0.5) forward(0.5)"), &limits)
            .unwrap();
    assert_eq!(written.develop(&limits, 0).unwrap().parts, c.parts);
    // Nested: a root, then 2 x (a part and 3 x a jointed part) = 1 + 2 * 4 = 9 parts, 8
    // joints of which 6 are revolute.
    let g = LSystemGenome::read_text(
        &one_step("forward(0.5) { forward(0.3) { revolute1 forward(0.2) }(3) }(2)"),
        &limits,
    )
    .unwrap();
    let c = g.develop(&limits, 0).unwrap();
    assert!(c.is_valid(), "{:?}", c.problems);
    assert_eq!((c.parts.len(), c.joints.len()), (9, 8));
    // A count above the limit is refused where the genome is read, with the key named.
    let e = LSystemGenome::read_text(&one_step("{ forward(0.5) }(5)"), &limits).unwrap_err();
    assert!(
        e.0.contains("repeats a block 5 times, not 2 to 4 (max_repeat)"),
        "{e}"
    );
    let e = LSystemGenome::read_text(&one_step("{ forward(0.5) }(2)"), &repeating(0)).unwrap_err();
    assert!(e.0.contains("the limits allow none (max_repeat 0)"), "{e}");
}

#[test]
fn nested_blocks_past_the_work_budget_make_the_creature_invalid() {
    // 100 x 100 x 100 turns: a million modules for the builder, far past the genome's
    // budget of max_modules (1000) in all.
    let limits = repeating(100);
    let text = one_step("forward(0.5) { { { left }(100) }(100) }(100) forward(0.5)");
    let g = LSystemGenome::read_text(&text, &limits).unwrap();
    let c = g.develop(&limits, 0).unwrap();
    assert!(!c.is_valid());
    let said: Vec<&str> = c.problems.iter().map(|p| p.message.as_str()).collect();
    // The string is 9 modules: 991 more may be interpreted.
    assert!(
        said.iter().any(|m| m.contains(
            "repeat blocks make the builder interpret more than 991 modules beyond the string's own"
        )),
        "{said:?}"
    );
    // The same blocks within the budget (2 x 2 x 2 turns) build both parts.
    let text = one_step("forward(0.5) { { { left }(2) }(2) }(2) forward(0.5)");
    let g = LSystemGenome::read_text(&text, &limits).unwrap();
    let c = g.develop(&limits, 0).unwrap();
    assert!(c.is_valid(), "{:?}", c.problems);
    assert_eq!(c.parts.len(), 2);
}

#[test]
fn a_seed_with_repeat_blocks_widens_max_repeat() {
    let text = "derivation length: 1\naxiom: A(1)\nA(x) --> forward(1) { revolute1 forward(0.5) output(1) }(3)\n";
    let s = LSystemGenome::seed_from_lsys("seed.lsys", text, &LSystemLimits::default()).unwrap();
    assert_eq!(s.limits.max_repeat, 3);
    assert!(
        s.notes.iter().any(|n| n.contains("max_repeat 0 → 3")),
        "{:?}",
        s.notes
    );
    assert_eq!(counts(&s.genome), vec![3]);
    // A count the genome cannot hold is refused where it is written.
    let text = "derivation length: 1\naxiom: A(1)\nA(x) --> { forward(1) }(x)\n";
    let e =
        LSystemGenome::seed_from_lsys("seed.lsys", text, &LSystemLimits::default()).unwrap_err();
    assert!(
        e.0.contains("line 3, column 25: a repeat block's count in the genome is a whole number of 2 to 100, not 'x'"),
        "{e}"
    );
}

#[test]
fn a_config_refuses_a_repeat_bound_out_of_its_range() {
    let dir = scratch_dir("lsystem-repeat-config");
    let config = dir.join("bad.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem\"\n\n[limits]\nmax_repeat = 1\n",
    )
    .unwrap();
    assert_bad_input(
        &[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            dir.join("run").to_str().unwrap(),
        ],
        "max_repeat must be 0 (no repeat blocks) or 2 to 100, not 1",
    );
}
