//! The L-system genome's operators: random productions and successors drawn within the
//! limits, mutation of successors, conditions and arguments, and crossover of productions.

use super::*;
use crate::encoding::draw::{clamp_rate, on_grid, perturb_stepwise, uniform_on_grid};

// ---- random pieces -------------------------------------------------------------------

/// A random value of `range` on the grid of `quantum`.
pub(super) fn random_constant(kind: Argument, rng: &mut Rng) -> f64 {
    let (lo, hi) = range(kind);
    let q = quantum(kind);
    let steps = ((hi - lo) / q).round() as u64;
    on_grid(lo + rng.random_range(0..=steps) as f64 * q, GRID)
}

/// A random command drawn by [`draw_weight`], with a random constant argument when it takes
/// one.
pub(crate) fn random_command(rng: &mut Rng) -> Item {
    let total: u32 = Command::ALL.into_iter().map(draw_weight).sum();
    let mut draw = rng.random_range(0..total);
    let mut command = Command::Forward;
    for c in Command::ALL {
        if draw < draw_weight(c) {
            command = c;
            break;
        }
        draw -= draw_weight(c);
    }
    let kind = command.argument();
    let arg = (kind != Argument::None).then(|| Arg::Const(random_constant(kind, rng)));
    Item::Command(command, arg)
}

/// A random argument of a production call: mostly a parameter expression.
pub(super) fn random_call_arg(params: usize, rng: &mut Rng) -> Arg {
    if params == 0 || rng.random_bool(0.25) {
        return Arg::Const(uniform_on_grid(rng, PARAM_RANGE, GRID));
    }
    let i = rng.random_range(0..params);
    if rng.random_bool(0.75) {
        // Mostly counting down, so that recursion ends by a condition.
        Arg::Plus(i, on_grid(rng.random_range(-2..=1) as f64, GRID))
    } else {
        Arg::Times(i, uniform_on_grid(rng, (0.0, 1.5), GRID))
    }
}

/// A random call from a successor of production `home`: half the time of the next
/// production, so that random genomes use most of their productions.
pub(super) fn random_call(home: usize, productions: usize, params: usize, rng: &mut Rng) -> Item {
    let target = if home + 1 < productions && rng.random_bool(0.5) {
        home + 1
    } else {
        rng.random_range(0..productions.max(1))
    };
    Item::Call(
        target,
        (0..params).map(|_| random_call_arg(params, rng)).collect(),
    )
}

pub(super) fn random_condition(params: usize, rng: &mut Rng) -> Option<Condition> {
    (params > 0).then(|| Condition {
        param: rng.random_range(0..params),
        compare: Compare::ALL[rng.random_range(0..4)],
        value: uniform_on_grid(rng, PARAM_RANGE, GRID),
        read: false,
    })
}

/// The chance that a random run, where three items or more are left to draw, draws a
/// repeat block next (when the limits allow blocks): about as often as a branch, so that
/// about half of the random genomes of the default sizes hold one.
const REPEAT_CHANCE: f64 = 0.06;

/// A random, well-nested run of exactly `len` items for a successor of production `home` of
/// a genome of `productions` productions, with repeat blocks of counts 2 to `repeat` (none
/// when `repeat` is below 2: then nothing more is drawn than before the genome had blocks);
/// with `productions == 0` (the direct genome) a run of commands and brackets only, where a
/// call would have been a random command.
pub(crate) fn random_run(
    len: usize,
    home: usize,
    productions: usize,
    params: usize,
    repeat: usize,
    rng: &mut Rng,
) -> Vec<Item> {
    let mut out = Vec::with_capacity(len);
    push_random_run(&mut out, len, home, productions, params, repeat, rng);
    out
}

pub(super) fn push_random_run(
    out: &mut Vec<Item>,
    len: usize,
    home: usize,
    productions: usize,
    params: usize,
    repeat: usize,
    rng: &mut Rng,
) {
    let mut left = len;
    while left > 0 {
        if repeat >= 2 && left >= 3 && rng.random_bool(REPEAT_CHANCE) {
            // A repeat block around a shorter run.
            let inner = rng.random_range(1..=(left - 2).min(6));
            out.push(Item::RepeatOpen);
            push_random_run(out, inner, home, productions, params, repeat, rng);
            out.push(Item::RepeatClose(rng.random_range(2..=repeat)));
            left -= inner + 2;
            continue;
        }
        let draw = rng.random_range(0..100);
        if draw < 12 && left >= 3 {
            // A branch around a shorter run.
            let inner = rng.random_range(1..=(left - 2).min(6));
            out.push(Item::Push);
            push_random_run(out, inner, home, productions, params, repeat, rng);
            out.push(Item::Pop);
            left -= inner + 2;
        } else if draw < 24 {
            out.push(if productions == 0 {
                random_command(rng)
            } else {
                random_call(home, productions, params, rng)
            });
            left -= 1;
        } else if draw < 36 && left >= 3 {
            // A driven segment: a joint, the part it moves, and an output driving it.
            let joint = [
                Command::Revolute1,
                Command::Revolute2,
                Command::Twist90,
                Command::Twist180,
            ][rng.random_range(0..4)];
            out.push(Item::Command(joint, None));
            for c in [Command::Forward, Command::Output] {
                let kind = c.argument();
                out.push(Item::Command(
                    c,
                    Some(Arg::Const(random_constant(kind, rng))),
                ));
            }
            left -= 3;
        } else {
            out.push(random_command(rng));
            left -= 1;
        }
    }
}

/// The kind of bracket an item opens or closes: `[` `]` (0), `{` `}(n)` (1); `None` for
/// any other item.
fn bracket(item: &Item) -> Option<(bool, u8)> {
    match item {
        Item::Push => Some((true, 0)),
        Item::Pop => Some((false, 0)),
        Item::RepeatOpen => Some((true, 1)),
        Item::RepeatClose(_) => Some((false, 1)),
        _ => None,
    }
}

/// Drops brackets and repeat-block ends that have no partner, so that a successor is well
/// nested: a close goes when the innermost open item is not of its kind (or there is none),
/// an open item that is never closed goes. Only removes items, so it never breaks a limit.
pub(crate) fn balance(items: &mut Vec<Item>) {
    let mut open: Vec<(usize, u8)> = Vec::new();
    let mut drop = vec![false; items.len()];
    for (k, item) in items.iter().enumerate() {
        match bracket(item) {
            Some((true, kind)) => open.push((k, kind)),
            Some((false, kind)) => match open.last() {
                Some(&(_, top)) if top == kind => {
                    open.pop();
                }
                _ => drop[k] = true,
            },
            None => {}
        }
    }
    for (k, _) in open {
        drop[k] = true;
    }
    let mut k = 0;
    items.retain(|_| {
        k += 1;
        !drop[k - 1]
    });
}

/// Whether every `[` of `items` has its `]` and every `{` its `}(n)`, well nested (no
/// `[ { ] }`).
pub(crate) fn is_balanced(items: &[Item]) -> bool {
    let mut open: Vec<u8> = Vec::new();
    for item in items {
        match bracket(item) {
            Some((true, kind)) => open.push(kind),
            Some((false, kind)) if open.pop() != Some(kind) => return false,
            _ => {}
        }
    }
    open.is_empty()
}

/// A repeat count of 2 to `most` moved one step up or down (Hornby & Pollack's "perturbing
/// a parameter of a command by adding or subtracting a small value"), back inside at either
/// end.
fn perturbed_count(n: usize, most: usize, rng: &mut Rng) -> usize {
    let up = rng.random_bool(0.5);
    let n = if up { n + 1 } else { n.saturating_sub(1) };
    match n {
        n if n > most => most.saturating_sub(1).max(2),
        n if n < 2 => 3.min(most),
        n => n,
    }
}

/// The ends `b` such that `items[at..b]` is a well-nested run that does not leave the
/// bracket or block `at` stands in (empty when `items[at]` closes one).
fn nested_ends(items: &[Item], at: usize) -> Vec<usize> {
    let mut ends = Vec::new();
    let mut depth = 0usize;
    for (k, item) in items.iter().enumerate().skip(at) {
        match bracket(item) {
            Some((true, _)) => depth += 1,
            Some((false, _)) if depth == 0 => break,
            Some((false, _)) => depth -= 1,
            None => {}
        }
        if depth == 0 {
            ends.push(k + 1);
        }
    }
    ends
}

/// Wraps a random well-nested run of a well-nested `successor` in a new repeat block of a
/// count of 2 to `most`.
fn wrap_in_block(successor: &mut Vec<Item>, most: usize, rng: &mut Rng) {
    // A block starts at any item but a close (from which no run stays inside).
    let starts: Vec<usize> = (0..successor.len())
        .filter(|&k| !matches!(bracket(&successor[k]), Some((false, _))))
        .collect();
    if starts.is_empty() {
        return;
    }
    let at = starts[rng.random_range(0..starts.len())];
    let ends = nested_ends(successor, at);
    if ends.is_empty() {
        return;
    }
    let end = ends[rng.random_range(0..ends.len())];
    let n = rng.random_range(2..=most);
    successor.insert(end, Item::RepeatClose(n));
    successor.insert(at, Item::RepeatOpen);
}

/// Removes a random repeat block's `{` and `}(n)` of a well-nested `successor`, keeping what
/// they enclose; does nothing (and draws nothing) when it has none.
fn unwrap_block(successor: &mut Vec<Item>, rng: &mut Rng) {
    let opens: Vec<usize> = (0..successor.len())
        .filter(|&k| matches!(successor[k], Item::RepeatOpen))
        .collect();
    if opens.is_empty() {
        return;
    }
    let at = opens[rng.random_range(0..opens.len())];
    // The close that ends the block: the last of the well-nested runs from `at`.
    if let Some(&end) = nested_ends(successor, at).first() {
        successor.remove(end - 1);
        successor.remove(at);
    }
}
impl LSystemGenome {
    /// Removes production `k`: calls of it disappear and later productions move down one.
    pub(super) fn remove_production(&mut self, k: usize) {
        self.productions.remove(k);
        for p in &mut self.productions {
            for pair in &mut p.pairs {
                pair.successor
                    .retain(|item| !matches!(item, Item::Call(t, _) if *t == k));
                for item in &mut pair.successor {
                    if let Item::Call(t, _) = item
                        && *t > k
                    {
                        *t -= 1;
                    }
                }
                balance(&mut pair.successor);
            }
        }
    }

    /// A random production `P<home>` of a genome of `productions` productions.
    pub(super) fn random_production(
        home: usize,
        productions: usize,
        limits: &LSystemLimits,
        rng: &mut Rng,
    ) -> Production {
        let params = limits.param_count();
        let count = rng.random_range(1..=limits.pairs());
        let pairs = (0..count)
            .map(|k| {
                let len = if limits.max_successor == 0 {
                    0
                } else {
                    rng.random_range(1..=limits.max_successor)
                };
                Pair {
                    // The last pair applies whatever the parameters: a production always
                    // rewrites.
                    condition: if k + 1 == count {
                        None
                    } else {
                        random_condition(params, rng)
                    },
                    successor: random_run(len, home, productions, params, limits.max_repeat, rng),
                }
            })
            .collect();
        Production { pairs, read: None }
    }

    /// Mutates one successor in place (its items and runs). Repeat blocks are build commands
    /// as Hornby & Pollack's mutation sees them: a block's count is a parameter, perturbed
    /// one step; an inserted run may hold blocks; a deleted run takes the ends of blocks it
    /// cuts (what they enclosed stays). Where the limits allow blocks, each successor also
    /// has a block wrapped around one of its well-nested runs, and one of its blocks
    /// unwrapped, each with probability `rate`.
    pub(super) fn mutate_successor(
        successor: &mut Vec<Item>,
        home: usize,
        productions: usize,
        limits: &LSystemLimits,
        rate: f64,
        rng: &mut Rng,
    ) {
        let params = limits.param_count();
        for item in successor.iter_mut() {
            // Replace a command (or call) by another.
            if rng.random_bool(rate) && bracket(item).is_none() {
                *item = if rng.random_bool(0.8) {
                    random_command(rng)
                } else {
                    random_call(home, productions, params, rng)
                };
            }
            // Perturb a parameter.
            if rng.random_bool(rate) {
                match item {
                    Item::Command(c, Some(arg)) => perturb_argument(*c, arg, rng),
                    Item::Call(_, args) if !args.is_empty() => {
                        let k = rng.random_range(0..args.len());
                        let arg = &mut args[k];
                        let range = match arg {
                            Arg::Const(_) => PARAM_RANGE,
                            _ => OFFSET_RANGE,
                        };
                        let v = arg.constant_mut();
                        *v = perturb_stepwise(*v, range, 1.0 / GRID, GRID, rng);
                    }
                    Item::RepeatClose(n) => *n = perturbed_count(*n, limits.max_repeat, rng),
                    _ => {}
                }
            }
        }
        // Insert a run of commands.
        let room = limits.max_successor.saturating_sub(successor.len());
        if room > 0 && rng.random_bool(rate) {
            let len = rng.random_range(1..=room.min(MAX_RUN));
            let at = rng.random_range(0..=successor.len());
            let run = random_run(len, home, productions, params, limits.max_repeat, rng);
            successor.splice(at..at, run);
        }
        // Delete a run.
        if !successor.is_empty() && rng.random_bool(rate) {
            let len = rng.random_range(1..=successor.len().min(MAX_RUN));
            let at = rng.random_range(0..=successor.len() - len);
            successor.drain(at..at + len);
        }
        balance(successor);
        // Wrap a run in a repeat block, unwrap a block: only where the limits allow blocks,
        // so that without them nothing more is drawn.
        if limits.max_repeat >= 2 {
            if successor.len() + 2 <= limits.max_successor && rng.random_bool(rate) {
                wrap_in_block(successor, limits.max_repeat, rng);
            }
            if successor.contains(&Item::RepeatOpen) && rng.random_bool(rate) {
                unwrap_block(successor, rng);
            }
        }
    }
}
/// Perturbs the argument of command `c`: a constant within the argument's range and on its
/// grid, the constant of a parameter expression within [`OFFSET_RANGE`].
pub(crate) fn perturb_argument(c: Command, arg: &mut Arg, rng: &mut Rng) {
    let kind = c.argument();
    let (range, quantum) = match arg {
        Arg::Const(_) => (range(kind), quantum(kind)),
        _ => (OFFSET_RANGE, 1.0 / GRID),
    };
    let v = arg.constant_mut();
    *v = perturb_stepwise(*v, range, quantum, GRID, rng);
}

/// Picks a contiguous run of `items` of at most `max` items (possibly empty).
pub(crate) fn pick_run(items: &[Item], max: usize, rng: &mut Rng) -> std::ops::Range<usize> {
    if items.is_empty() || max == 0 {
        return 0..0;
    }
    let len = rng.random_range(1..=items.len().min(max));
    let at = rng.random_range(0..=items.len() - len);
    at..at + len
}
impl LSystemGenome {
    /// A random genome within `limits`.
    pub(super) fn random_genome(limits: &LSystemLimits, rng: &mut Rng) -> Self {
        let count = rng.random_range(1..=limits.productions());
        let productions = (0..count)
            .map(|home| LSystemGenome::random_production(home, count, limits, rng))
            .collect();
        let mut genome = LSystemGenome {
            start: (0..limits.param_count())
                .map(|_| uniform_on_grid(rng, PARAM_RANGE, GRID))
                .collect(),
            derivation_length: limits.derivation_length,
            productions,
            environment: Vec::new(),
            projectile: limits.projectile,
        };
        genome.add_random_reads(limits, rng);
        genome
    }

    /// A mutant: every mutation site changes with probability `rate`.
    pub(super) fn mutant(&self, limits: &LSystemLimits, rate: f64, rng: &mut Rng) -> Self {
        let rate = clamp_rate(rate);
        let params = limits.param_count();
        let mut g = self.clone();
        for v in &mut g.start {
            if rng.random_bool(rate) {
                *v = perturb_stepwise(*v, PARAM_RANGE, 1.0 / GRID, GRID, rng);
            }
        }
        // Delete a production (never the start), then perhaps add one.
        if g.productions.len() > 1 && rng.random_bool(rate) {
            let k = rng.random_range(1..g.productions.len());
            g.remove_production(k);
        }
        if g.productions.len() < limits.productions() && rng.random_bool(rate) {
            let n = g.productions.len() + 1;
            let p = LSystemGenome::random_production(n - 1, n, limits, rng);
            g.productions.push(p);
        }
        let n = g.productions.len();
        for (home, p) in g.productions.iter_mut().enumerate() {
            // Delete a pair, or add one before the last (the last often has no condition).
            if p.pairs.len() > 1 && rng.random_bool(rate) {
                let k = rng.random_range(0..p.pairs.len());
                p.pairs.remove(k);
            }
            if p.pairs.len() < limits.pairs() && rng.random_bool(rate) {
                let len = rng.random_range(0..=limits.max_successor);
                let pair = Pair {
                    condition: random_condition(params, rng),
                    successor: random_run(len, home, n, params, limits.max_repeat, rng),
                };
                let at = rng.random_range(0..p.pairs.len());
                p.pairs.insert(at, pair);
            }
            for pair in &mut p.pairs {
                // Change a condition: perturb its constant, or draw a new one (or none).
                if rng.random_bool(rate) {
                    pair.condition = match pair.condition {
                        Some(c) if rng.random_bool(0.5) => {
                            Some(super::reads::perturbed_condition(c, rng))
                        }
                        _ if rng.random_bool(0.2) => None,
                        _ => random_condition(params, rng),
                    };
                }
                LSystemGenome::mutate_successor(&mut pair.successor, home, n, limits, rate, rng);
            }
        }
        g.mutate_reads(limits, rate, rng);
        g.fit_environment();
        // Last, so that a run whose projectile does not evolve draws as it always has.
        g.projectile = crate::encoding::projectile::mutated(
            g.projectile,
            limits.projectile,
            rate,
            crate::encoding::projectile::Step::Stepwise,
            rng,
        );
        g
    }

    /// A child by crossover of productions, or `None` when there is none to make.
    pub(super) fn child(
        &self,
        other: &Self,
        limits: &LSystemLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        let mut child = self.clone();
        let n = child.productions.len();
        let params = limits.param_count();
        // The donor: one successor of the other parent.
        let donor: Vec<&Vec<Item>> = other.successors().collect();
        let receivers = crate::encoding::index_pairs(&child.productions, |p| p.pairs.len());
        if donor.is_empty() || receivers.is_empty() {
            return Some(child);
        }
        let from = donor[rng.random_range(0..donor.len())];
        let (i, j) = receivers[rng.random_range(0..receivers.len())];
        let target = &mut child.productions[i].pairs[j].successor;
        // Calls into productions the child lacks wrap round; arguments fit the child's
        // parameter count.
        let adapt = |item: &Item| super::mirror::adapted(item, n, params);
        match rng.random_range(0..3) {
            0 => {
                // Replace the whole successor.
                *target = from.iter().take(limits.max_successor).map(adapt).collect();
            }
            1 => {
                // Insert a run of the donor.
                let room = limits.max_successor.saturating_sub(target.len());
                let run = pick_run(from, room.min(limits.max_successor), rng);
                let at = rng.random_range(0..=target.len());
                let piece: Vec<Item> = from[run].iter().map(adapt).collect();
                target.splice(at..at, piece);
            }
            _ => {
                // Replace a run with a run of the donor.
                let out = pick_run(target, target.len(), rng);
                let room = limits
                    .max_successor
                    .saturating_sub(target.len() - out.len());
                let run = pick_run(from, room, rng);
                let piece: Vec<Item> = from[run].iter().map(adapt).collect();
                target.splice(out, piece);
            }
        }
        balance(target);
        if other.environment.len() > child.environment.len() {
            child.environment = other.environment.clone();
        }
        child.fit_environment();
        Some(child)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn fwd(l: f64) -> Item {
        Item::Command(Command::Forward, Some(Arg::Const(l)))
    }

    #[test]
    fn balance_drops_only_unpartnered_brackets() {
        let mut items = vec![
            Item::Pop,
            Item::Push,
            fwd(1.0),
            Item::Push,
            Item::Pop,
            Item::Push,
        ];
        assert!(!is_balanced(&items));
        balance(&mut items);
        // `]` first has nothing to close; the `[` before `f` and the last are never closed.
        assert_eq!(items, vec![fwd(1.0), Item::Push, Item::Pop]);
        assert!(is_balanced(&items));
        let kept = items.clone();
        balance(&mut items);
        assert_eq!(items, kept);
    }

    #[test]
    fn a_repeat_count_moves_one_step_and_stays_in_range() {
        let mut rng = Rng::seed_from_u64(4);
        let mut seen = std::collections::BTreeSet::new();
        for _ in 0..200 {
            for (n, most, allowed) in [
                (2, 4, &[3][..]),
                (3, 4, &[2, 4][..]),
                (4, 4, &[3][..]),
                (2, 2, &[2][..]),
            ] {
                let m = perturbed_count(n, most, &mut rng);
                assert!(allowed.contains(&m), "{n} of at most {most}: {m}");
                seen.insert((n, most, m));
            }
        }
        assert_eq!(seen.len(), 5);
    }

    #[test]
    fn blocks_are_wrapped_around_well_nested_runs_and_unwrapped_keeping_their_items() {
        let mut rng = Rng::seed_from_u64(9);
        let start = vec![fwd(1.0), Item::Push, fwd(2.0), Item::Pop, fwd(3.0)];
        for _ in 0..200 {
            let mut s = start.clone();
            wrap_in_block(&mut s, 4, &mut rng);
            assert!(is_balanced(&s), "{s:?}");
            assert_eq!(s.len(), start.len() + 2);
            let mut kept = s.clone();
            kept.retain(|i| !matches!(i, Item::RepeatOpen | Item::RepeatClose(_)));
            assert_eq!(kept, start);
            unwrap_block(&mut s, &mut rng);
            assert_eq!(s, start);
        }
        // A typed balance: `[ { ] }` keeps the block, drops the bracket's ends.
        let mut items = vec![
            Item::Push,
            Item::RepeatOpen,
            fwd(1.0),
            Item::Pop,
            Item::RepeatClose(2),
        ];
        assert!(!is_balanced(&items));
        balance(&mut items);
        assert_eq!(
            items,
            vec![Item::RepeatOpen, fwd(1.0), Item::RepeatClose(2)]
        );
    }

    #[test]
    fn perturbation_stays_in_range_and_on_the_grid() {
        let mut rng = Rng::seed_from_u64(3);
        let mut turn = 1.0;
        let mut length = 0.2;
        for _ in 0..1000 {
            turn = perturb_stepwise(
                turn,
                range(Argument::Turn),
                quantum(Argument::Turn),
                GRID,
                &mut rng,
            );
            assert!(turn == 0.5 || turn == 1.0, "{turn}");
            let before = length;
            length = perturb_stepwise(length, range(Argument::Length), 1.0 / GRID, GRID, &mut rng);
            assert!((0.2..=1.2).contains(&length));
            // A tenth of the range at most, plus rounding.
            assert!((length - before).abs() <= 0.1 + 1e-9);
            assert_eq!(length, on_grid(length, GRID));
            assert_eq!(format!("{length}").parse::<f64>().unwrap(), length);
        }
        let index = perturb_stepwise(0.0, range(Argument::Index), 1.0, GRID, &mut rng);
        assert!(index == 0.0 || index == 1.0);
    }

    #[test]
    fn random_constants_cover_their_grid() {
        let mut rng = Rng::seed_from_u64(1);
        let mut seen = [false; 3];
        for _ in 0..200 {
            let f = random_constant(Argument::Function, &mut rng);
            assert_eq!(f, f.round());
            seen[f as usize] = true;
        }
        assert_eq!(seen, [true; 3]);
    }

    #[test]
    fn removing_a_production_drops_its_calls_and_renumbers_the_rest() {
        let call = |t| Item::Call(t, vec![]);
        let production = |successor| Production {
            pairs: vec![Pair {
                condition: None,
                successor,
            }],
            read: None,
        };
        let mut g = LSystemGenome {
            start: vec![],
            derivation_length: 2,
            productions: vec![
                production(vec![call(1), Item::Push, call(2), Item::Pop, call(0)]),
                production(vec![fwd(1.0)]),
                production(vec![call(1)]),
            ],
            environment: Vec::new(),
            projectile: None,
        };
        g.remove_production(1);
        assert_eq!(
            g.productions[0].pairs[0].successor,
            vec![Item::Push, call(1), Item::Pop, call(0)]
        );
        assert!(g.productions[1].pairs[0].successor.is_empty());
        let limits = LSystemLimits {
            params: 0,
            ..LSystemLimits::default()
        };
        assert_eq!(g.check(&limits), Ok(()));
        assert_eq!(
            g.to_text().lines().skip(1).collect::<Vec<_>>(),
            [
                "derivation length: 2",
                "axiom: P0",
                "",
                "P0 --> [ P1 ] P0",
                "P1 -->",
            ]
        );
    }
}
