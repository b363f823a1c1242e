//! The L-system genome's environment reads: productions that read a slot of the chemical
//! array and conditions that test the value read, the `chem` and `secrete` neurons, the
//! operators that make, change and remove them (with chance `[ga] environment_reads`), and
//! their listing for `ontogeny genome show`.
//!
//! Every draw here is guarded by that chance or by reads the genome already has: a genome
//! without reads, under a chance of 0, draws exactly what it drew before reads existed.

use super::*;
use crate::encoding::draw::{perturb_stepwise, uniform_on_grid};

/// A random condition on the value read: a comparison with a constant of [0, 1].
fn random_read_condition(rng: &mut Rng) -> Condition {
    Condition {
        param: 0,
        compare: Compare::ALL[rng.random_range(0..4)],
        value: uniform_on_grid(rng, READ_RANGE, GRID),
        read: true,
    }
}

/// A random `chem` or `secrete` neuron on a random slot of an array of `slots` slots (at
/// least 1).
fn random_neuron(slots: usize, rng: &mut Rng) -> Item {
    let command = ENVIRONMENT_COMMANDS[rng.random_range(0..ENVIRONMENT_COMMANDS.len())];
    let slot = rng.random_range(0..slots.max(1));
    Item::Command(command, Some(Arg::Const(slot as f64)))
}

/// Whether `item` is a `chem` or `secrete` neuron.
fn is_neuron(item: &Item) -> bool {
    matches!(item, Item::Command(c, _) if is_environment_command(*c))
}

/// The perturbed constant of a condition: within [0, 1] when it tests the value read, else
/// within the parameters' range.
pub(super) fn perturbed_condition(mut c: Condition, rng: &mut Rng) -> Condition {
    let range = if c.read { READ_RANGE } else { PARAM_RANGE };
    c.value = perturb_stepwise(c.value, range, 1.0 / GRID, GRID, rng);
    c
}

impl LSystemGenome {
    /// Gives the genome an array of one slot, at 0, when it has none.
    fn ensure_environment(&mut self) {
        if self.environment.is_empty() {
            self.environment = vec![0.0];
        }
    }

    /// Makes production `k` read a random slot, with a condition on the value read: a new
    /// first pair with a random successor where the production has room for one, else its
    /// first pair's condition.
    fn make_read(&mut self, k: usize, limits: &LSystemLimits, rng: &mut Rng) {
        self.ensure_environment();
        let n = self.productions.len();
        let params = limits.param_count();
        let slot = rng.random_range(0..self.environment.len());
        let condition = Some(random_read_condition(rng));
        let production = &mut self.productions[k];
        production.read = Some(slot);
        if production.pairs.len() < limits.pairs() {
            let len = rng.random_range(0..=limits.max_successor);
            let successor = random_run(len, k, n, params, limits.max_repeat, rng);
            production.pairs.insert(
                0,
                Pair {
                    condition,
                    successor,
                },
            );
        } else if let Some(pair) = production.pairs.first_mut() {
            pair.condition = condition;
        }
    }

    /// Inserts a random `chem` or `secrete` neuron at a random place of a random successor
    /// with room for it.
    fn insert_neuron(&mut self, limits: &LSystemLimits, rng: &mut Rng) {
        self.ensure_environment();
        let item = random_neuron(self.environment.len(), rng);
        let mut places: Vec<&mut Vec<Item>> = self
            .productions
            .iter_mut()
            .flat_map(|p| p.pairs.iter_mut().map(|pair| &mut pair.successor))
            .filter(|s| s.len() < limits.max_successor)
            .collect();
        if places.is_empty() {
            return;
        }
        let k = rng.random_range(0..places.len());
        let at = rng.random_range(0..=places[k].len());
        places[k].insert(at, item);
    }

    /// Removes a random `chem` or `secrete` neuron; `false` when the genome has none.
    fn remove_neuron(&mut self, rng: &mut Rng) -> bool {
        let mut sites: Vec<(&mut Vec<Item>, usize)> = Vec::new();
        for successor in self
            .productions
            .iter_mut()
            .flat_map(|p| p.pairs.iter_mut().map(|pair| &mut pair.successor))
        {
            let count = successor.iter().filter(|i| is_neuron(i)).count();
            if count > 0 {
                sites.push((successor, count));
            }
        }
        let total: usize = sites.iter().map(|(_, n)| n).sum();
        if total == 0 {
            return false;
        }
        let mut pick = rng.random_range(0..total);
        for (successor, count) in sites {
            if pick < count {
                let at = successor
                    .iter()
                    .enumerate()
                    .filter(|(_, i)| is_neuron(i))
                    .nth(pick)
                    .map(|(at, _)| at)
                    .expect("counted");
                successor.remove(at);
                return true;
            }
            pick -= count;
        }
        false
    }

    /// A random genome's reads (after its productions are drawn): with chance
    /// `environment_reads`, each production reads, and a neuron is added. Draws nothing when
    /// the chance is 0.
    pub(super) fn add_random_reads(&mut self, limits: &LSystemLimits, rng: &mut Rng) {
        let p = limits.read_chance();
        if p == 0.0 {
            return;
        }
        self.ensure_environment();
        for k in 0..self.productions.len() {
            if rng.random_bool(p) {
                self.make_read(k, limits, rng);
            }
        }
        if rng.random_bool(p) {
            self.insert_neuron(limits, rng);
        }
    }

    /// Mutates the reads: each reading production's slot changes with chance `rate`; with
    /// chance `environment_reads`, a random production reads or stops reading (or a reading
    /// one gains a condition on the value read), and a neuron is added or removed. Draws
    /// nothing from a genome that reads nothing when the chance is 0.
    pub(super) fn mutate_reads(&mut self, limits: &LSystemLimits, rate: f64, rng: &mut Rng) {
        let slots = self.environment.len();
        for production in &mut self.productions {
            if let Some(slot) = &mut production.read
                && slots > 1
                && rng.random_bool(rate)
            {
                *slot = rng.random_range(0..slots);
            }
        }
        let p = limits.read_chance();
        if p > 0.0 && !self.productions.is_empty() && rng.random_bool(p) {
            let k = rng.random_range(0..self.productions.len());
            if self.productions[k].read.is_some() && rng.random_bool(0.5) {
                self.productions[k].read = None;
            } else if self.productions[k].read.is_some() {
                let pairs = &mut self.productions[k].pairs;
                let at = rng.random_range(0..pairs.len());
                pairs[at].condition = Some(random_read_condition(rng));
            } else {
                self.make_read(k, limits, rng);
            }
        }
        if p > 0.0 && rng.random_bool(p) && !(rng.random_bool(0.5) && self.remove_neuron(rng)) {
            self.insert_neuron(limits, rng);
        }
    }

    /// Keeps what reads and writes the array within it (no random draws): conditions on the
    /// value read go where their production reads nothing; slots past the array's end
    /// become its last; without an array, reads and neurons go.
    pub(super) fn fit_environment(&mut self) {
        let slots = self.environment.len();
        for production in &mut self.productions {
            if slots == 0 {
                production.read = None;
            }
            if let Some(slot) = &mut production.read {
                *slot = (*slot).min(slots - 1);
            }
            let reads = production.read.is_some();
            for pair in &mut production.pairs {
                if pair.condition.is_some_and(|c| c.read && !reads) {
                    pair.condition = None;
                }
                if slots == 0 {
                    pair.successor.retain(|i| !is_neuron(i));
                }
                for item in &mut pair.successor {
                    if let Item::Command(c, Some(arg)) = item
                        && is_environment_command(*c)
                    {
                        let v = match *arg {
                            Arg::Const(v) if v.is_finite() => v,
                            _ => 0.0,
                        };
                        *arg = Arg::Const(v.round().clamp(0.0, slots.saturating_sub(1) as f64));
                    }
                }
            }
        }
    }

    /// The genome's environment reads for people (`ontogeny genome show`): a line per
    /// production that reads, saying which slot, how many reads its text writes and what
    /// its rules test the value read for; then the `chem` and `secrete` neurons. Empty when
    /// it reads nothing.
    pub fn environment_reads(&self) -> Vec<String> {
        let mut lines = Vec::new();
        let calls = |k: usize| {
            let in_axiom = usize::from(k == 0);
            in_axiom
                + self
                    .successors()
                    .flat_map(|s| s.iter())
                    .filter(|i| matches!(i, Item::Call(t, _) if *t == k))
                    .count()
        };
        for (k, production) in self.productions.iter().enumerate() {
            let Some(slot) = production.read else {
                continue;
            };
            let tests: Vec<String> = production
                .pairs
                .iter()
                .filter_map(|pair| {
                    let c = pair.condition.filter(|c| c.read)?;
                    let successor = self.successor_text(&pair.successor);
                    Some(format!("{} -->{successor}", c.text()))
                })
                .collect();
            let tests = if tests.is_empty() {
                "no rule tests the value read".to_string()
            } else {
                format!("where {READ_VALUE} is the value read, {}", tests.join("; "))
            };
            lines.push(format!(
                "P{k} reads slot {slot} ({} read(s) written): {tests}",
                calls(k)
            ));
        }
        let written = self.successors().flatten().filter_map(|item| match item {
            Item::Command(c, Some(Arg::Const(v))) if is_environment_command(*c) => Some((*c, *v)),
            _ => None,
        });
        lines.extend(crate::encoding::neurons_written(written));
        lines
    }
}
