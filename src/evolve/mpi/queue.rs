//! The jobs of a batch not yet handed out, as rank 0 keeps them: one list per rank (the jobs
//! only it may do, or that were dealt to it) and one of jobs any rank may do.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The jobs of a batch not yet handed out: one list per rank (the jobs it must do) and one
/// of jobs any rank may do, each in the batch's order.
pub(super) struct Queues {
    lists: Vec<Vec<usize>>,
    next: Vec<AtomicUsize>,
    /// Whether a rank that has run out of its own jobs takes other ranks'.
    steal: bool,
    /// The jobs of the batch, and how many were handed out.
    size: usize,
    handed: AtomicUsize,
}

impl Queues {
    /// The queues of jobs held as `holders` say, over `ranks` ranks; with `deal`, the jobs
    /// held by none are dealt to the ranks in turn, `threads[r]` at a time to rank `r`.
    pub(super) fn new(
        holders: &[Option<u32>],
        ranks: usize,
        deal: Option<&[usize]>,
        steal: bool,
    ) -> Queues {
        let mut lists = vec![Vec::new(); ranks + 1];
        let turns: Vec<usize> = match deal {
            Some(threads) => (0..ranks)
                .flat_map(|rank| std::iter::repeat_n(rank, threads[rank].max(1)))
                .collect(),
            None => Vec::new(),
        };
        for (index, holder) in holders.iter().enumerate() {
            let list = match holder {
                Some(rank) => (*rank as usize).min(ranks),
                None if turns.is_empty() => ranks,
                None => turns[index % turns.len()],
            };
            lists[list].push(index);
        }
        let next = lists.iter().map(|_| AtomicUsize::new(0)).collect();
        Queues {
            lists,
            next,
            steal: steal && deal.is_none(),
            size: holders.len(),
            handed: AtomicUsize::new(0),
        }
    }

    /// The jobs not yet handed out (to any rank).
    pub(super) fn remaining(&self) -> usize {
        self.size.saturating_sub(self.handed.load(Ordering::SeqCst))
    }

    /// The next jobs, at most `count`, for `rank`: its own first, then anyone's, then (when
    /// the batch allows it) other ranks', each with whether it is another rank's.
    pub(super) fn take(&self, rank: usize, count: usize) -> Vec<(usize, bool)> {
        let ranks = self.lists.len() - 1;
        let others = (1..ranks).map(|step| (rank + step) % ranks);
        let lists = [rank, ranks]
            .into_iter()
            .chain(others.filter(|_| self.steal));
        let mut taken = Vec::new();
        for list in lists {
            while taken.len() < count {
                // A list already run out is not advanced further (no overflow however often
                // it is asked).
                if self.next[list].load(Ordering::SeqCst) >= self.lists[list].len() {
                    break;
                }
                let at = self.next[list].fetch_add(1, Ordering::SeqCst);
                match self.lists[list].get(at) {
                    Some(&index) => taken.push((index, list != rank && list != ranks)),
                    None => break,
                }
            }
        }
        self.handed.fetch_add(taken.len(), Ordering::SeqCst);
        taken
    }
}

#[cfg(test)]
mod tests {
    use super::Queues;

    #[test]
    fn births_are_dealt_by_threads_and_walks_are_taken_over_only_when_allowed() {
        // Rank 0 with 2 threads, ranks 1 and 2 with 1: turns 0, 0, 1, 2, then again.
        let queues = Queues::new(&[None; 8], 3, Some(&[2, 1, 1]), true);
        assert_eq!(queues.take(1, 5), vec![(2, false), (6, false)]);
        assert_eq!(queues.remaining(), 6);
        assert_eq!(
            queues.take(0, 10),
            vec![(0, false), (1, false), (4, false), (5, false)]
        );
        assert_eq!(queues.take(2, usize::MAX), vec![(3, false), (7, false)]);
        assert_eq!(queues.remaining(), 0);
        // Walks of held births: rank 1 runs out of its own and takes over rank 2's in order.
        let queues = Queues::new(&[Some(2), Some(1), Some(2), Some(2)], 3, None, true);
        assert_eq!(queues.take(1, 1), vec![(1, false)]);
        assert_eq!(queues.take(1, 2), vec![(0, true), (2, true)]);
        assert_eq!(queues.take(2, 2), vec![(3, false)]);
        assert!(queues.take(2, 2).is_empty());
        // Without taking over, a rank's job waits for it.
        let queues = Queues::new(&[Some(1)], 3, None, false);
        assert!(queues.take(0, 1).is_empty());
        assert_eq!(queues.take(1, 1), vec![(0, false)]);
    }
}
