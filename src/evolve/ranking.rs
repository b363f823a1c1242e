//! The order of a generation: indices from best to worst fitness, ties broken by the lower
//! index, the same for individuals, store records or anything with a fitness.

/// Indices of `items` from best to worst `fitness` (ties: lower index first), in the total
/// order of `f64`: the order of [`super::ga::ranking`], for anything that has a fitness (the store's
/// records of a generation, say), so a rank means the same everywhere.
pub fn ranking_by<T>(items: &[T], fitness: impl Fn(&T) -> f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| {
        fitness(&items[b])
            .total_cmp(&fitness(&items[a]))
            .then(a.cmp(&b))
    });
    order
}
