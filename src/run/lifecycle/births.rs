//! Where a steady-state run's births are made: this process's worker threads
//! ([`super::pool`]), or, on rank 0 of an MPI job of several ranks, those threads and every
//! other rank (`evolve::steady::BirthStream`, with the `mpi` feature). The run's driver
//! offers births and takes them back made, in any order, the same either way.

use std::sync::mpsc::{Receiver, Sender};

use super::RunError;
use super::pool::Panicked;
use crate::cancel::Interrupted;
use crate::encoding::Genome;
use crate::evolve::key::EvaluationKey;
use crate::evolve::steady::{Birth, Order};

/// What a worker thread gives back for an order.
pub(super) type Made<G> = Result<Result<Birth<G>, Interrupted>, Panicked>;

/// Where births are made.
pub(super) enum Births<'a, G: Genome> {
    /// This process's threads, which take `orders` and send back `made`.
    Here {
        orders: &'a Sender<Order<G>>,
        made: &'a Receiver<Made<G>>,
    },
    /// This process's threads and the other ranks of the MPI job.
    #[cfg(feature = "mpi")]
    Ranks {
        stream: Box<crate::evolve::steady::BirthStream<G>>,
        orders: &'a Sender<Order<G>>,
        made: &'a Receiver<Made<G>>,
    },
}

impl<G: Genome> Births<'_, G> {
    /// Offers birth `order` to be made (on other ranks, from the next
    /// [`Births::dispatch`] on).
    pub(super) fn offer(&mut self, order: Order<G>) {
        match self {
            // The workers hold the receiver until the driver returns.
            Births::Here { orders, .. } => {
                let _ = orders.send(order);
            }
            #[cfg(feature = "mpi")]
            Births::Ranks { stream, .. } => stream.offer(order),
        }
    }

    /// Hands the births offered out to the ranks at once (nothing to do on this process's
    /// threads alone: they take their orders as they are offered).
    pub(super) fn dispatch(&mut self) {
        #[cfg(feature = "mpi")]
        if let Births::Ranks { stream, orders, .. } = self {
            stream.dispatch(orders);
        }
    }

    /// Notes `keys` as first stored by generation `generation`, before any birth bred from
    /// it is offered (the ranks then skip a birth stored up to its source, as this process
    /// does).
    pub(super) fn stored(&mut self, generation: u32, keys: Vec<EvaluationKey>) {
        #[cfg(feature = "mpi")]
        if let Births::Ranks { stream, .. } = self {
            stream.stored(generation, keys);
        }
        #[cfg(not(feature = "mpi"))]
        let _ = (generation, keys);
    }

    /// The next birth made, waiting for one: `Interrupted` once the run is told to stop, or
    /// the panic of a worker thread.
    pub(super) fn next(&mut self) -> Result<Birth<G>, RunError> {
        let made = match self {
            Births::Here { made, .. } => made.recv().map_err(|_| Interrupted)?,
            #[cfg(feature = "mpi")]
            Births::Ranks {
                stream,
                orders,
                made,
            } => {
                use crate::evolve::steady::Next;
                match stream.next(orders, made) {
                    Next::Local(made) => made,
                    Next::Remote(birth) => return Ok(*birth),
                    Next::Closed | Next::Cancelled => return Err(Interrupted.into()),
                    Next::Panicked(message) => return Err(RunError::Panicked(message)),
                }
            }
        };
        match made {
            Ok(birth) => Ok(birth?),
            Err(Panicked(message)) => Err(RunError::Panicked(message)),
        }
    }
}
