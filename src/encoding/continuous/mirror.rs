//! Walking with Dinosaurs' crossover (3.3.1) for the `lsystem-continuous` genome: a part (a
//! branch `[` ... `]`, or a tail: a part built after another, with what places it and what
//! follows it) of the elite's axiom or of one of its rules' successors, half turned by
//! `left(1) left(1)` (a turn's parameter is at most 1 in this genome), replaces a part of the
//! breeder's (see `crate::encoding::mirror` for the parts and the axis).

use super::*;
use crate::encoding::mirror::{Shape, Site, copy_a_part};

/// `left(1) left(1)`: half a turn about the turtle's up axis.
const HALF_TURN: [Token; 2] = [
    Token::Command(Command::Left, Some(1.0)),
    Token::Command(Command::Left, Some(1.0)),
];
/// `right(1) right(1)`: the same half turn the other way.
const HALF_TURN_BACK: [Token; 2] = [
    Token::Command(Command::Right, Some(1.0)),
    Token::Command(Command::Right, Some(1.0)),
];

/// The tokens as the crossover sees them: a `forward` builds a part, and so does a maturing
/// token (a part growing, or a token whose rule may grow parts).
const TOKENS: Shape<Token> = Shape {
    is_push: |t| matches!(t, Token::Push),
    is_pop: |t| matches!(t, Token::Pop),
    is_body: |t| matches!(t, Token::Command(Command::Forward, _) | Token::Grower(_)),
    brackets: || [Token::Push, Token::Pop],
    turn: &HALF_TURN,
    back: &HALF_TURN_BACK,
};

impl ContinuousGenome {
    /// The axiom, then each rule's successor and its plastic branch's, in order.
    fn sequences(&self) -> Vec<&[Token]> {
        std::iter::once(self.axiom.as_slice())
            .chain(self.rules.iter().flat_map(|r| {
                std::iter::once(r.successor.as_slice())
                    .chain(r.plastic.as_ref().map(|p| p.successor.as_slice()))
            }))
            .collect()
    }

    /// [`ContinuousGenome::sequences`], to change one.
    fn sequence_mut(&mut self, k: usize) -> Option<&mut Vec<Token>> {
        std::iter::once(&mut self.axiom)
            .chain(self.rules.iter_mut().flat_map(|r| {
                std::iter::once(&mut r.successor)
                    .chain(r.plastic.as_mut().map(|p| &mut p.successor))
            }))
            .nth(k)
    }

    /// Walking with Dinosaurs' crossover: `self` with a part of its axiom or of a successor
    /// (or, when it has none, a place in one) replaced by a half-turned copy of a part of
    /// `other`'s, drawn among the pairs whose sequence keeps its length limit (`max_axiom`,
    /// `max_successor`) and `max_growers`. `None` when `other` has no part or none fits.
    pub(super) fn mirrored_child(
        &self,
        other: &Self,
        limits: &ContinuousLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        let limits = limits.sane();
        let donor = other.sequences();
        let receiver = self.sequences();
        let growers = |seq: &[Token]| seq.iter().filter(|t| t.is_grower()).count();
        let fits = |copy: &[Token], site: &Site| {
            let seq = receiver[site.seq];
            let max = if site.seq == 0 {
                limits.max_axiom
            } else {
                limits.max_successor
            };
            seq.len() - site.range.len() + copy.len() <= max
                && growers(seq) - growers(&seq[site.range.clone()]) + growers(copy)
                    <= limits.max_growers
        };
        let (copy, site) = copy_a_part(&donor, &receiver, &TOKENS, fits, rng)?;
        let mut child = self.clone();
        child.sequence_mut(site.seq)?.splice(site.range, copy);
        if other.environment.len() > child.environment.len() {
            child.environment = other.environment.clone();
        }
        child.fit_environment(&limits);
        Some(child)
    }
}
