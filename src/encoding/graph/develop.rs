//! The graph genome's development: the depth-first walk from the root that makes a part per
//! visit of a node, with its joint, its copies of local neurons, and its sensors and effectors.

use super::*;

impl GraphGenome {
    /// The creature the genome develops into, with at most `max_parts` parts (see the module
    /// documentation). Never panics; the genome should pass [`GraphGenome::check`] (values out
    /// of range are used as they are, connections to missing nodes are skipped).
    pub fn creature(&self, max_parts: usize) -> Creature {
        let mut d = Development {
            genome: self,
            max_parts: max_parts.max(1),
            creature: Creature::default(),
            on_cycle: on_cycle(&self.nodes),
            counts: vec![0; self.nodes.len()],
            instances: Vec::new(),
            links: Vec::new(),
            capped: false,
        };
        for g in &self.neurons {
            let role = match g.effector {
                Some(Effector::Release) => Role::Actuator {
                    actuator: Actuator::Release,
                },
                _ => Role::Hidden,
            };
            d.creature.brain.neurons.push(neuron_of(g, role, None));
        }
        if let Some(root) = self.nodes.first() {
            let size = clamp_size(Vector3::from(root.size));
            d.grow(
                0,
                None,
                Vector3::zeros(),
                Rotation3::identity(),
                size,
                1.0,
                false,
            );
        }
        // Global neurons' inputs: other globals and the root part's touch sensors.
        for (k, g) in self.neurons.iter().enumerate() {
            for input in &g.inputs {
                let from = match input.source {
                    Source::Global { neuron } if neuron < self.neurons.len() => Some(neuron),
                    Source::Touch { face } if !d.instances.is_empty() => Some(d.sensor(
                        0,
                        Sensor::Touch {
                            part: 0,
                            face: Some(face),
                        },
                    )),
                    _ => None,
                };
                if let Some(from) = from {
                    d.links.push((
                        k,
                        Link {
                            from,
                            to: k,
                            weight: input.weight,
                        },
                    ));
                }
            }
        }
        if d.capped {
            d.creature.problems.push(Problem {
                severity: Severity::Warning,
                message: format!(
                    "the graph makes more than {} parts (max_parts): the rest is not built",
                    d.max_parts
                ),
                module: None,
                t: None,
            });
        }
        // Links grouped by destination, each neuron's inputs in order.
        d.links.sort_by_key(|(to, _)| *to);
        d.creature.brain.links = d.links.into_iter().map(|(_, l)| l).collect();
        for (a, b) in d.creature.interpenetrating_pairs() {
            d.creature.problems.push(Problem {
                severity: Severity::Error,
                message: format!("parts {a} and {b} interpenetrate"),
                module: None,
                t: None,
            });
        }
        d.creature
    }
}

pub(super) fn clamp_size(v: Vector3<f64>) -> Vector3<f64> {
    v.map(|x| {
        if x.is_finite() {
            x.clamp(PART_SIZE_RANGE.0, PART_SIZE_RANGE.1)
        } else {
            PART_SIZE_RANGE.0
        }
    })
}

/// The rotation from a face's frame to the part's: its x is the face's outward normal; its y
/// and z span the face (the `position` coordinates).
pub fn face_frame(face: Face) -> Matrix3<f64> {
    let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
    let cols = match face {
        Face::Front => [x, y, z],
        Face::Back => [-x, y, -z],
        Face::Top => [y, -x, z],
        Face::Bottom => [-y, x, z],
        Face::Right => [z, y, -x],
        Face::Left => [-z, y, x],
    };
    Matrix3::from_columns(&cols)
}

/// The face a mirrored part calls `face` (the mirror flips its width axis).
pub(super) fn mirrored_face(face: Face) -> Face {
    match face {
        Face::Right => Face::Left,
        Face::Left => Face::Right,
        f => f,
    }
}

/// The rotation of a connection's turn: bends about the face's y and z axes, then a roll
/// about the child's length.
pub(super) fn turn(o: &[f64; 3]) -> Matrix3<f64> {
    let r = Rotation3::from_axis_angle(&Vector3::y_axis(), o[0])
        * Rotation3::from_axis_angle(&Vector3::z_axis(), o[1])
        * Rotation3::from_axis_angle(&Vector3::x_axis(), o[2]);
    *r.matrix()
}

/// One part made by development.
pub(super) struct Instance {
    node: usize,
    /// Brain index of the node's first local neuron in this part.
    first_neuron: usize,
    /// The joint to the parent part.
    joint: Option<usize>,
    /// Sensors made for this part so far.
    sensors: Vec<(Sensor, usize)>,
}

pub(super) struct Development<'a> {
    genome: &'a GraphGenome,
    max_parts: usize,
    creature: Creature,
    on_cycle: Vec<bool>,
    /// How many times each node is on the current path from the root.
    counts: Vec<u32>,
    instances: Vec<Instance>,
    /// (destination, link), collected in input order.
    links: Vec<(usize, Link)>,
    capped: bool,
}

impl Development<'_> {
    /// The brain index of part `part`'s sensor `sensor`, made on first use.
    pub(super) fn sensor(&mut self, part: usize, sensor: Sensor) -> usize {
        if let Some((_, i)) = self.instances[part]
            .sensors
            .iter()
            .find(|(s, _)| *s == sensor)
        {
            return *i;
        }
        let i = self.creature.brain.neurons.len();
        self.creature.brain.neurons.push(Neuron {
            function: NeuronFunction::Linear,
            params: Vec::new(),
            bias: 0.0,
            role: Role::Sensor { sensor },
            part: Some(part),
        });
        self.instances[part].sensors.push((sensor, i));
        i
    }

    /// Makes a part of node `node` (and, recursively, its children): `parent` is the parent
    /// part and the joint's anchor, `centre`, `rotation` and `size` the part's pose and size,
    /// `scale` the product of the scales on its path, `mirrored` whether it is reflected.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn grow(
        &mut self,
        node: usize,
        parent: Option<(usize, Vector3<f64>)>,
        centre: Vector3<f64>,
        rotation: Rotation3<f64>,
        size: Vector3<f64>,
        scale: f64,
        mirrored: bool,
    ) {
        let gene = &self.genome.nodes[node];
        let part = self.creature.parts.len();
        self.creature.parts.push(Part {
            size,
            position: centre,
            orientation: UnitQuaternion::from_rotation_matrix(&rotation),
            density: DEFAULT_DENSITY,
            growing: false,
        });
        let joint = parent.map(|(parent, anchor)| {
            let m = rotation.matrix();
            let (x, y, z) = (
                m.column(0).into_owned(),
                m.column(1).into_owned(),
                m.column(2).into_owned(),
            );
            let axes = match gene.joint {
                JointKind::Rigid => vec![],
                JointKind::Revolute => vec![z],
                JointKind::Twist => vec![x],
                JointKind::Universal => vec![z, y],
                JointKind::BendTwist => vec![z, x],
                JointKind::TwistBend => vec![x, z],
                JointKind::Spherical => vec![x, y, z],
            };
            let dof = gene.joint.dof();
            let mut limits: Vec<(f64, f64)> = gene
                .limits
                .iter()
                .take(dof)
                .map(|&(lo, hi)| {
                    let (lo, hi) = (lo.min(0.0), hi.max(0.0));
                    (lo.max(-std::f64::consts::PI), hi.min(std::f64::consts::PI))
                })
                .collect();
            limits.resize(dof, (0.0, 0.0));
            let j = self.creature.joints.len();
            self.creature.joints.push(Joint {
                parent,
                child: part,
                kind: gene.joint,
                anchor,
                axes,
                limits,
                strength: 1.0,
                growing: false,
            });
            j
        });
        let dof = joint.map_or(0, |j| self.creature.joints[j].kind.dof());
        // Local neurons: a copy per part.
        let first_neuron = self.creature.brain.neurons.len();
        for g in &gene.neurons {
            let role = match g.effector {
                Some(Effector::Joint { dof: k }) if k < dof => Role::Actuator {
                    actuator: Actuator::Joint {
                        joint: joint.expect("dof > 0 needs a joint"),
                        dof: k,
                    },
                },
                Some(Effector::Release) => Role::Actuator {
                    actuator: Actuator::Release,
                },
                _ => Role::Hidden,
            };
            self.creature
                .brain
                .neurons
                .push(neuron_of(g, role, Some(part)));
        }
        let parent_instance = parent.map(|(p, _)| p);
        self.instances.push(Instance {
            node,
            first_neuron,
            joint,
            sensors: Vec::new(),
        });
        for (k, g) in gene.neurons.iter().enumerate() {
            let to = first_neuron + k;
            for input in &g.inputs {
                let from = match input.source {
                    Source::Local { neuron } if neuron < gene.neurons.len() => {
                        Some(first_neuron + neuron)
                    }
                    Source::Parent { neuron } => parent_instance.and_then(|p| {
                        let inst = &self.instances[p];
                        (neuron < self.genome.nodes[inst.node].neurons.len())
                            .then_some(inst.first_neuron + neuron)
                    }),
                    Source::Global { neuron } if neuron < self.genome.neurons.len() => Some(neuron),
                    Source::Touch { face } => {
                        let face = if mirrored { mirrored_face(face) } else { face };
                        Some(self.sensor(
                            part,
                            Sensor::Touch {
                                part,
                                face: Some(face),
                            },
                        ))
                    }
                    Source::Angle { dof: k } if k < dof => {
                        let joint = self.instances[part].joint.expect("dof > 0 needs a joint");
                        Some(self.sensor(part, Sensor::Angle { joint, dof: k }))
                    }
                    _ => None,
                };
                if let Some(from) = from {
                    self.links.push((
                        to,
                        Link {
                            from,
                            to,
                            weight: input.weight,
                        },
                    ));
                }
            }
        }
        // Children.
        self.counts[node] += 1;
        let terminal = self.counts[node] >= gene.recursive_limit || !self.on_cycle[node];
        let half = size / 2.0;
        for c in &gene.connections {
            if c.to >= self.genome.nodes.len()
                || (c.terminal_only && !terminal)
                || self.counts[c.to] >= self.genome.nodes[c.to].recursive_limit.max(1)
            {
                continue;
            }
            if self.creature.parts.len() >= self.max_parts {
                self.capped = true;
                break;
            }
            let child = &self.genome.nodes[c.to];
            let child_scale = scale * c.scale;
            let child_size = clamp_size(Vector3::from(child.size) * child_scale);
            let f = face_frame(c.face);
            let extent = |col: usize| f.column(col).abs().dot(&half);
            let mut anchor = f.column(0) * extent(0)
                + f.column(1) * (c.position[0].clamp(-1.0, 1.0) * extent(1))
                + f.column(2) * (c.position[1].clamp(-1.0, 1.0) * extent(2));
            let mut q = f * turn(&c.orientation);
            let child_mirrored = mirrored ^ c.reflection;
            if child_mirrored {
                let p = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
                anchor = p * anchor;
                q = p * q * p;
            }
            let local_centre = anchor + q.column(0) * (child_size.x / 2.0);
            let child_rotation = rotation * Rotation3::from_matrix_unchecked(q);
            let world_anchor = centre + rotation * anchor;
            let child_centre = centre + rotation * local_centre;
            self.grow(
                c.to,
                Some((part, world_anchor)),
                child_centre,
                child_rotation,
                child_size,
                child_scale,
                child_mirrored,
            );
        }
        self.counts[node] -= 1;
    }
}

pub(super) fn neuron_of(g: &NeuronGene, role: Role, part: Option<usize>) -> Neuron {
    Neuron {
        function: g.function,
        params: g.params.clone(),
        bias: g.bias,
        role,
        part,
    }
}
