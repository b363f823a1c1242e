//! A comparison's pairwise tests: Mann–Whitney U, A12 and the effect each test can detect,
//! of one measure (the stored best fitness, or the champions' fitness at the fine reference)
//! between every two encodings or conditions; a primary pair, when the comparison names one,
//! tested alone at [`stats::ALPHA`] and the others, secondary, with Holm's correction over
//! them.

use std::collections::HashMap;

use crate::study::stats;

/// The effect a comparison's power is stated for: Vargha and Delaney's threshold of a large
/// effect, and the size of the effect Hornby & Pollack's comparison reports.
pub const LARGE_A12: f64 = 0.71;

/// One pairwise test.
#[derive(Clone, Debug, PartialEq)]
pub struct Pair {
    /// The first encoding or condition.
    pub a: String,
    /// The second.
    pub b: String,
    /// Whether it is the comparison's primary pair: tested alone at [`stats::ALPHA`].
    pub primary: bool,
    /// The test of a's values against b's.
    pub test: stats::MannWhitney,
    /// The p-value the verdict reads: the primary pair's own p, a secondary pair's Holm p over
    /// the secondary pairs (over all pairs when there is no primary one).
    pub holm_p: f64,
    /// Vargha–Delaney A12 of a over b.
    pub a12: f64,
    /// The smallest effect this test detects with power [`stats::POWER`], with these
    /// replicates at its level (the primary pair's [`stats::ALPHA`]; a secondary pair's
    /// [`stats::ALPHA`] divided by the secondary pairs).
    pub detectable: stats::Detectable,
}

impl Pair {
    /// Whether the test found a difference: its p (Holm's for a secondary pair) at most
    /// [`stats::ALPHA`].
    pub fn detected(&self) -> bool {
        self.holm_p <= stats::ALPHA
    }

    /// What the test found, in words: "detected", or "not detected at this power (smallest
    /// detectable A12 0.84)" — never "no difference", which a test that finds nothing does
    /// not show.
    pub fn verdict(&self) -> String {
        if self.detected() {
            return if self.primary {
                format!("detected (p ≤ {})", stats::ALPHA)
            } else {
                format!("detected (Holm p ≤ {})", stats::ALPHA)
            };
        }
        match self.detectable.a12() {
            Some(a) => format!("not detected at this power (smallest detectable A12 {a:.2})"),
            None => format!(
                "not detected at this power (none is detectable with {} and {} replicates)",
                self.detectable.m, self.detectable.n
            ),
        }
    }
}

/// Whether `a` and `b` are the pair `primary` names, in either order.
pub fn is_primary(primary: &[String], a: &str, b: &str) -> bool {
    primary.len() == 2
        && ((primary[0] == a && primary[1] == b) || (primary[0] == b && primary[1] == a))
}

/// The tests between every two of `names` (in order; a primary pair in the order `primary`
/// gives it), but those of `too_few`, of the values `sample` gives each; `primary` names the
/// primary pair (empty: none).
pub fn pairwise(
    names: &[String],
    too_few: &[String],
    primary: &[String],
    sample: impl Fn(&str) -> Vec<f64>,
) -> Vec<Pair> {
    let mut tested = Vec::new();
    for (i, a) in names.iter().enumerate() {
        for b in &names[i + 1..] {
            if too_few.contains(a) || too_few.contains(b) {
                continue;
            }
            let (a, b) = if is_primary(primary, a, b) && primary[0] != *a {
                (b, a)
            } else {
                (a, b)
            };
            tested.push((a.clone(), b.clone(), sample(a), sample(b)));
        }
    }
    let secondary = tested
        .iter()
        .filter(|(a, b, _, _)| !is_primary(primary, a, b))
        .count();
    let mut detectable: HashMap<(usize, usize, usize), stats::Detectable> = HashMap::new();
    let mut pairs: Vec<Pair> = tested
        .into_iter()
        .map(|(a, b, x, y)| {
            let primary = is_primary(primary, &a, &b);
            let level_pairs = if primary { 1 } else { secondary };
            let key = (x.len(), y.len(), level_pairs);
            let d = *detectable
                .entry(key)
                .or_insert_with(|| stats::detectable_a12(key.0, key.1, key.2));
            Pair {
                test: stats::mann_whitney(&x, &y),
                holm_p: f64::NAN,
                a12: stats::a12(&x, &y),
                detectable: d,
                primary,
                a,
                b,
            }
        })
        .collect();
    let corrected = stats::holm(
        &pairs
            .iter()
            .filter(|p| !p.primary)
            .map(|p| p.test.p)
            .collect::<Vec<_>>(),
    );
    let mut corrected = corrected.into_iter();
    for p in &mut pairs {
        p.holm_p = if p.primary {
            p.test.p
        } else {
            corrected.next().unwrap_or(f64::NAN)
        };
    }
    pairs
}

/// A comparison's power as planned: its replicates on every side, every pair tested.
#[derive(Clone, Debug, PartialEq)]
pub struct Power {
    /// Replicates per side.
    pub replicates: usize,
    /// The primary pair, if the comparison names one.
    pub primary: Option<(String, String)>,
    /// The secondary pairs (all pairs without a primary one).
    pub secondary: usize,
    /// The effect the primary pair's test detects (at [`stats::ALPHA`]).
    pub primary_detectable: Option<stats::Detectable>,
    /// The effect each secondary pair's test detects (at [`stats::ALPHA`] / `secondary`);
    /// `None` without secondary pairs.
    pub secondary_detectable: Option<stats::Detectable>,
    /// The primary test's power at A12 = [`LARGE_A12`].
    pub primary_power: Option<f64>,
    /// A secondary test's power at A12 = [`LARGE_A12`].
    pub secondary_power: Option<f64>,
    /// The replicates per side a single pair at [`stats::ALPHA`] needs to detect A12 =
    /// [`LARGE_A12`] with power [`stats::POWER`].
    pub needed: Option<usize>,
}

/// The power of a comparison of `arms` names with `replicates` each and the `primary` pair
/// (empty: none).
pub fn planned_power(arms: usize, replicates: usize, primary: &[String]) -> Option<Power> {
    let pairs = arms * arms.saturating_sub(1) / 2;
    if pairs == 0 {
        return None;
    }
    let primary = (primary.len() == 2).then(|| (primary[0].clone(), primary[1].clone()));
    let secondary = pairs - usize::from(primary.is_some());
    let n = replicates;
    Some(Power {
        replicates,
        secondary,
        primary_detectable: primary.as_ref().map(|_| stats::detectable_a12(n, n, 1)),
        secondary_detectable: (secondary > 0).then(|| stats::detectable_a12(n, n, secondary)),
        primary_power: primary
            .as_ref()
            .map(|_| stats::power_at(n, n, 1, LARGE_A12)),
        secondary_power: (secondary > 0).then(|| stats::power_at(n, n, secondary, LARGE_A12)),
        needed: stats::replicates_for(LARGE_A12, 1),
        primary,
    })
}

/// The report's paragraph on power: the level each pair is tested at, the effect it detects
/// with probability [`stats::POWER`], its power at A12 = [`LARGE_A12`], how that was computed,
/// and the replicates a single pair needs for that effect.
pub fn power_note(power: &Power, kind: &str) -> String {
    let method = |d: &stats::Detectable| match (d.distance, d.method) {
        (None, _) => String::new(),
        (Some(_), stats::PowerMethod::Simulated) => format!(
            " (simulated: {} pairs of normal samples, one shifted by δ, A12 = Φ(δ/√2), \
             through the exact test)",
            stats::POWER_DRAWS
        ),
        (Some(_), stats::PowerMethod::Noether) => " (Noether's normal approximation)".into(),
    };
    let mut out = format!("Power: with {} replicates per {kind}", power.replicates);
    if let (Some((a, b)), Some(d), Some(p)) = (
        &power.primary,
        &power.primary_detectable,
        power.primary_power,
    ) {
        out.push_str(&format!(
            ", the primary pair ({a} against {b}) is tested alone at {} (two-sided): it detects \
             {}{}, and has power {p:.2} for A12 = {LARGE_A12}.",
            stats::ALPHA,
            d.words(),
            method(d),
        ));
        if let (Some(d), Some(p)) = (&power.secondary_detectable, power.secondary_power) {
            out.push_str(&format!(
                " The {} secondary pair{} are Holm-corrected among themselves, each tested at \
                 {} / {} = {:.4} at worst: each detects {}{}, and has power {p:.2} for A12 = \
                 {LARGE_A12}.",
                power.secondary,
                if power.secondary == 1 { "" } else { "s" },
                stats::ALPHA,
                power.secondary,
                d.level,
                d.words(),
                method(d),
            ));
        }
    } else if let (Some(d), Some(p)) = (&power.secondary_detectable, power.secondary_power) {
        let pairs = power.secondary;
        out.push_str(&format!(
            " and {pairs} pair{}, each pair is tested at {} / {pairs} = {:.4} (two-sided; the \
             strictest level Holm's correction uses, so it holds for every pair). The \
             comparison detects {}{}, and has power {p:.2} for A12 = {LARGE_A12}.",
            if pairs == 1 { "" } else { "s" },
            stats::ALPHA,
            d.level,
            d.words(),
            method(d),
        ));
    }
    if let Some(n) = power.needed {
        out.push_str(&format!(
            " A single pair at {} needs {n} replicates a side to detect A12 = {LARGE_A12} (a large \
             effect) with probability {} (`ontogeny compare --power-for {LARGE_A12}`).",
            stats::ALPHA,
            stats::POWER,
        ));
    }
    out.push_str(&format!(
        " A pair whose p (Holm's, for a secondary pair) is above {} is \"not detected at this \
         power\": a smaller difference may exist.",
        stats::ALPHA
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn a_primary_pair_is_tested_alone_and_the_others_with_holm_among_themselves() {
        // a beats b completely (5 vs 5: exact p = 2/252 = 0.0079); c sits in between.
        let values = |n: &str| -> Vec<f64> {
            match n {
                "a" => vec![10.0, 11.0, 12.0, 13.0, 14.0],
                "b" => vec![0.0, 1.0, 2.0, 3.0, 4.0],
                _ => vec![5.0, 6.0, 7.0, 8.0, 9.0],
            }
        };
        let all = names(&["a", "b", "c"]);
        let pairs = pairwise(&all, &[], &names(&["b", "a"]), values);
        // The primary pair comes in the order the primary names it: b against a.
        let primary: Vec<&Pair> = pairs.iter().filter(|p| p.primary).collect();
        assert_eq!(primary.len(), 1);
        assert_eq!((primary[0].a.as_str(), primary[0].b.as_str()), ("b", "a"));
        assert_eq!(primary[0].a12, 0.0);
        // Tested alone: its p is its own.
        assert!((primary[0].holm_p - 2.0 / 252.0).abs() < 1e-12);
        assert_eq!(primary[0].detectable.level, stats::ALPHA);
        // Each secondary pair also has p = 2/252; Holm over the two: 2 · 2/252 for both.
        for p in pairs.iter().filter(|p| !p.primary) {
            assert!((p.holm_p - 4.0 / 252.0).abs() < 1e-12, "{p:?}");
            assert_eq!(p.detectable.level, stats::ALPHA / 2.0);
            assert!(p.verdict().starts_with("detected (Holm"));
        }
        assert_eq!(primary[0].verdict(), "detected (p ≤ 0.05)");
        // Without a primary pair, Holm over all three.
        let plain = pairwise(&all, &[], &[], values);
        assert!(plain.iter().all(|p| !p.primary));
        assert!(plain.iter().all(|p| (p.holm_p - 6.0 / 252.0).abs() < 1e-12));
    }

    #[test]
    fn the_planned_power_separates_the_primary_pair_from_the_secondary_ones() {
        let p = planned_power(4, 10, &names(&["lsystem", "direct"])).unwrap();
        assert_eq!(p.secondary, 5);
        let primary = p.primary_detectable.unwrap();
        let secondary = p.secondary_detectable.unwrap();
        assert_eq!(primary.level, 0.05);
        assert_eq!(secondary.level, 0.01);
        assert!(primary.a12().unwrap() < secondary.a12().unwrap());
        assert!(p.primary_power.unwrap() > p.secondary_power.unwrap());
        let note = power_note(&p, "encoding");
        assert!(
            note.contains("primary pair (lsystem against direct) is tested alone"),
            "{note}"
        );
        assert!(note.contains("5 secondary pairs"), "{note}");
        assert!(note.contains("not detected at this power"));
        assert!(!note.contains("no difference"));
        assert_eq!(planned_power(1, 10, &[]), None);
    }
}
