//! Statistics over samples of fitness values: ranks and correlations (for `bench`), and what
//! `compare` reports of encodings: mean, standard deviation and a Student-t 95% confidence
//! interval, the two-sided Mann–Whitney U test, Holm's correction for multiple tests, the
//! Vargha–Delaney A12 effect size, and the power of the test: the smallest A12 a comparison
//! can detect ([`detectable_a12`]).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

/// The ranks of `values` (1 for the smallest), ties given the mean of the ranks they span.
/// NaN values rank after every number.
pub fn ranks(values: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut out = vec![0.0; values.len()];
    let mut start = 0;
    while start < order.len() {
        let mut end = start + 1;
        while end < order.len() && values[order[end]] == values[order[start]] {
            end += 1;
        }
        // Positions start..end (0-based) hold ranks start+1 ..= end: their mean.
        let mean = (start + 1 + end) as f64 / 2.0;
        for &i in &order[start..end] {
            out[i] = mean;
        }
        start = end;
    }
    out
}

/// Pearson's correlation of two samples of equal length; NaN when either is constant or
/// shorter than 2.
pub fn pearson(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len(), "samples of different lengths");
    let n = x.len() as f64;
    if x.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    sxy / (sxx * syy).sqrt()
}

/// Spearman's rank correlation: Pearson's correlation of the ranks (ties averaged).
pub fn spearman(x: &[f64], y: &[f64]) -> f64 {
    pearson(&ranks(x), &ranks(y))
}

/// Mean, sample standard deviation and a 95% confidence interval of the mean of a sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// The sample's size.
    pub n: usize,
    /// Its mean (NaN when empty).
    pub mean: f64,
    /// Its sample standard deviation (divisor n − 1; NaN below 2 values).
    pub sd: f64,
    /// The half-width of the 95% confidence interval of the mean, t(0.975, n − 1) · sd / √n
    /// (NaN below 2 values).
    pub ci95: f64,
}

/// The [`Summary`] of `values`.
pub fn summary(values: &[f64]) -> Summary {
    let n = values.len();
    if n == 0 {
        return Summary {
            n,
            mean: f64::NAN,
            sd: f64::NAN,
            ci95: f64::NAN,
        };
    }
    let mean = values.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return Summary {
            n,
            mean,
            sd: f64::NAN,
            ci95: f64::NAN,
        };
    }
    let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    Summary {
        n,
        mean,
        sd,
        ci95: t_quantile_975(n - 1) * sd / (n as f64).sqrt(),
    }
}

/// Student's t quantile at 0.975 with `df` degrees of freedom (`df` ≥ 1).
pub fn t_quantile_975(df: usize) -> f64 {
    StudentsT::new(0.0, 1.0, df as f64)
        .expect("df ≥ 1 is a valid Student t")
        .inverse_cdf(0.975)
}

/// The median of `values` (the mean of the middle two for an even count; NaN when empty).
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => v[n / 2],
        _ => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

/// How a Mann–Whitney p-value was computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PMethod {
    /// The exact distribution of U (no ties, both samples of at most [`EXACT_MAX`] values).
    Exact,
    /// The normal approximation with the tie correction of the variance and a continuity
    /// correction of 0.5.
    Normal,
}

impl PMethod {
    /// The name the report uses.
    pub fn name(self) -> &'static str {
        match self {
            PMethod::Exact => "exact",
            PMethod::Normal => "normal",
        }
    }
}

/// The largest sample for which [`mann_whitney`] uses the exact distribution.
pub const EXACT_MAX: usize = 30;

/// The outcome of a two-sided Mann–Whitney U test of samples `x` (size m) and `y` (size n).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MannWhitney {
    /// U of the first sample: the number of pairs (x, y) with x > y, ties counting ½;
    /// R₁ − m(m + 1)/2 with R₁ the first sample's rank sum in the pooled sample.
    pub u: f64,
    /// The two-sided p-value (1 when either sample is empty).
    pub p: f64,
    /// How `p` was computed.
    pub method: PMethod,
}

/// The two-sided Mann–Whitney U test of `x` against `y`.
///
/// Without ties and with both samples of at most [`EXACT_MAX`] values, p is exact:
/// 2 · min(P(U ≤ u), P(U ≥ u)), capped at 1, from the number of arrangements of the pooled
/// ranks giving each U (the recurrence N(u; m, n) = N(u − n; m − 1, n) + N(u; m, n − 1)).
/// Otherwise p comes from the normal approximation: z = (|U − mn/2| − ½) / σ with
/// σ² = mn/12 · ((N + 1) − Σ(t³ − t)/(N(N − 1))) over the tie groups t, N = m + n; p = 2(1 − Φ(z)),
/// and 1 when every value is tied.
pub fn mann_whitney(x: &[f64], y: &[f64]) -> MannWhitney {
    let (m, n) = (x.len(), y.len());
    if m == 0 || n == 0 {
        return MannWhitney {
            u: 0.0,
            p: 1.0,
            method: PMethod::Exact,
        };
    }
    let (u, ties) = u_and_ties(x, y);
    if ties.is_empty() && m <= EXACT_MAX && n <= EXACT_MAX {
        let counts = u_counts(m, n);
        let total: f64 = counts.iter().sum();
        // u is a whole number without ties.
        let k = u.round() as usize;
        let below: f64 = counts[..=k].iter().sum::<f64>() / total;
        let above: f64 = counts[k..].iter().sum::<f64>() / total;
        return MannWhitney {
            u,
            p: (2.0 * below.min(above)).min(1.0),
            method: PMethod::Exact,
        };
    }
    mann_whitney_normal(x, y)
}

/// The two-sided Mann–Whitney U test of `x` against `y` by the normal approximation (tie and
/// continuity corrections), whatever the samples; see [`mann_whitney`].
pub fn mann_whitney_normal(x: &[f64], y: &[f64]) -> MannWhitney {
    let (mf, nf) = (x.len() as f64, y.len() as f64);
    let (u, ties) = u_and_ties(x, y);
    let big_n = mf + nf;
    let tie_term: f64 = ties.iter().map(|t| t * t * t - t).sum::<f64>() / (big_n * (big_n - 1.0));
    let variance = mf * nf / 12.0 * ((big_n + 1.0) - tie_term);
    let p = if variance.is_nan() || variance <= 0.0 {
        1.0
    } else {
        let z = ((u - mf * nf / 2.0).abs() - 0.5).max(0.0) / variance.sqrt();
        let normal = Normal::standard();
        (2.0 * (1.0 - normal.cdf(z))).min(1.0)
    };
    MannWhitney {
        u,
        p,
        method: PMethod::Normal,
    }
}

/// U of `x` against `y`, and the sizes of the pooled sample's tie groups (of 2 or more).
fn u_and_ties(x: &[f64], y: &[f64]) -> (f64, Vec<f64>) {
    let m = x.len();
    let pooled: Vec<f64> = x.iter().chain(y).copied().collect();
    let r1: f64 = ranks(&pooled)[..m].iter().sum();
    let u = r1 - (m * (m + 1)) as f64 / 2.0;
    let mut sorted = pooled;
    sorted.sort_by(f64::total_cmp);
    let mut ties = Vec::new();
    let mut start = 0;
    while start < sorted.len() {
        let mut end = start + 1;
        while end < sorted.len() && sorted[end] == sorted[start] {
            end += 1;
        }
        if end - start > 1 {
            ties.push((end - start) as f64);
        }
        start = end;
    }
    (u, ties)
}

/// The number of arrangements of samples of sizes `m` and `n` (no ties) giving U = 0 ..= mn,
/// as floating-point counts (exact below 2^53, ample for C(60, 30) ≈ 1.2 · 10^17 to well
/// within the p-value's precision).
fn u_counts(m: usize, n: usize) -> Vec<f64> {
    // table[j][u] = N(u; i, j) for the current i; N(u; 0, j) = [u == 0].
    let width = m * n + 1;
    let mut table = vec![vec![0.0; width]; n + 1];
    for row in table.iter_mut() {
        row[0] = 1.0;
    }
    for _i in 1..=m {
        let mut next = vec![vec![0.0; width]; n + 1];
        next[0][0] = 1.0;
        for j in 1..=n {
            for u in 0..width {
                // The largest value belongs to the first sample (it beats all j of the
                // second: u − j from the rest) or to the second (u unchanged).
                let first = if u >= j { table[j][u - j] } else { 0.0 };
                next[j][u] = first + next[j - 1][u];
            }
        }
        table = next;
    }
    table.swap_remove(n)
}

/// Holm's step-down correction of `p` (in any order): the k-th smallest p-value of m is
/// multiplied by m − k + 1, the results made non-decreasing in that order and capped at 1.
/// Returned in the input's order.
pub fn holm(p: &[f64]) -> Vec<f64> {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| p[a].total_cmp(&p[b]));
    let mut out = vec![0.0; m];
    let mut running: f64 = 0.0;
    for (k, &i) in order.iter().enumerate() {
        running = running.max(((m - k) as f64 * p[i]).min(1.0));
        out[i] = running;
    }
    out
}

/// Vargha and Delaney's A12: the probability that a value of `x` beats one of `y`, ties
/// counting ½, i.e. U / (mn) = (R₁/m − (m + 1)/2)/n. 0.5 is no effect; Vargha and Delaney call
/// |A12 − 0.5| ≥ 0.06 small, ≥ 0.14 medium and ≥ 0.21 large. NaN when either is empty.
pub fn a12(x: &[f64], y: &[f64]) -> f64 {
    let (m, n) = (x.len(), y.len());
    if m == 0 || n == 0 {
        return f64::NAN;
    }
    let pooled: Vec<f64> = x.iter().chain(y).copied().collect();
    let r1: f64 = ranks(&pooled)[..m].iter().sum();
    (r1 / m as f64 - (m as f64 + 1.0) / 2.0) / n as f64
}

/// Vargha and Delaney's words for an A12: negligible, small, medium or large.
pub fn a12_magnitude(a: f64) -> &'static str {
    let d = (a - 0.5).abs();
    if d.is_nan() {
        "n/a"
    } else if d >= 0.21 {
        "large"
    } else if d >= 0.14 {
        "medium"
    } else if d >= 0.06 {
        "small"
    } else {
        "negligible"
    }
}

/// The significance level of a comparison's pairwise tests, before the correction for
/// multiple pairs.
pub const ALPHA: f64 = 0.05;

/// The power at which a comparison states the effect it can detect.
pub const POWER: f64 = 0.8;

/// Draws of pairs of samples behind a simulated power ([`detectable_a12`]).
pub const POWER_DRAWS: usize = 10_000;

/// How a [`Detectable`] effect was computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PowerMethod {
    /// A seeded simulation of the exact test (both samples of at most [`EXACT_MAX`] values).
    Simulated,
    /// Noether's (1987) normal approximation (larger samples, where the test itself uses the
    /// normal approximation).
    Noether,
}

impl PowerMethod {
    /// The name the report uses.
    pub fn name(self) -> &'static str {
        match self {
            PowerMethod::Simulated => "simulated",
            PowerMethod::Noether => "Noether",
        }
    }
}

/// The smallest effect a two-sided Mann–Whitney test of samples of two sizes detects with
/// power [`POWER`] at a level ([`detectable_a12`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detectable {
    /// The first sample's size.
    pub m: usize,
    /// The second's.
    pub n: usize,
    /// The level each test is held to: [`ALPHA`] divided by the number of pairs (the
    /// strictest level Holm's correction can use).
    pub level: f64,
    /// The smallest distance |A12 − 0.5| detected with power [`POWER`], in either direction;
    /// `None` when no difference can be detected at all: even samples that do not overlap
    /// give a p-value above the level.
    pub distance: Option<f64>,
    /// How it was computed.
    pub method: PowerMethod,
}

impl Detectable {
    /// The smallest detectable A12 above 0.5 (its mirror, 1 − A12, is detected as well).
    pub fn a12(&self) -> Option<f64> {
        self.distance.map(|d| 0.5 + d)
    }

    /// The effect in words, after "detects": "A12 ≥ 0.84 or ≤ 0.16 with probability 0.8",
    /// or "nothing: ..." when nothing can be detected.
    pub fn words(&self) -> String {
        match self.distance {
            Some(d) => format!(
                "A12 ≥ {:.2} or ≤ {:.2} with probability {POWER}",
                0.5 + d,
                0.5 - d
            ),
            None => format!(
                "nothing: with {} and {} replicates no result reaches p ≤ {:.4}",
                self.m, self.n, self.level
            ),
        }
    }
}

/// The smallest A12 that a two-sided Mann–Whitney test of samples of sizes `m` and `n`
/// detects with power [`POWER`] when `pairs` pairs are tested, each at level
/// [`ALPHA`] / `pairs` (Bonferroni's level, the strictest one Holm's step-down correction
/// applies, so the figure holds for every pair whatever the others' p-values).
///
/// The effect is a shift δ of one normal sample against another of the same spread, for
/// which A12 = Φ(δ/√2). With both samples of at most [`EXACT_MAX`] values the test is the
/// exact one [`mann_whitney`] makes, and its power is simulated: [`POWER_DRAWS`] pairs of
/// standard normal samples drawn from a fixed seed (the same for every δ), the power at δ the
/// share of them whose U, with δ added to the first sample, lies in the test's rejection
/// region; δ is found by bisection. Larger samples use Noether's formula,
/// |A12 − 0.5| = (z(1 − level/2) + z(power)) / √(12 m n / (m + n)).
pub fn detectable_a12(m: usize, n: usize, pairs: usize) -> Detectable {
    let level = ALPHA / pairs.max(1) as f64;
    let mut out = Detectable {
        m,
        n,
        level,
        distance: None,
        method: PowerMethod::Simulated,
    };
    if m == 0 || n == 0 {
        return out;
    }
    if m > EXACT_MAX || n > EXACT_MAX {
        let normal = Normal::standard();
        let z = normal.inverse_cdf(1.0 - level / 2.0) + normal.inverse_cdf(POWER);
        let d = z / (12.0 * (m * n) as f64 / (m + n) as f64).sqrt();
        out.method = PowerMethod::Noether;
        out.distance = (d < 0.5).then_some(d);
        return out;
    }
    let Some(power) = exact_power(m, n, level) else {
        return out;
    };
    let (mut lo, mut hi) = (0.0, 16.0);
    for _ in 0..40 {
        let mid = (lo + hi) / 2.0;
        if power(mid) >= POWER {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    out.distance = Some(Normal::standard().cdf(hi / std::f64::consts::SQRT_2) - 0.5);
    out
}

/// The simulated power of the exact two-sided Mann–Whitney test of samples of sizes `m` and
/// `n` (at most [`EXACT_MAX`]) at `level`, as a function of the shift δ of the first sample
/// ([`detectable_a12`] says how); `None` when even samples that do not overlap are not
/// significant at that level (the power is 0 at any δ).
fn exact_power(m: usize, n: usize, level: f64) -> Option<impl Fn(f64) -> f64> {
    // The rejection region over U = 0 ..= mn: p as `mann_whitney` computes it, at most the level.
    let counts = u_counts(m, n);
    let total: f64 = counts.iter().sum();
    let mut below = 0.0;
    let cumulative: Vec<f64> = counts
        .iter()
        .map(|c| {
            below += c;
            below
        })
        .collect();
    let reject: Vec<bool> = (0..counts.len())
        .map(|u| {
            let lower = cumulative[u] / total;
            let upper = (total - cumulative[u] + counts[u]) / total;
            (2.0 * lower.min(upper)).min(1.0) <= level
        })
        .collect();
    if !reject[m * n] {
        return None;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(0x0005_eed0_fa12);
    let mut draw = |size: usize| {
        let mut v: Vec<f64> = (0..size).map(|_| StandardNormal.sample(&mut rng)).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let draws: Vec<(Vec<f64>, Vec<f64>)> = (0..POWER_DRAWS).map(|_| (draw(m), draw(n))).collect();
    Some(move |delta: f64| {
        let hits = draws
            .iter()
            .filter(|(x, y)| {
                // U: the pairs with x + δ above y, counted along both sorted samples.
                let (mut u, mut j) = (0, 0);
                for xi in x {
                    while j < y.len() && y[j] < xi + delta {
                        j += 1;
                    }
                    u += j;
                }
                reject[u]
            })
            .count();
        hits as f64 / draws.len() as f64
    })
}

/// The power of a two-sided Mann–Whitney test of samples of sizes `m` and `n`, when `pairs`
/// pairs are tested (each at [`ALPHA`] / `pairs`, as in [`detectable_a12`]), to detect an
/// effect of `a12` (a shift δ of normal samples, A12 = Φ(δ/√2); `a12` and 1 − `a12` have the
/// same power): simulated through the exact test with both samples of at most [`EXACT_MAX`]
/// values, else Noether's approximation, power = Φ(|A12 − 0.5| · √(12mn/(m + n)) −
/// z(1 − level/2)). 0 with an empty sample or an `a12` outside (0, 1).
pub fn power_at(m: usize, n: usize, pairs: usize, a12: f64) -> f64 {
    let level = ALPHA / pairs.max(1) as f64;
    if m == 0 || n == 0 || !(a12 > 0.0 && a12 < 1.0) {
        return 0.0;
    }
    let normal = Normal::standard();
    let a = a12.max(1.0 - a12);
    if m > EXACT_MAX || n > EXACT_MAX {
        let scale = (12.0 * (m * n) as f64 / (m + n) as f64).sqrt();
        return normal.cdf((a - 0.5) * scale - normal.inverse_cdf(1.0 - level / 2.0));
    }
    exact_power(m, n, level).map_or(0.0, |power| {
        power(std::f64::consts::SQRT_2 * normal.inverse_cdf(a))
    })
}

/// The fewest replicates per side (the same on both) whose two-sided Mann–Whitney test, with
/// `pairs` pairs tested, detects an effect of `a12` with power [`POWER`] ([`power_at`]);
/// `None` for no effect (0.5) or when even 10,000 a side would not.
pub fn replicates_for(a12: f64, pairs: usize) -> Option<usize> {
    (2..=10_000).find(|&n| power_at(n, n, pairs, a12) >= POWER)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranks_average_ties() {
        assert_eq!(ranks(&[10.0, 20.0, 20.0, 5.0]), vec![2.0, 3.5, 3.5, 1.0]);
    }

    #[test]
    fn spearman_by_hand() {
        // Without ties ρ = 1 − 6 Σ d² / (n (n² − 1)). x ranks 1..5; y ranks 2,1,4,3,5:
        // d = (1, −1, 1, −1, 0), Σ d² = 4, ρ = 1 − 24 / 120 = 0.8.
        let x = [1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [0.2, 0.1, 0.9, 0.5, 7.0];
        assert!((spearman(&x, &y) - 0.8).abs() < 1e-12);
        // Monotone transformations do not change it.
        let y2: Vec<f64> = y.iter().map(|v: &f64| v.exp()).collect();
        assert!((spearman(&x, &y2) - 0.8).abs() < 1e-12);
        let reversed: Vec<f64> = x.iter().map(|v| -v).collect();
        assert!((spearman(&x, &reversed) + 1.0).abs() < 1e-12);
    }

    #[test]
    fn constant_samples_have_no_correlation() {
        assert!(spearman(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0]).is_nan());
    }

    #[test]
    fn summary_by_hand() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, Σ(x − 5)² = 32, sd = √(32/7) = 2.13809.
        let s = summary(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert_eq!(s.n, 8);
        assert!((s.mean - 5.0).abs() < 1e-12);
        assert!((s.sd - (32.0f64 / 7.0).sqrt()).abs() < 1e-12);
        // t(0.975, 7) = 2.364624 (tables: 2.365).
        assert!((t_quantile_975(7) - 2.364624).abs() < 1e-5);
        assert!((s.ci95 - 2.364624 * (32.0f64 / 7.0).sqrt() / 8f64.sqrt()).abs() < 1e-5);
        // t(0.975, 1) = 12.706, t(0.975, 9) = 2.262 (published tables).
        assert!((t_quantile_975(1) - 12.706).abs() < 1e-3);
        assert!((t_quantile_975(9) - 2.262).abs() < 1e-3);
        assert!(summary(&[3.0]).sd.is_nan());
        assert!(summary(&[]).mean.is_nan());
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
    }

    /// SciPy's documented example of `mannwhitneyu` (after Conover): males' and females'
    /// values.
    const MALES: [f64; 5] = [19.0, 22.0, 16.0, 29.0, 24.0];
    const FEMALES: [f64; 4] = [20.0, 11.0, 17.0, 12.0];

    #[test]
    fn mann_whitney_of_a_published_example() {
        // SciPy's documentation of `mannwhitneyu` (after Conover): males against females,
        // U = 17, exact two-sided p = 0.1111 = 2 · 7/126 (7 of the C(9, 4) = 126 orders give
        // U ≥ 17); the normal approximation with continuity correction: 0.11134688653314041.
        let t = mann_whitney(&MALES, &FEMALES);
        assert_eq!(t.u, 17.0);
        assert_eq!(t.method, PMethod::Exact);
        assert!((t.p - 14.0 / 126.0).abs() < 1e-12, "{}", t.p);
        // The other way round: U = 20 − 17 = 3, the same p.
        let r = mann_whitney(&FEMALES, &MALES);
        assert_eq!(r.u, 3.0);
        assert!((r.p - t.p).abs() < 1e-12);
        // A tie forces the normal approximation with the tie-corrected variance.
        let tied = mann_whitney(&[1.0, 2.0, 2.0, 5.0], &[3.0, 4.0, 6.0, 7.0]);
        assert_eq!(tied.method, PMethod::Normal);
        // Pooled ranks of x: 1, 2.5, 2.5, 6 → R1 = 12, U = 12 − 10 = 2; mn/2 = 8; ties: one
        // pair, Σ(t³ − t) = 6, σ² = 16/12 · (9 − 6/56) = 11.857143, σ = 3.443420,
        // z = (6 − 0.5)/3.443420 = 1.597249, p = 2(1 − Φ(1.597249)) = 0.110210.
        assert_eq!(tied.u, 2.0);
        assert!((tied.p - 0.110210).abs() < 1e-5, "{}", tied.p);
    }

    #[test]
    fn mann_whitney_normal_approximation_of_the_published_example() {
        // SciPy's documented asymptotic p of the same example: 0.11134688653314041
        // (σ² = 5·4·10/12, z = (|17 − 10| − 0.5)/σ).
        let t = mann_whitney_normal(&MALES, &FEMALES);
        assert_eq!(t.u, 17.0);
        assert_eq!(t.method, PMethod::Normal);
        assert!((t.p - 0.11134688653314041).abs() < 1e-9, "{}", t.p);
        // Above EXACT_MAX values the normal route is taken even without ties.
        let x: Vec<f64> = (0..31).map(f64::from).collect();
        let y: Vec<f64> = (0..31).map(|k| f64::from(k) + 0.5).collect();
        assert_eq!(mann_whitney(&x, &y).method, PMethod::Normal);
    }

    #[test]
    fn mann_whitney_exact_agrees_with_a_table_of_critical_values() {
        // Published tables (e.g. Siegel & Castellan): for m = n = 10, two-sided α = 0.05, the
        // critical value of U is 23: U ≤ 23 is significant, U = 24 is not.
        let sample = |u_target: usize| {
            // x = 0..10 shifted so that exactly u_target pairs have x > y: y = 0.5, 1.5, ...
            // ranks make U = Σ over x of the y's below it.
            let y: Vec<f64> = (0..10).map(|k| k as f64 + 0.5).collect();
            let mut x = vec![-1.0; 10];
            let mut left = u_target;
            for xi in x.iter_mut() {
                let beat = left.min(10);
                *xi = if beat == 0 { -1.0 } else { beat as f64 - 0.25 };
                left -= beat;
            }
            // Ties within x do not matter to U, but the exact route needs none: spread them.
            for (k, xi) in x.iter_mut().enumerate() {
                *xi += k as f64 * 1e-6;
            }
            (x, y)
        };
        let (x, y) = sample(23);
        let t = mann_whitney(&x, &y);
        assert_eq!(t.u, 23.0);
        assert_eq!(t.method, PMethod::Exact);
        assert!(t.p <= 0.05, "{}", t.p);
        let (x, y) = sample(24);
        let t = mann_whitney(&x, &y);
        assert_eq!(t.u, 24.0);
        assert!(t.p > 0.05, "{}", t.p);
        // The distribution sums to C(20, 10) = 184756 and is symmetric.
        let counts = u_counts(10, 10);
        assert_eq!(counts.iter().sum::<f64>(), 184_756.0);
        assert_eq!(counts[0], 1.0);
        assert_eq!(counts[3], 3.0);
        assert_eq!(counts[97], counts[3]);
        // Identical samples: p = 1.
        assert_eq!(mann_whitney(&[1.0, 2.0], &[1.0, 2.0]).p, 1.0);
        assert_eq!(mann_whitney(&[1.0; 3], &[1.0; 4]).p, 1.0);
    }

    #[test]
    fn holm_by_hand() {
        // p = 0.01, 0.04, 0.03, 0.005 (m = 4). Sorted: 0.005 · 4 = 0.02; 0.01 · 3 = 0.03;
        // 0.03 · 2 = 0.06; 0.04 · 1 = 0.04, raised to the running maximum 0.06.
        let adjusted = holm(&[0.01, 0.04, 0.03, 0.005]);
        let expected = [0.03, 0.06, 0.06, 0.02];
        for (a, e) in adjusted.iter().zip(expected) {
            assert!((a - e).abs() < 1e-12, "{adjusted:?}");
        }
        // Capped at 1.
        assert_eq!(holm(&[0.5, 0.6]), vec![1.0, 1.0]);
        assert!(holm(&[]).is_empty());
    }

    #[test]
    fn a12_by_hand() {
        // x = 1, 2, 3 against y = 2, 4: of the 6 pairs, (3, 2) wins and (2, 2) ties:
        // A12 = (1 + ½)/6 = 0.25. By ranks: pooled 1, 2, 3, 2, 4 → x's ranks 1, 2.5, 4,
        // R1 = 7.5, (7.5/3 − 2)/2 = 0.25.
        assert!((a12(&[1.0, 2.0, 3.0], &[2.0, 4.0]) - 0.25).abs() < 1e-12);
        assert!((a12(&[2.0, 4.0], &[1.0, 2.0, 3.0]) - 0.75).abs() < 1e-12);
        assert_eq!(a12(&[5.0, 6.0], &[1.0]), 1.0);
        // A12 = U / mn on the published example: 17/20.
        assert!((a12(&MALES, &FEMALES) - 0.85).abs() < 1e-12);
        assert_eq!(a12_magnitude(0.85), "large");
        assert_eq!(a12_magnitude(0.40), "small");
        assert_eq!(a12_magnitude(0.64), "medium");
        assert_eq!(a12_magnitude(0.5), "negligible");
    }
    #[test]
    fn the_detectable_a12_of_ten_replicates_a_side_is_that_of_an_independent_simulation() {
        // One pair, n = 10 a side, level 0.05: the exact test rejects U ≤ 23 or U ≥ 77 (the
        // published critical value). A separate simulation of that region under a normal
        // shift (plain Python, its own enumeration of U's distribution, 200 000 draws per
        // shift) gives power 0.8 at δ = 1.399, A12 = Φ(1.399/√2) = 0.839.
        let d = detectable_a12(10, 10, 1);
        assert_eq!(d.method, PowerMethod::Simulated);
        assert_eq!(d.level, 0.05);
        let a = d.a12().unwrap();
        assert!((a - 0.839).abs() < 0.005, "{a}");
        assert_eq!(
            d.words(),
            format!("A12 ≥ {a:.2} or ≤ {:.2} with probability 0.8", 1.0 - a)
        );
        // The same seed, the same figure.
        assert_eq!(detectable_a12(10, 10, 1), d);
        // Three pairs test each at 0.05/3: a larger effect is needed.
        let three = detectable_a12(10, 10, 3);
        assert!((three.level - 0.05 / 3.0).abs() < 1e-15);
        assert!(three.a12().unwrap() > a + 0.02, "{three:?}");
        // More replicates detect less.
        assert!(detectable_a12(20, 20, 1).a12().unwrap() < a - 0.05);
    }

    #[test]
    fn too_few_replicates_detect_nothing() {
        // 3 against 3: the most extreme order has p = 2/C(6, 3) = 0.1 > 0.05.
        let d = detectable_a12(3, 3, 1);
        assert_eq!(d.distance, None);
        assert_eq!(
            d.words(),
            "nothing: with 3 and 3 replicates no result reaches p ≤ 0.0500"
        );
        // 4 against 4: p = 2/70 = 0.029, detectable at 0.05 but not at 0.05/3.
        assert!(detectable_a12(4, 4, 1).distance.is_some());
        assert_eq!(detectable_a12(4, 4, 3).distance, None);
        assert_eq!(detectable_a12(0, 4, 1).distance, None);
    }

    #[test]
    fn large_samples_use_noethers_formula() {
        // 50 a side, level 0.05: (z(0.975) + z(0.8)) / √(12 · 2500 / 100) =
        // (1.959964 + 0.841621) / √300 = 2.801585 / 17.320508 = 0.161750.
        let d = detectable_a12(50, 50, 1);
        assert_eq!(d.method, PowerMethod::Noether);
        assert!((d.distance.unwrap() - 0.161750).abs() < 1e-6, "{d:?}");
        // Two pairs: z(1 − 0.0125) = 2.241403; (2.241403 + 0.841621)/17.320508 = 0.177998.
        assert!((detectable_a12(50, 50, 2).distance.unwrap() - 0.177998).abs() < 1e-6);
        // Noether's formula is close to the simulation where both apply: at 30 a side the
        // simulated exact test needs a little more (its real level is below 0.05).
        let simulated = detectable_a12(30, 30, 1).distance.unwrap();
        let noether = 2.801585 / (12.0f64 * 900.0 / 60.0).sqrt();
        assert!((simulated - noether).abs() < 0.02, "{simulated} {noether}");
    }

    #[test]
    fn power_at_an_effect_agrees_with_the_detectable_effect_and_noethers_formula() {
        // The detectable effect of 10 a side is where the power reaches 0.8.
        let d = detectable_a12(10, 10, 1).a12().unwrap();
        assert!((power_at(10, 10, 1, d) - POWER).abs() < 0.01);
        assert!(power_at(10, 10, 1, d - 0.03) < POWER);
        // A12 and 1 − A12 have the same power; no effect, or an empty side, none.
        assert_eq!(power_at(10, 10, 1, 0.3), power_at(10, 10, 1, 0.7));
        assert_eq!(power_at(0, 10, 1, 0.9), 0.0);
        // Three a side and three pairs: nothing is significant, so no power at all.
        assert_eq!(power_at(3, 3, 3, 0.99), 0.0);
        // 50 a side at A12 0.71, level 0.05: Φ(0.21 · √300 − 1.959964) = Φ(3.637307 −
        // 1.959964) = Φ(1.677343) = 0.953264.
        assert!((power_at(50, 50, 1, 0.71) - 0.953264).abs() < 1e-5);
    }

    #[test]
    fn replicates_for_a_large_effect_are_the_fewest_that_reach_the_power() {
        // Noether's formula asks √(6n) ≥ (1.959964 + 0.841621) / 0.21 = 13.3409, n ≥ 29.7:
        // 30 a side. The exact test's simulated power gets there a little sooner or later.
        let n = replicates_for(0.71, 1).unwrap();
        assert!(power_at(n, n, 1, 0.71) >= POWER);
        assert!(power_at(n - 1, n - 1, 1, 0.71) < POWER);
        assert!((25..=32).contains(&n), "{n}");
        // More pairs (a stricter level) need more replicates; no effect needs infinitely many.
        assert!(replicates_for(0.71, 3).unwrap() > n);
        assert_eq!(replicates_for(0.5, 1), None);
    }
}
