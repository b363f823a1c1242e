//! The order in which a generation's walks are handed to the evaluator: it changes when each
//! walk starts, never a result.

/// The order in which a generation's walks are handed to the evaluator, each to the first
/// thread (or rank) to fall free. Results are put back in their individuals' places, so the
/// order changes how well the threads are kept busy before the generation's end, never a
/// result: a run is the same to the digit in either order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WalkOrder {
    /// The likely-longest first: walks of creatures with more parts first (a step's cost
    /// grows with the parts), ties in the individuals' order; so that a long walk does not
    /// start last and hold the generation's end while the other threads idle. A pure function
    /// of the generation's creatures: no clock is read.
    #[default]
    LongestFirst,
    /// The individuals' order.
    Index,
}

impl WalkOrder {
    /// Every order.
    pub const ALL: [WalkOrder; 2] = [WalkOrder::LongestFirst, WalkOrder::Index];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            WalkOrder::LongestFirst => "longest-first",
            WalkOrder::Index => "index",
        }
    }

    /// One line for people.
    pub fn summary(self) -> &'static str {
        match self {
            WalkOrder::LongestFirst => {
                "creatures with more parts first, ties in the individuals' order (the default)"
            }
            WalkOrder::Index => "in the individuals' order",
        }
    }

    /// The order named `name`.
    pub fn named(name: &str) -> Option<WalkOrder> {
        WalkOrder::ALL.into_iter().find(|o| o.name() == name)
    }

    /// The order in which to hand out walks of creatures with `parts` parts (a walk each, in
    /// the individuals' order): their indices.
    pub fn order(self, parts: &[usize]) -> Vec<usize> {
        let mut order: Vec<usize> = (0..parts.len()).collect();
        if self == WalkOrder::LongestFirst {
            // Stable: ties keep the individuals' order.
            order.sort_by_key(|&i| std::cmp::Reverse(parts[i]));
        }
        order
    }
}
