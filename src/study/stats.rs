//! Statistics over samples of fitness values: ranks and correlations (for `bench`), and what
//! `compare` reports of encodings: mean, standard deviation and a Student-t 95% confidence
//! interval, the two-sided Mann–Whitney U test, Holm's correction for multiple tests and the
//! Vargha–Delaney A12 effect size.

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
}
