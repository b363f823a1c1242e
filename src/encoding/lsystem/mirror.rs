//! Walking with Dinosaurs' crossover (3.3.1) for the L-system genome, and the items it shares
//! with the direct genome: a part of one of the elite's successors (a branch `[` ... `]`, or a
//! tail: a part built after another, with what places it and what follows it), half turned by
//! `left(2)`, replaces a part of one of the breeder's successors (see
//! `crate::encoding::mirror` for the parts and the axis).

use super::*;
use crate::encoding::mirror::{Shape, copy_a_part};

/// `left(2)`: half a turn about the turtle's up axis.
const HALF_TURN: [Item; 1] = [Item::Command(Command::Left, Some(Arg::Const(2.0)))];
/// `right(2)`: the same half turn the other way.
const HALF_TURN_BACK: [Item; 1] = [Item::Command(Command::Right, Some(Arg::Const(2.0)))];

/// The items of the L-system and direct genomes as their crossover sees them: a `forward`
/// builds a part, and so may a call (its production may build one).
pub(crate) const ITEMS: Shape<Item> = Shape {
    is_push: |i| matches!(i, Item::Push),
    is_pop: |i| matches!(i, Item::Pop),
    is_body: |i| matches!(i, Item::Command(Command::Forward, _) | Item::Call(..)),
    brackets: || [Item::Push, Item::Pop],
    turn: &HALF_TURN,
    back: &HALF_TURN_BACK,
};

/// `item` fitted to a genome of `productions` productions of `params` parameters: a call of a
/// production it lacks wraps round, and its arguments fit the parameter count (a parameter it
/// lacks reads 0).
pub(super) fn adapted(item: &Item, productions: usize, params: usize) -> Item {
    match item {
        Item::Call(t, args) => {
            let mut args = args.clone();
            args.resize(params, Arg::Const(0.0));
            for a in &mut args {
                if let Arg::Plus(k, _) | Arg::Times(k, _) = a
                    && *k >= params
                {
                    *a = Arg::Const(0.0);
                }
            }
            Item::Call(t % productions.max(1), args)
        }
        other => other.clone(),
    }
}

impl LSystemGenome {
    /// Walking with Dinosaurs' crossover: `self` with a part of one of its successors (or,
    /// when it has none, a place in one) replaced by a half-turned copy of a part of
    /// `other`'s, drawn among the pairs whose successor stays within `max_successor`; calls
    /// in the copy fit `self`'s productions ([`adapted`]). `None` when `other` has no part or
    /// none fits.
    pub(super) fn mirrored_child(
        &self,
        other: &Self,
        limits: &LSystemLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        let donor: Vec<&[Item]> = other.successors().map(Vec::as_slice).collect();
        let receiver: Vec<&[Item]> = self.successors().map(Vec::as_slice).collect();
        let fits = |copy: &[Item], site: &crate::encoding::mirror::Site| {
            receiver[site.seq].len() - site.range.len() + copy.len() <= limits.max_successor
        };
        let (copy, site) = copy_a_part(&donor, &receiver, &ITEMS, fits, rng)?;
        let mut child = self.clone();
        let (n, params) = (child.productions.len(), limits.param_count());
        let target = child
            .productions
            .iter_mut()
            .flat_map(|p| p.pairs.iter_mut().map(|pair| &mut pair.successor))
            .nth(site.seq)?;
        target.splice(site.range, copy.iter().map(|i| adapted(i, n, params)));
        // A copied part may hold one end of a repeat block only; without blocks this keeps
        // everything.
        balance(target);
        if other.environment.len() > child.environment.len() {
            child.environment = other.environment.clone();
        }
        child.fit_environment();
        Some(child)
    }
}
