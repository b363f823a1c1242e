//! The edge-encoding brain builder (Hornby & Pollack; Matos & Arita, Table 1).
//!
//! Commands act on the **current link**, which runs from a *source* neuron (Hornby & Pollack's
//! "from-neuron", Matos & Arita's "head") to a *target* neuron (the "to-neuron", the "tail").
//! It is *actual* when such a link exists in the network and *virtual* when it does not (after
//! a `cut`, or a `parent(n)` to a neuron with no link to the target). The network starts with
//! one oscillator neuron and one link into it: a self-link of weight 1, which is the first
//! current link.

use crate::creature::{Actuator, Brain, Link, Neuron, NeuronFunction, Role, Sensor};
use crate::lang::commands::Command;

/// The current link: source, target, and the link's index when it is actual.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CurrentLink {
    pub from: usize,
    pub to: usize,
    pub link: Option<usize>,
}

pub(crate) struct BrainBuilder {
    neurons: Vec<Neuron>,
    alive: Vec<bool>,
    /// For a neuron merged away, the neuron it was merged into.
    merged_into: Vec<Option<usize>>,
    /// Links; `None` once cut or merged away.
    links: Vec<Option<Link>>,
    /// For each joint, how many of its degrees of freedom already have an output neuron.
    driven: Vec<(usize, usize)>,
    environment_len: usize,
}

impl BrainBuilder {
    pub fn new(environment_len: usize) -> Self {
        BrainBuilder {
            neurons: vec![Neuron {
                function: NeuronFunction::Oscillator,
                params: Vec::new(),
                bias: 0.0,
                role: Role::Hidden,
                part: None,
            }],
            alive: vec![true],
            merged_into: vec![None],
            links: vec![Some(Link {
                from: 0,
                to: 0,
                weight: 1.0,
            })],
            driven: Vec::new(),
            environment_len,
        }
    }

    pub fn initial_link(&self) -> CurrentLink {
        CurrentLink {
            from: 0,
            to: 0,
            link: Some(0),
        }
    }

    fn add_neuron(&mut self, function: NeuronFunction, role: Role, part: Option<usize>) -> usize {
        self.neurons.push(Neuron {
            function,
            params: Vec::new(),
            bias: 0.0,
            role,
            part,
        });
        self.alive.push(true);
        self.merged_into.push(None);
        self.neurons.len() - 1
    }

    /// The living neuron `n` now is (following merges).
    fn resolve(&self, mut n: usize) -> usize {
        while let Some(m) = self.merged_into[n] {
            n = m;
        }
        n
    }

    fn add_link(&mut self, from: usize, to: usize, weight: f64) -> usize {
        self.links.push(Some(Link { from, to, weight }));
        self.links.len() - 1
    }

    /// Indices of the actual links into `neuron`, in order of creation.
    fn inputs(&self, neuron: usize) -> Vec<usize> {
        self.links
            .iter()
            .enumerate()
            .filter_map(|(i, l)| l.as_ref().filter(|l| l.to == neuron).map(|_| i))
            .collect()
    }

    /// The first actual link `from` → `to`, in order of creation.
    fn first_link(&self, from: usize, to: usize) -> Option<usize> {
        self.links
            .iter()
            .position(|l| l.as_ref().is_some_and(|l| l.from == from && l.to == to))
    }

    fn current_of(&self, link: usize) -> CurrentLink {
        let l = self.links[link].as_ref().expect("an actual link");
        CurrentLink {
            from: l.from,
            to: l.to,
            link: Some(link),
        }
    }

    /// Applies one command. `joint` is the current part's joint and its degrees of freedom.
    /// An `Err` is a warning: the command did nothing.
    pub fn apply(
        &mut self,
        op: Command,
        params: &[f64],
        current: &mut CurrentLink,
        part: Option<usize>,
        joint: Option<(usize, usize)>,
    ) -> Result<(), String> {
        let arg = |default: f64| -> Result<f64, String> {
            let v = params.first().copied().unwrap_or(default);
            if v.is_finite() {
                Ok(v)
            } else {
                Err("a non-finite parameter: ignored".to_string())
            }
        };
        let index = |default: f64| -> Result<usize, String> {
            let v = arg(default)?;
            if v < 0.0 {
                Err(format!("index {v} is negative: ignored"))
            } else {
                Ok(v.round() as usize)
            }
        };
        // A current link saved by `[` may name a neuron merged away since, or a link since
        // changed or removed, in another branch: follow merges, and treat a removed link as
        // virtual.
        // The link itself is the current link's identity: its ends are its ends now.
        current.from = self.resolve(current.from);
        current.to = self.resolve(current.to);
        if let Some(l) = current.link {
            match &self.links[l] {
                Some(link) => {
                    current.from = link.from;
                    current.to = link.to;
                }
                None => current.link = None,
            }
        }
        let (s, t) = (current.from, current.to);
        match op {
            Command::Split => {
                let w = arg(1.0)?;
                let m = self.add_neuron(NeuronFunction::Sigmoid, Role::Hidden, part);
                match current.link {
                    Some(l) => self.links[l].as_mut().expect("checked").to = m,
                    None => {
                        self.add_link(s, m, 1.0);
                    }
                }
                let new = self.add_link(m, t, w);
                *current = self.current_of(new);
            }
            Command::Duplicate => {
                let w = arg(1.0)?;
                self.add_link(s, t, w);
            }
            Command::Loop => {
                let w = arg(1.0)?;
                self.add_link(t, t, w);
            }
            Command::Merge => {
                let n = index(0.0)?;
                if s != t {
                    if self.neurons[s].role != Role::Hidden {
                        return Err(
                            "merge would remove a sensor or actuator neuron: ignored".into()
                        );
                    }
                    for l in self.links.iter_mut().flatten() {
                        if l.to == s {
                            l.to = t;
                        }
                        if l.from == s {
                            l.from = t;
                        }
                    }
                    self.alive[s] = false;
                    self.merged_into[s] = Some(t);
                }
                let inputs = self.inputs(t);
                *current = if inputs.is_empty() {
                    CurrentLink {
                        from: t,
                        to: t,
                        link: None,
                    }
                } else {
                    self.current_of(inputs[n % inputs.len()])
                };
            }
            Command::Next => {
                let n = index(1.0)?;
                let inputs = self.inputs(t);
                if inputs.is_empty() {
                    return Err("the target neuron has no input links: ignored".into());
                }
                let at = current
                    .link
                    .and_then(|l| inputs.iter().position(|&k| k == l))
                    .map_or(n, |k| k + n);
                *current = self.current_of(inputs[at % inputs.len()]);
            }
            Command::Parent => {
                // Hornby & Pollack: the from-neuron becomes the nth input neuron of the current
                // from-neuron, the to-neuron stays, and when no link joins them the current
                // link is virtual (Matos & Arita, Table 1: "changes the head neuron to its nth
                // parent, if it exists").
                let n = index(0.0)?;
                let inputs = self.inputs(s);
                if inputs.is_empty() {
                    return Err("the source neuron has no input links: ignored".into());
                }
                let p = self.links[inputs[n % inputs.len()]]
                    .as_ref()
                    .expect("an actual link")
                    .from;
                if p != s {
                    *current = match self.first_link(p, t) {
                        Some(l) => self.current_of(l),
                        None => CurrentLink {
                            from: p,
                            to: t,
                            link: None,
                        },
                    };
                }
            }
            Command::Output => {
                let w = arg(1.0)?;
                let Some((joint, dof)) = joint.filter(|&(_, dof)| dof > 0) else {
                    return Err("output needs a part with a movable joint: ignored".into());
                };
                let used = self
                    .driven
                    .iter()
                    .find(|(j, _)| *j == joint)
                    .map_or(0, |(_, n)| *n);
                if used >= dof {
                    return Err(format!(
                        "joint {joint} already has an output for each of its {dof} degree(s) of freedom: ignored"
                    ));
                }
                match self.driven.iter_mut().find(|(j, _)| *j == joint) {
                    Some(entry) => entry.1 += 1,
                    None => self.driven.push((joint, 1)),
                }
                let o = self.add_neuron(
                    NeuronFunction::Linear,
                    Role::Actuator {
                        actuator: Actuator::Joint { joint, dof: used },
                    },
                    part,
                );
                self.add_link(t, o, w);
            }
            Command::Reverse => {
                if let Some(l) = current.link {
                    let link = self.links[l].as_mut().expect("checked");
                    std::mem::swap(&mut link.from, &mut link.to);
                }
                std::mem::swap(&mut current.from, &mut current.to);
            }
            Command::Setfunc => {
                let n = index(0.0)?;
                if matches!(self.neurons[t].role, Role::Sensor { .. }) {
                    return Err("a sensor neuron's output is its reading: setfunc ignored".into());
                }
                let choices = NeuronFunction::SETFUNC;
                self.neurons[t].function = choices[n % choices.len()];
            }
            Command::Bias => {
                let b = arg(1.0)?;
                if matches!(self.neurons[t].role, Role::Sensor { .. }) {
                    return Err("a sensor neuron's output is its reading: bias ignored".into());
                }
                self.neurons[t].bias = b;
            }
            Command::Cut => {
                if let Some(l) = current.link.take() {
                    self.links[l] = None;
                }
            }
            Command::Weight | Command::Increase | Command::Decrease => {
                let mut w = arg(1.0)?;
                if op == Command::Decrease {
                    w = -w;
                }
                match current.link {
                    Some(l) => self.links[l].as_mut().expect("checked").weight += w,
                    None => {
                        let new = self.add_link(s, t, w);
                        *current = self.current_of(new);
                    }
                }
            }
            Command::Touch | Command::Angle | Command::Chem | Command::Target => {
                let sensor = match op {
                    Command::Touch => Sensor::Touch {
                        part: part.ok_or("touch needs a part to sense: ignored")?,
                        face: None,
                    },
                    Command::Angle => {
                        let (joint, _) = joint
                            .filter(|&(_, dof)| dof > 0)
                            .ok_or("angle needs a part with a movable joint: ignored")?;
                        Sensor::Angle { joint, dof: 0 }
                    }
                    Command::Chem => Sensor::Chemical {
                        slot: self.slot(index(0.0)?)?,
                    },
                    _ => Sensor::Target,
                };
                let i = self.add_neuron(NeuronFunction::Linear, Role::Sensor { sensor }, part);
                self.add_link(i, t, 1.0);
            }
            Command::Secrete | Command::Release => {
                let actuator = if op == Command::Secrete {
                    Actuator::Secrete {
                        slot: self.slot(index(0.0)?)?,
                    }
                } else {
                    Actuator::Release
                };
                let o = self.add_neuron(NeuronFunction::Linear, Role::Actuator { actuator }, part);
                self.add_link(t, o, 1.0);
            }
            body => return Err(format!("'{}' is not a brain command", body.name())),
        }
        Ok(())
    }

    fn slot(&self, slot: usize) -> Result<usize, String> {
        if slot < self.environment_len {
            Ok(slot)
        } else {
            Err(format!(
                "environment slot {slot} is outside the environment of {} slot(s): ignored",
                self.environment_len
            ))
        }
    }

    /// The network, with removed neurons and links left out and indices renumbered.
    pub fn finish(self) -> Brain {
        let mut new_index = vec![usize::MAX; self.neurons.len()];
        let mut neurons = Vec::new();
        for (i, n) in self.neurons.into_iter().enumerate() {
            if self.alive[i] {
                new_index[i] = neurons.len();
                neurons.push(n);
            }
        }
        let links = self
            .links
            .into_iter()
            .flatten()
            .map(|l| Link {
                from: new_index[l.from],
                to: new_index[l.to],
                weight: l.weight,
            })
            .collect();
        Brain { neurons, links }
    }
}
