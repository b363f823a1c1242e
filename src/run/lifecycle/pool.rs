//! The worker threads of a steady-state run: orders sent through a queue, each taken by the
//! first thread free, each result sent back as it is made. A panic on either side ends the
//! work rather than leaving a thread waiting for ever: a worker's panic is sent back as a
//! result, and the queue is dropped when the driving thread returns or unwinds.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Mutex, mpsc};

/// A worker's panic: its message. The worker that panicked takes no more orders.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Panicked(pub(super) String);

/// Runs `drive` on this thread beside `threads` worker threads (at least one). `drive` sends
/// orders through the sender it is given, and receives through the receiver the result of
/// `work(thread, order)` for each, in the order they are made, or [`Panicked`] where `work`
/// panicked. The queue of orders is dropped as soon as `drive` returns or panics, so the
/// workers end after the order each is working on; then `with_workers` returns what `drive`
/// returned, or goes on with its panic.
pub(super) fn with_workers<O: Send, R: Send, X>(
    threads: usize,
    work: impl Fn(usize, O) -> R + Sync,
    drive: impl FnOnce(&mpsc::Sender<O>, &mpsc::Receiver<Result<R, Panicked>>) -> X,
) -> X {
    let (order_tx, order_rx) = mpsc::channel::<O>();
    let order_rx = Mutex::new(order_rx);
    let (result_tx, result_rx) = mpsc::channel::<Result<R, Panicked>>();
    let work = &work;
    std::thread::scope(|scope| {
        for thread in 0..threads.max(1) {
            let (order_rx, result_tx) = (&order_rx, result_tx.clone());
            scope.spawn(move || {
                loop {
                    let next = order_rx
                        .lock()
                        .unwrap_or_else(|poisoned| poisoned.into_inner())
                        .recv();
                    let Ok(order) = next else {
                        return; // the queue is dropped: no more orders
                    };
                    let result = catch_unwind(AssertUnwindSafe(|| work(thread, order)))
                        .map_err(|payload| Panicked(message(payload.as_ref())));
                    let panicked = result.is_err();
                    if result_tx.send(result).is_err() || panicked {
                        return;
                    }
                }
            });
        }
        drop(result_tx);
        // Owned by this closure: dropped when `drive` returns or unwinds, which ends the
        // workers' wait for orders before the scope waits for the workers.
        let order_tx = order_tx;
        drive(&order_tx, &result_rx)
    })
}

pub(super) use crate::evolve::steady::panic_message as message;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_order_comes_back_as_its_result() {
        let mut doubled = with_workers(
            3,
            |_, x: u32| 2 * x,
            |orders, results| {
                (0..10).for_each(|x| orders.send(x).unwrap());
                (0..10)
                    .map(|_| results.recv().unwrap().unwrap())
                    .collect::<Vec<_>>()
            },
        );
        doubled.sort();
        assert_eq!(doubled, [0, 2, 4, 6, 8, 10, 12, 14, 16, 18]);
    }

    #[test]
    fn a_workers_panic_reaches_the_driver_while_other_workers_wait() {
        // Two workers: the one that does not panic stays waiting for orders, so the driver
        // would wait for ever for the missing result were the panic not sent back.
        let panic = with_workers(
            2,
            |_, x: u32| {
                if x == 3 {
                    panic!("order {x} failed");
                }
                x
            },
            |orders, results| {
                (0..5).for_each(|x| orders.send(x).unwrap());
                loop {
                    match results.recv() {
                        Ok(Ok(_)) => continue,
                        Ok(Err(panicked)) => return Some(panicked),
                        Err(_) => return None,
                    }
                }
            },
        );
        assert_eq!(panic, Some(Panicked("order 3 failed".to_string())));
    }

    #[test]
    fn a_drivers_panic_ends_the_workers_and_goes_on() {
        // The workers wait for orders when the driver panics: its queue is dropped, they
        // end, and the panic goes on to the caller.
        let caught = catch_unwind(|| {
            with_workers(
                2,
                |_, x: u32| x,
                |orders, results| {
                    orders.send(1).unwrap();
                    assert_eq!(results.recv().unwrap(), Ok(1));
                    panic!("the driver failed");
                },
            )
        });
        let payload = caught.expect_err("the driver's panic goes on");
        assert_eq!(message(payload.as_ref()), "the driver failed");
    }
}
