//! The projectile genes every genome carries when a thrower's projectile evolves with it
//! (Chaumont et al. 4.1: "In some experiments, mutations are allowed on the size and shape of
//! the projectile"): the projectile's three edge lengths, their mutation, their check, and
//! the line that carries them in a grammar genome's text.
//!
//! A run whose `[task.catapult]` sets `evolve_projectile` gives its genomes' limits the
//! projectile newborns start with ([`super::Genome::evolve_projectile`]); a genome then
//! carries its projectile from birth, a mutant changes each edge with the mutation rate,
//! and crossover and grafting keep the first parent's projectile whole (4.1: "keep one arm
//! and one projectile only"). Without it no genome carries one, and no operator draws a
//! number for it, so the runs of before draw exactly as they did.

use rand::RngExt;

use super::draw::{clamp_rate, perturb_gaussian, perturb_stepwise};
use super::{DevelopError, Rng};
use crate::creature::PROJECTILE_EDGE;

/// How a genome perturbs its projectile's edges: as it perturbs its other numbers.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Step {
    /// Sims' Gaussian step (the graph genome).
    Gaussian,
    /// A step of up to a tenth of the range on a 1 cm grid (the L-system genomes).
    Stepwise,
}

/// Values are kept on a grid of 1 mm so that printed genomes stay readable.
const GRID: f64 = 1000.0;

/// The projectile of a mutant of a genome whose projectile is `genes`, in a run whose
/// newborns start with `start` (none: the projectile does not evolve, and `genes` is kept
/// without a draw). A genome without one (read from a grammar) starts from `start`; each edge
/// then changes with probability `rate`, within [`PROJECTILE_EDGE`].
pub(crate) fn mutated(
    genes: Option<[f64; 3]>,
    start: Option<[f64; 3]>,
    rate: f64,
    step: Step,
    rng: &mut Rng,
) -> Option<[f64; 3]> {
    let Some(start) = start else {
        return genes;
    };
    let rate = clamp_rate(rate);
    let mut edges = genes.unwrap_or(start);
    for edge in &mut edges {
        if rng.random_bool(rate) {
            *edge = match step {
                Step::Gaussian => perturb_gaussian(*edge, PROJECTILE_EDGE, GRID, rng),
                Step::Stepwise => perturb_stepwise(*edge, PROJECTILE_EDGE, 0.01, GRID, rng),
            };
        }
    }
    Some(edges)
}

/// `Err` saying what is wrong unless every edge of `genes` is within [`PROJECTILE_EDGE`].
pub(crate) fn check(genes: Option<[f64; 3]>) -> Result<(), String> {
    let (lo, hi) = PROJECTILE_EDGE;
    match genes {
        Some(edges) if !edges.iter().all(|e| (lo..=hi).contains(e)) => Err(format!(
            "its projectile, {} × {} × {} m, has an edge outside [{lo}, {hi}] m",
            edges[0], edges[1], edges[2]
        )),
        _ => Ok(()),
    }
}

/// The start of the comment line that carries a grammar genome's projectile.
const LINE: &str = "# projectile:";

/// The line that carries `genes` at the head of a grammar genome's text (`# projectile: 0.2
/// 0.2 0.05`, a comment to the grammar), or nothing when the genome carries none.
pub(crate) fn text_line(genes: Option<[f64; 3]>) -> String {
    match genes {
        Some([x, y, z]) => format!(
            "{LINE} {} {} {}\n",
            crate::number::format_number(x),
            crate::number::format_number(y),
            crate::number::format_number(z)
        ),
        None => String::new(),
    }
}

/// The projectile a grammar genome's `text` carries ([`text_line`]), checked; none when no
/// line carries one (every text written before projectiles evolved).
pub(crate) fn read_line(text: &str) -> Result<Option<[f64; 3]>, DevelopError> {
    let Some(rest) = text.lines().find_map(|l| l.trim().strip_prefix(LINE)) else {
        return Ok(None);
    };
    let bad = || {
        DevelopError(format!(
            "'{LINE}{rest}' is not three edge lengths in metres, as '{LINE} 0.2 0.2 0.05'"
        ))
    };
    let edges: Vec<f64> = rest
        .split_whitespace()
        .map(|w| w.parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let genes: [f64; 3] = edges.try_into().map_err(|_| bad())?;
    check(Some(genes)).map_err(DevelopError)?;
    Ok(Some(genes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn without_a_start_the_projectile_is_kept_and_nothing_is_drawn() {
        let mut rng = Rng::seed_from_u64(3);
        let before = rng.clone();
        assert_eq!(mutated(None, None, 1.0, Step::Gaussian, &mut rng), None);
        let kept = Some([0.3, 0.2, 0.1]);
        assert_eq!(mutated(kept, None, 1.0, Step::Stepwise, &mut rng), kept);
        assert_eq!(rng, before, "no number was drawn");
    }

    #[test]
    fn mutation_keeps_every_edge_in_range_and_is_a_function_of_the_seed() {
        for step in [Step::Gaussian, Step::Stepwise] {
            let mut rng = Rng::seed_from_u64(11);
            let mut genes = Some([0.05, 1.0, 0.2]);
            let mut changed = 0;
            for _ in 0..2000 {
                let next = mutated(genes, Some([0.2; 3]), 0.5, step, &mut rng);
                assert_eq!(check(next), Ok(()), "{next:?}");
                changed += usize::from(next != genes);
                genes = next;
            }
            assert!(
                changed > 1000,
                "{step:?}: {changed} of 2000 mutants changed"
            );
            let again = (0..2000).fold(
                (Some([0.05, 1.0, 0.2]), Rng::seed_from_u64(11)),
                |(g, mut rng), _| (mutated(g, Some([0.2; 3]), 0.5, step, &mut rng), rng),
            );
            assert_eq!(again.0, genes, "the same seed gives the same projectile");
        }
        // A rate of 0 changes nothing; a genome without a projectile gets the start.
        let mut rng = Rng::seed_from_u64(1);
        assert_eq!(
            mutated(None, Some([0.2, 0.2, 0.2]), 0.0, Step::Gaussian, &mut rng),
            Some([0.2, 0.2, 0.2])
        );
    }

    #[test]
    fn the_line_reads_back_and_a_text_without_it_has_none() {
        let genes = Some([0.25, 0.25, 0.06]);
        let line = text_line(genes);
        assert_eq!(line, "# projectile: 0.25 0.25 0.06\n");
        let text = format!("{line}axiom: P0(1)\n");
        assert_eq!(read_line(&text), Ok(genes));
        assert_eq!(text_line(None), "");
        assert_eq!(read_line("# a comment\naxiom: P0(1)\n"), Ok(None));
        assert_eq!(
            read_line("# projectile: 0.2 0.2\n").unwrap_err().0,
            "'# projectile: 0.2 0.2' is not three edge lengths in metres, as '# projectile: 0.2 0.2 0.05'"
        );
        assert_eq!(
            read_line("# projectile: 0.2 0.2 3\n").unwrap_err().0,
            "its projectile, 0.2 × 0.2 × 3 m, has an edge outside [0.05, 1] m"
        );
    }
}
