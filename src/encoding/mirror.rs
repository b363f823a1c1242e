//! Walking with Dinosaurs' crossover (3.3.1) over the genomes that are strings of building
//! commands (`lsystem`, `lsystem-continuous`, `direct`): what a part of such a string is, and
//! the choice of the part copied and of the place it goes.
//!
//! The report's parts are "complete parts": a body part with its joint and everything that
//! grows from it, never the root. A turtle string has two shapes of them ([`parts`]):
//!
//! - a **branch**: a `[`, its matching `]` and what lies between. The turtle builds a branch
//!   from where it stands and comes back after it, so a branch is a whole sub-assembly hung
//!   from one place;
//! - a **tail**: a part built after another at the same bracket level (the turtle went on from
//!   the first), with the turns, joint and other commands that place it since the part before
//!   it, and everything after it to the end of its level (its branch, or the string). What the
//!   turtle builds after a part hangs from that part, so a tail is the part's whole subtree.
//!   The first part of a string (the root, in the direct genome) is never a tail.
//!
//! A copy of either is a branch (a tail gets the brackets it lacks), and it replaces a branch
//! or a tail of the receiving string; a string that has neither gets the copy inserted at one
//! of its places. The string genomes turn a copied part half a turn about the turtle's up axis
//! where the copy starts (the attachment's vertical axis, for a body lying on the ground): a
//! limb that left its parent to one side leaves it to the other, and what pointed down still
//! points down (a leg stays a leg). A copy that went straight on folds back onto its parent
//! after the half turn; such a newborn's parts interpenetrate, and it is treated as any other
//! such newborn. The turn is the copy's first item after its `[`; a copy that already starts
//! with a half turn loses it instead (two half turns are none), so repeated copies never
//! lengthen the string.

use std::ops::Range;

use rand::RngExt;

use super::Rng;

/// What a string genome's items are to its crossover: brackets, what builds a part, and the
/// items of a half turn each way.
pub(crate) struct Shape<T: 'static> {
    /// Whether an item is `[`.
    pub is_push: fn(&T) -> bool,
    /// Whether an item is `]`.
    pub is_pop: fn(&T) -> bool,
    /// Whether an item builds (or may build) a part.
    pub is_body: fn(&T) -> bool,
    /// `[` and `]`.
    pub brackets: fn() -> [T; 2],
    /// A half turn about the turtle's up axis.
    pub turn: &'static [T],
    /// The same half turn written the other way.
    pub back: &'static [T],
}

/// The parts of `items` (see the module documentation): each branch, with its brackets, and
/// each tail, in the order of their first item (a branch before a tail that starts with it).
pub(crate) fn parts<T>(items: &[T], shape: &Shape<T>) -> Vec<Range<usize>> {
    /// A bracket level: where a tail may start (after the last part or bracket), whether a
    /// part was built at it, and the starts of its tails.
    struct Level {
        boundary: usize,
        built: bool,
        tails: Vec<usize>,
    }
    let level = |boundary| Level {
        boundary,
        built: false,
        tails: Vec::new(),
    };
    let mut found = Vec::new();
    let mut open: Vec<(usize, Level)> = vec![(0, level(0))];
    for (k, item) in items.iter().enumerate() {
        if (shape.is_push)(item) {
            open.push((k, level(k + 1)));
        } else if (shape.is_pop)(item) {
            if open.len() < 2 {
                continue; // a `]` without its `[`
            }
            let (start, closed) = open.pop().expect("two levels are open");
            found.push(start..k + 1);
            found.extend(closed.tails.into_iter().map(|t| t..k));
            if let Some((_, outer)) = open.last_mut() {
                outer.boundary = k + 1;
            }
        } else if (shape.is_body)(item)
            && let Some((_, current)) = open.last_mut()
        {
            if current.built {
                current.tails.push(current.boundary);
            }
            current.built = true;
            current.boundary = k + 1;
        }
    }
    // Levels left open (a `[` without its `]`) end with the string.
    for (_, unclosed) in open {
        found.extend(unclosed.tails.into_iter().map(|t| t..items.len()));
    }
    found.sort_by_key(|r| (r.start, std::cmp::Reverse(r.end)));
    found
}

/// Where a copied part goes: the sequence `seq` of the receiving genome (its successor,
/// axiom, ...), and the `range` of it that the copy replaces (empty: the copy is inserted at
/// its start).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Site {
    /// The sequence's index among the genome's sequences.
    pub seq: usize,
    /// The items replaced.
    pub range: Range<usize>,
}

/// The sites of a genome whose sequences are `seqs`: each part of each sequence
/// ([`parts`]), replaced by the copy; a genome without a part has every place of every
/// sequence instead, where the copy is inserted (it then hangs where the turtle stands).
pub(crate) fn sites<T>(seqs: &[&[T]], shape: &Shape<T>) -> Vec<Site> {
    let replaced: Vec<Site> = seqs
        .iter()
        .enumerate()
        .flat_map(|(seq, items)| {
            parts(items, shape)
                .into_iter()
                .map(move |range| Site { seq, range })
        })
        .collect();
    if !replaced.is_empty() {
        return replaced;
    }
    seqs.iter()
        .enumerate()
        .flat_map(|(seq, items)| (0..=items.len()).map(move |at| Site { seq, range: at..at }))
        .collect()
}

/// One (donor, site) pair, drawn uniformly among the `donors` × `sites` pairs for which
/// `fits(donor, site)`; `None` when none fits. Two passes over the pairs, no retry.
pub(crate) fn pick_pair(
    donors: usize,
    sites: usize,
    fits: impl Fn(usize, usize) -> bool,
    rng: &mut Rng,
) -> Option<(usize, usize)> {
    let total: usize = (0..sites)
        .map(|s| (0..donors).filter(|&d| fits(d, s)).count())
        .sum();
    if total == 0 {
        return None;
    }
    let mut k = rng.random_range(0..total);
    for s in 0..sites {
        for d in 0..donors {
            if fits(d, s) {
                if k == 0 {
                    return Some((d, s));
                }
                k -= 1;
            }
        }
    }
    None
}

/// The copy of `part` (a branch, or a tail, which gets brackets), turned half a turn when it
/// builds a part: the `turn` put after its `[`, or taken away when its contents start with
/// `turn` or `back` (the half turn the other way). A branch that builds nothing is copied as
/// it is.
pub(crate) fn half_turned<T: Clone + PartialEq>(part: &[T], shape: &Shape<T>) -> Vec<T> {
    let n = part.len();
    let bracketed = n >= 2 && (shape.is_push)(&part[0]) && (shape.is_pop)(&part[n - 1]);
    let inner = if bracketed { &part[1..n - 1] } else { part };
    let [push, pop] = (shape.brackets)();
    let mut out = Vec::with_capacity(inner.len() + shape.turn.len() + 2);
    out.push(push);
    if !inner.iter().any(shape.is_body) {
        out.extend_from_slice(inner);
    } else if let Some(undo) = [shape.turn, shape.back]
        .into_iter()
        .find(|undo| !undo.is_empty() && inner.starts_with(undo))
    {
        out.extend_from_slice(&inner[undo.len()..]);
    } else {
        out.extend_from_slice(shape.turn);
        out.extend_from_slice(inner);
    }
    out.push(pop);
    out
}

/// A part of the genome whose sequences are `donor`, copied and half turned
/// ([`half_turned`]), and the site of the genome whose sequences are `receiver` that it goes
/// to ([`sites`]), drawn uniformly among the pairs for which `fits(copy, site)` (the
/// receiver's limits); `None` when the donor has no part or no copy fits anywhere.
pub(crate) fn copy_a_part<T: Clone + PartialEq>(
    donor: &[&[T]],
    receiver: &[&[T]],
    shape: &Shape<T>,
    fits: impl Fn(&[T], &Site) -> bool,
    rng: &mut Rng,
) -> Option<(Vec<T>, Site)> {
    let copies: Vec<Vec<T>> = donor
        .iter()
        .flat_map(|items| {
            parts(items, shape)
                .into_iter()
                .map(|r| half_turned(&items[r], shape))
        })
        .collect();
    if copies.is_empty() {
        return None;
    }
    let sites = sites(receiver, shape);
    let (d, s) = pick_pair(
        copies.len(),
        sites.len(),
        |d, s| fits(&copies[d], &sites[s]),
        rng,
    )?;
    let site = sites[s].clone();
    copies.into_iter().nth(d).map(|copy| (copy, site))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Letters for items: `f` builds a part, `L` and `R` are the half turns, the rest build
    /// nothing.
    const LETTERS: Shape<char> = Shape {
        is_push: |c| *c == '[',
        is_pop: |c| *c == ']',
        is_body: |c| *c == 'f',
        brackets: || ['[', ']'],
        turn: &['L'],
        back: &['R'],
    };

    fn chars(s: &str) -> Vec<char> {
        s.chars().collect()
    }

    fn text(items: &[char]) -> String {
        items.iter().collect()
    }

    #[test]
    fn the_parts_of_a_string_are_its_branches_and_its_tails() {
        // The root f (0) and its tail from the turn after it: `tj f g [ f ] t f`; that tail's
        // own parts: the branch `[ f ]` and the tail `t f` after it; inside the branch, the
        // single part is no tail.
        let s = chars("ftjfg[f]tf");
        let found: Vec<String> = parts(&s, &LETTERS)
            .into_iter()
            .map(|r| text(&s[r]))
            .collect();
        assert_eq!(found, ["tjfg[f]tf", "[f]", "tf"]);
        // A tail inside a branch ends at its `]`.
        let s = chars("f[ftf]");
        let found: Vec<String> = parts(&s, &LETTERS)
            .into_iter()
            .map(|r| text(&s[r]))
            .collect();
        assert_eq!(found, ["[ftf]", "tf"]);
        // A single part has none.
        assert!(parts(&chars("tfg"), &LETTERS).is_empty());
    }

    #[test]
    fn a_string_without_parts_offers_every_place_to_insert() {
        let s = chars("ab");
        let found = sites(&[&s[..]], &LETTERS);
        let ranges: Vec<_> = found.into_iter().map(|s| s.range).collect();
        assert_eq!(ranges, vec![0..0, 1..1, 2..2]);
    }

    #[test]
    fn a_half_turn_is_added_once_and_taken_away_the_second_time() {
        let once = half_turned(&chars("[fg]"), &LETTERS);
        assert_eq!(text(&once), "[Lfg]");
        assert_eq!(text(&half_turned(&once, &LETTERS)), "[fg]");
        assert_eq!(text(&half_turned(&chars("[Rf]"), &LETTERS)), "[f]");
        // A tail gets its brackets.
        assert_eq!(text(&half_turned(&chars("tf"), &LETTERS)), "[Ltf]");
        // A branch that builds no part is copied as it is.
        assert_eq!(text(&half_turned(&chars("[gg]"), &LETTERS)), "[gg]");
    }

    #[test]
    fn pick_pair_draws_only_pairs_that_fit() {
        let mut rng = Rng::seed_from_u64(1);
        for _ in 0..100 {
            let (d, s) = pick_pair(3, 4, |d, s| d == s, &mut rng).unwrap();
            assert_eq!(d, s);
        }
        assert_eq!(pick_pair(3, 4, |_, _| false, &mut rng), None);
    }
}
