//! Statistics over samples of fitness values.

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
}
