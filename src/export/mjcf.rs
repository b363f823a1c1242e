//! MuJoCo's MJCF: a creature as a `<mujoco>` model, with the settings of [`SimOptions`].
//!
//! What is mapped, and how (docs/guide/exporting.md says the same for users):
//!
//! - **Axes.** MuJoCo is Z up; Ontogeny is Y up. The whole model is rotated +90° about x:
//!   Ontogeny's (x, y, z) is MuJoCo's (x, −z, y). The ground is a `plane` at z = 0 and
//!   gravity is (0, 0, −[`GRAVITY`]).
//! - **Bodies.** One `<body name="partI">` per part, nested along the joints from each root
//!   part (a part that is no joint's child: part 0, and any part joined to nothing). Root
//!   bodies carry a `<freejoint>`; positions and orientations are relative to the parent body.
//!   The creature is lifted, as the simulator drops it, so that its lowest point is
//!   `drop_height` above the ground.
//! - **Geoms.** One `box` per part, `size` = half its edge lengths, `density` = the part's,
//!   `friction` = `options.friction` (MuJoCo's default torsional and rolling friction, which
//!   its default `condim` 3 does not use). The ground has the same friction.
//! - **Joints.** A joint of n degrees of freedom is n `hinge`s in the child body, at the
//!   anchor, about the axes of the simulator's joint frame (x along the first axis, y along the
//!   second made perpendicular, z = x × y), in that order, each with its `range` in radians:
//!   MuJoCo composes them as the simulator's angles read them (intrinsic x, then y, then z).
//!   A rigid joint is no joint: the child body is welded to its parent. A part that is the
//!   child of two joints (a loop) is an error.
//! - **Contacts.** The simulator disables contacts between the two parts of every joint and
//!   keeps them between all other parts: the export writes a `<contact><exclude>` per joint
//!   and turns MuJoCo's own parent filter off (`<flag filterparent="disable"/>`). Without
//!   self-collision, parts have `conaffinity="0"`, so they touch the ground only.
//! - **Time.** `timestep` = `dt / substeps`, `iterations` = `solver_iterations` (MuJoCo's
//!   Newton solver counts iterations differently from rapier's), and `integrator` =
//!   `implicitfast`, which integrates the actuators' stiff velocity gains implicitly. The
//!   control step, the substeps and the actuator model are in `<custom>`.
//! - **Actuators.** One per driven degree of freedom (the last neuron driving it wins, as in
//!   the simulator), named after its hinge, with force range ± the joint's maximum torque
//!   ([`max_torque`]): the *velocity* model is a `<velocity>` actuator, `kv` =
//!   [`SATURATION_DAMPING`] × maximum torque, ctrl = s × `max_speed`; the *angle* model a
//!   `<position>` actuator, `kp` = [`ANGLE_STIFFNESS`] and `kv` = [`ANGLE_DAMPING`] × maximum
//!   torque, ctrl = the target angle lo + (s + 1)/2 × (hi − lo); the *muscle* model the same
//!   `<velocity>` actuator, driven with ctrl = V_des (`muscle_speed`) × sign(s) and
//!   its force range scaled to ± |s| × maximum torque at every control step (MuJoCo cannot
//!   scale a force limit by the control inside the model). `<custom>` lists the neuron of
//!   every actuator (`ontogeny_actuator_neurons`) and its maximum torque
//!   (`ontogeny_max_torque`); a comment before each actuator says the same.
//! - **World.** [`to_mjcf_in`] writes the creature's world beside it (module `mjcf_world`),
//!   the creature lifted above the highest ground under it.
//!
//! Not exported: the brain itself, sensors, secreting and release effectors, the catapult's
//! projectile, and the simulator's explosion checks.

use std::fmt::Write as _;

use nalgebra::{UnitQuaternion, Vector3};

pub use super::mjcf_numbers::z_up;
use super::mjcf_numbers::{numbers, quat, vec3};
use super::{ExportError, mjcf_world};
use crate::creature::{Actuator, Creature, Joint, Role};
use crate::sim::terrain::Terrain;
use crate::sim::{
    ANGLE_DAMPING, ANGLE_STIFFNESS, ActuatorModel, GRAVITY, SATURATION_DAMPING, SimOptions,
    WorldSpec, max_torque,
};

/// MuJoCo's default torsional and rolling friction, written beside the sliding friction.
const TORSIONAL_AND_ROLLING: &str = "0.005 0.0001";

/// One exported actuator: which hinge it drives, and from which neuron.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfActuator {
    /// Its name, which is also the name of the hinge it drives (`jointJ_dofK`).
    pub name: String,
    /// The creature's joint.
    pub joint: usize,
    /// The joint's degree of freedom.
    pub dof: usize,
    /// The actuator neuron whose output drives it.
    pub neuron: usize,
    /// The joint's maximum torque (N·m), the actuator's force range.
    pub max_torque: f64,
}

/// The name of degree of freedom `dof` of joint `joint` (the hinge and its actuator).
fn hinge_name(joint: usize, dof: usize) -> String {
    format!("joint{joint}_dof{dof}")
}

/// The actuators [`to_mjcf`] writes, in order: one per (joint, degree of freedom) that an
/// actuator neuron drives and whose maximum torque is positive, sorted by joint and degree of
/// freedom; when several neurons drive one degree of freedom, the last one (the one whose
/// command the simulator applies) is listed.
pub fn mjcf_actuators(creature: &Creature, options: &SimOptions) -> Vec<MjcfActuator> {
    let mut driven = std::collections::BTreeMap::new();
    for (neuron, n) in creature.brain.neurons.iter().enumerate() {
        if let Role::Actuator {
            actuator: Actuator::Joint { joint, dof },
        } = n.role
            && joint < creature.joints.len()
            && dof < creature.joints[joint].kind.dof()
        {
            driven.insert((joint, dof), neuron);
        }
    }
    driven
        .into_iter()
        .map(|((joint, dof), neuron)| MjcfActuator {
            name: hinge_name(joint, dof),
            joint,
            dof,
            neuron,
            max_torque: max_torque(creature, &creature.joints[joint], options),
        })
        .filter(|a| a.max_torque > 0.0)
        .collect()
}

/// The joints as a forest: per part, the joint that makes it a child, and per part, the
/// joints that make it a parent (in joint order).
struct Tree {
    parent_joint: Vec<Option<usize>>,
    child_joints: Vec<Vec<usize>>,
}

fn tree(creature: &Creature) -> Result<Tree, ExportError> {
    let n = creature.parts.len();
    let mut parent_joint: Vec<Option<usize>> = vec![None; n];
    let mut child_joints = vec![Vec::new(); n];
    for (j, joint) in creature.joints.iter().enumerate() {
        if let Some(first) = parent_joint[joint.child] {
            return Err(ExportError::SecondParent {
                joint: j,
                part: joint.child,
                first,
            });
        }
        parent_joint[joint.child] = Some(j);
        child_joints[joint.parent].push(j);
    }
    // Every part must hang from a root: with one parent each, a part that does not lies on a
    // ring.
    let mut reached = vec![false; n];
    let mut stack: Vec<usize> = (0..n).filter(|&p| parent_joint[p].is_none()).collect();
    while let Some(p) = stack.pop() {
        reached[p] = true;
        stack.extend(child_joints[p].iter().map(|&j| creature.joints[j].child));
    }
    if let Some(part) = reached.iter().position(|r| !r) {
        return Err(ExportError::Ring { part });
    }
    Ok(Tree {
        parent_joint,
        child_joints,
    })
}

/// The simulator's joint frame axes, one per degree of freedom, in world coordinates: x along
/// the first axis; y along the second made perpendicular to x (or, when there is none, the
/// image of Y under the shortest rotation taking X to x); z = x × y.
fn frame_axes(joint: &Joint) -> Vec<Vector3<f64>> {
    let dof = joint.kind.dof();
    let Some(first) = joint.axes.first() else {
        return Vec::new();
    };
    let x = first.normalize();
    let y = joint
        .axes
        .get(1)
        .map(|a| a - x * a.dot(&x))
        .filter(|y| y.norm() > 1e-6)
        .map(|y| y.normalize())
        .unwrap_or_else(|| {
            let arc = UnitQuaternion::rotation_between(&Vector3::x(), &x).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI)
            });
            arc * Vector3::y()
        });
    [x, y, x.cross(&y)].into_iter().take(dof).collect()
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

/// The simulator's settings in range ([`SimOptions::check`]), so that the model's numbers are
/// finite and its time step positive.
fn check_settings(options: &SimOptions) -> Result<(), ExportError> {
    options
        .check()
        .map_err(|e| ExportError::Settings(e.to_string()))
}

/// Indentation of a body at `depth` (capped, so that deep chains stay linear in size).
fn indent(depth: usize) -> String {
    "  ".repeat(depth.min(30) + 2)
}

/// Writes the opening of a part's `<body>`: its pose, joint and geom.
struct BodyWriter<'a> {
    creature: &'a Creature,
    tree: &'a Tree,
    lift: Vector3<f64>,
    friction: &'a str,
    contacts: &'a str,
}

impl BodyWriter<'_> {
    fn open(&self, w: &mut String, part: usize, depth: usize) {
        let indent = indent(depth);
        let creature = self.creature;
        let p = &creature.parts[part];
        let parent_joint = self.tree.parent_joint[part];
        let (position, orientation) = match parent_joint {
            None => (z_up() * (p.position + self.lift), z_up() * p.orientation),
            Some(j) => {
                let parent = &creature.parts[creature.joints[j].parent];
                let inverse = parent.orientation.inverse();
                (
                    inverse * (p.position - parent.position),
                    inverse * p.orientation,
                )
            }
        };
        let _ = writeln!(
            w,
            "{indent}<body name=\"part{part}\" pos=\"{}\" quat=\"{}\">",
            vec3(&position),
            quat(&orientation)
        );
        match parent_joint {
            None => {
                let _ = writeln!(w, "{indent}  <freejoint name=\"part{part}_free\"/>");
            }
            Some(j) => {
                let joint = &creature.joints[j];
                let inverse = p.orientation.inverse();
                let anchor = inverse * (joint.anchor - p.position);
                for (k, axis) in frame_axes(joint).iter().enumerate() {
                    let (lo, hi) = joint.limits[k];
                    let _ = writeln!(
                        w,
                        "{indent}  <joint name=\"{}\" type=\"hinge\" pos=\"{}\" axis=\"{}\" limited=\"true\" range=\"{}\"/>",
                        hinge_name(j, k),
                        vec3(&anchor),
                        vec3(&(inverse * axis)),
                        numbers(&[lo, hi])
                    );
                }
            }
        }
        let _ = writeln!(
            w,
            "{indent}  <geom name=\"part{part}\" type=\"box\" size=\"{}\" density=\"{}\" friction=\"{}\"{}/>",
            numbers(&[p.size.x / 2.0, p.size.y / 2.0, p.size.z / 2.0]),
            numbers(&[p.density]),
            self.friction,
            self.contacts
        );
    }
}

/// Writes `creature` as an MJCF model named `name`, with the physics settings of `options`
/// (see the module documentation for what is mapped and how).
pub fn to_mjcf(
    creature: &Creature,
    options: &SimOptions,
    name: &str,
) -> Result<String, ExportError> {
    to_mjcf_in(creature, options, name, &WorldSpec::default())
}

/// Writes `creature` in `world` as an MJCF model named `name`, with the physics settings of
/// `options`: the creature as [`to_mjcf`] writes it, lifted above the ground under it, and
/// the world as module `mjcf_world` writes it (the slope's tilted plane, step and obstacle
/// boxes, the rough ground's `hfield`, free bodies for objects, water's options).
pub fn to_mjcf_in(
    creature: &Creature,
    options: &SimOptions,
    name: &str,
    world: &WorldSpec,
) -> Result<String, ExportError> {
    if creature.parts.is_empty() {
        return Err(ExportError::NoParts);
    }
    creature
        .check_consistency()
        .map_err(ExportError::Malformed)?;
    check_settings(options)?;
    for (j, joint) in creature.joints.iter().enumerate() {
        let dof = joint.kind.dof();
        if let Some(k) = joint.limits.iter().take(dof).position(|(lo, hi)| lo >= hi) {
            return Err(ExportError::EqualLimits { joint: j, dof: k });
        }
    }
    let tree = tree(creature)?;
    let actuators = mjcf_actuators(creature, options);
    let substeps = options.substeps.max(1);
    let friction = format!("{} {TORSIONAL_AND_ROLLING}", numbers(&[options.friction]));
    let model = match options.actuator {
        ActuatorModel::Muscle => "muscle",
        ActuatorModel::MuscleTorque => "muscle-torque",
        ActuatorModel::Angle => "angle",
        ActuatorModel::Velocity => "velocity",
    };

    let mut out = String::new();
    let w = &mut out;
    // Writing to a String cannot fail.
    let _ = writeln!(w, "<mujoco model=\"{}\">", escape(name));
    let _ = writeln!(
        w,
        "  <!-- Written by ontogeny {}. Z is up: Ontogeny's world is rotated +90 degrees about x, \
         so its (x, y, z) is this model's (x, -z, y). -->",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        w,
        "  <compiler angle=\"radian\" autolimits=\"true\" inertiafromgeom=\"true\"/>"
    );
    let terrain = Terrain::new(world);
    let medium = mjcf_world::medium_attributes(&terrain);
    if medium.is_some() {
        let _ = writeln!(w, "  {}", mjcf_world::WATER_NOTE);
    }
    let _ = writeln!(
        w,
        "  <option timestep=\"{}\" iterations=\"{}\" {} integrator=\"implicitfast\">",
        numbers(&[options.control_step / substeps as f64]),
        options.solver_iterations.max(1),
        medium.unwrap_or_else(|| format!("gravity=\"0 0 {}\"", numbers(&[-GRAVITY])))
    );
    let _ = writeln!(w, "    <flag filterparent=\"disable\"/>");
    let _ = writeln!(w, "  </option>");

    let _ = writeln!(w, "  <custom>");
    let _ = writeln!(
        w,
        "    <!-- Apply the controller every ontogeny_substeps time steps. -->"
    );
    let _ = writeln!(
        w,
        "    <numeric name=\"ontogeny_control_step\" data=\"{}\"/>",
        numbers(&[options.control_step])
    );
    let _ = writeln!(
        w,
        "    <numeric name=\"ontogeny_substeps\" data=\"{substeps}\"/>"
    );
    let _ = writeln!(
        w,
        "    <numeric name=\"ontogeny_max_speed\" data=\"{}\"/>",
        numbers(&[target_speed(options)])
    );
    let _ = writeln!(
        w,
        "    <text name=\"ontogeny_actuator_model\" data=\"{model}\"/>"
    );
    if !actuators.is_empty() {
        let neurons: Vec<String> = actuators.iter().map(|a| a.neuron.to_string()).collect();
        let torques: Vec<f64> = actuators.iter().map(|a| a.max_torque).collect();
        let _ = writeln!(
            w,
            "    <numeric name=\"ontogeny_actuator_neurons\" data=\"{}\"/>",
            neurons.join(" ")
        );
        let _ = writeln!(
            w,
            "    <numeric name=\"ontogeny_max_torque\" data=\"{}\"/>",
            numbers(&torques)
        );
    }
    let _ = writeln!(w, "  </custom>");

    mjcf_world::write_assets(w, &terrain);
    let _ = writeln!(w, "  <worldbody>");
    if world.is_flat() {
        let _ = writeln!(
            w,
            "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" friction=\"{friction}\"/>"
        );
    } else {
        let ground = mjcf_world::ground_friction(&terrain, &friction, TORSIONAL_AND_ROLLING);
        mjcf_world::write_world(w, &terrain, &ground, &friction);
    }
    let (lo, hi) = creature.bounding_box();
    // The ground's highest point under the creature (0 on level ground).
    let under = if world.medium.is_air() {
        terrain.extremes_under([lo.x, hi.x], [lo.z, hi.z]).0
    } else {
        0.0
    };
    let body = BodyWriter {
        creature,
        tree: &tree,
        lift: Vector3::new(0.0, options.drop_height - lo.y + under, 0.0),
        friction: &friction,
        contacts: if options.self_collision {
            ""
        } else {
            " conaffinity=\"0\""
        },
    };
    // Depth-first from each root, children in joint order, with an explicit stack (a chain
    // read from a file may be deeper than the call stack).
    enum Visit {
        Open(usize, usize),
        Close(usize),
    }
    let mut stack: Vec<Visit> = (0..creature.parts.len())
        .rev()
        .filter(|&p| tree.parent_joint[p].is_none())
        .map(|p| Visit::Open(p, 0))
        .collect();
    while let Some(visit) = stack.pop() {
        match visit {
            Visit::Open(part, depth) => {
                body.open(w, part, depth);
                stack.push(Visit::Close(depth));
                for &j in tree.child_joints[part].iter().rev() {
                    stack.push(Visit::Open(creature.joints[j].child, depth + 1));
                }
            }
            Visit::Close(depth) => {
                let _ = writeln!(w, "{}</body>", indent(depth));
            }
        }
    }
    let _ = writeln!(w, "  </worldbody>");

    if !creature.joints.is_empty() {
        let _ = writeln!(w, "  <contact>");
        for joint in &creature.joints {
            let _ = writeln!(
                w,
                "    <exclude body1=\"part{}\" body2=\"part{}\"/>",
                joint.parent, joint.child
            );
        }
        let _ = writeln!(w, "  </contact>");
    }

    if !actuators.is_empty() {
        let _ = writeln!(w, "  <actuator>");
        let target_speed = target_speed(options);
        for a in &actuators {
            let t = a.max_torque;
            let _ = writeln!(
                w,
                "    <!-- neuron {} drives joint {}, degree of freedom {}; maximum torque {} N m -->",
                a.neuron,
                a.joint,
                a.dof,
                numbers(&[t])
            );
            let force = format!("forcerange=\"{}\"", numbers(&[-t, t]));
            let line = match options.actuator {
                ActuatorModel::Muscle | ActuatorModel::Velocity => format!(
                    "<velocity name=\"{0}\" joint=\"{0}\" kv=\"{1}\" ctrlrange=\"{2}\" {force}/>",
                    a.name,
                    numbers(&[t * SATURATION_DAMPING]),
                    numbers(&[-target_speed, target_speed])
                ),
                ActuatorModel::MuscleTorque => format!(
                    "<motor name=\"{0}\" joint=\"{0}\" gear=\"{1}\" ctrlrange=\"-1 1\" {force}/>",
                    a.name,
                    numbers(&[t])
                ),
                ActuatorModel::Angle => {
                    let (lo, hi) = creature.joints[a.joint].limits[a.dof];
                    format!(
                        "<position name=\"{0}\" joint=\"{0}\" kp=\"{1}\" kv=\"{2}\" ctrlrange=\"{3}\" {force}/>",
                        a.name,
                        numbers(&[t * ANGLE_STIFFNESS]),
                        numbers(&[t * ANGLE_DAMPING]),
                        numbers(&[lo, hi])
                    )
                }
            };
            let _ = writeln!(w, "    {line}");
        }
        let _ = writeln!(w, "  </actuator>");
    }
    let _ = writeln!(w, "</mujoco>");
    Ok(out)
}

/// The speed a velocity actuator's control spans: the muscle's V_des, or the velocity
/// model's top speed (`ontogeny_max_speed` in `<custom>`).
fn target_speed(options: &SimOptions) -> f64 {
    match options.actuator {
        ActuatorModel::Muscle => options.muscle_speed,
        _ => options.max_speed,
    }
}
