//! Random values for the genomes' operators: draws and perturbations kept on a grid (so that
//! printed genomes stay readable) and within a range, and mutation rates kept probabilities.
//!
//! The genomes perturb values in different ways on purpose, and each way has its own name
//! here: the graph genome's Gaussian step ([`perturb_gaussian`], Sims), the L-system genomes'
//! steps on a quantum ([`perturb_stepwise`]); the continuous genome's triangular step depends
//! on its limits and stays with it.

use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};

use super::Rng;

/// `x` rounded to the nearest multiple of `1 / grid`.
pub(crate) fn on_grid(x: f64, grid: f64) -> f64 {
    (x * grid).round() / grid
}

/// A value drawn uniformly from `[lo, hi)`, rounded to the grid of `1 / grid` and kept in
/// `[lo, hi]`.
pub(crate) fn uniform_on_grid(rng: &mut Rng, (lo, hi): (f64, f64), grid: f64) -> f64 {
    on_grid(lo + rng.random::<f64>() * (hi - lo), grid).clamp(lo, hi)
}

/// Sims' scalar mutation: a Gaussian step relative to the value's magnitude (at least a tenth
/// of the range), kept in range and on the grid of `1 / grid`.
pub(crate) fn perturb_gaussian(x: f64, (lo, hi): (f64, f64), grid: f64, rng: &mut Rng) -> f64 {
    let z: f64 = StandardNormal.sample(rng);
    let scale = x.abs().max(0.1 * (hi - lo));
    on_grid((x + 0.25 * scale * z).clamp(lo, hi), grid).clamp(lo, hi)
}

/// A small change of `x` within `range` on the grid of `quantum`: one quantum either way on a
/// coarse grid (at most 20 steps across the range), else up to a tenth of the range either
/// way, rounded to the grid of `1 / grid`.
pub(crate) fn perturb_stepwise(
    x: f64,
    (lo, hi): (f64, f64),
    quantum: f64,
    grid: f64,
    rng: &mut Rng,
) -> f64 {
    let snap = |v: f64| ((v / quantum).round() * quantum).clamp(lo, hi);
    let steps = ((hi - lo) / quantum).round();
    if steps <= 20.0 {
        let step = if rng.random_bool(0.5) {
            quantum
        } else {
            -quantum
        };
        return snap(x + step);
    }
    let step = (hi - lo) * 0.1 * (2.0 * rng.random::<f64>() - 1.0);
    on_grid(snap(x + step), grid)
}

/// Keeps a mutation rate a probability (`NaN` is 0).
pub(crate) fn clamp_rate(rate: f64) -> f64 {
    if rate.is_nan() {
        0.0
    } else {
        rate.clamp(0.0, 1.0)
    }
}
