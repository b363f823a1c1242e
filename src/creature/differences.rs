//! How two creatures differ: the phenotypes one genome grows in two environments (parts,
//! joints, sizes, placements, neurons), so that a body that depends on its environment can be
//! told from one that does not.

use std::fmt;

use super::Creature;
use crate::number::format_number;

/// A difference in an edge length or a position smaller than this (in metres), or in an
/// orientation smaller than this (in radians), is rounding, not a change.
const SIZE_TOLERANCE: f64 = 1e-9;

/// How creature `b` differs from creature `a` ([`phenotype_differences`]): each count as
/// (a's, b's).
#[derive(Clone, Debug, PartialEq)]
pub struct PhenotypeDifferences {
    /// Parts.
    pub parts: (usize, usize),
    /// Joints.
    pub joints: (usize, usize),
    /// Neurons.
    pub neurons: (usize, usize),
    /// Links between neurons.
    pub links: (usize, usize),
    /// Total volume of the parts (m³).
    pub volume: (f64, f64),
    /// Of the parts both have (the same id: the same place in order), how many differ in
    /// size.
    pub resized: usize,
    /// The largest difference of an edge length between two parts of the same id (m).
    pub largest_resize: f64,
    /// The summed size difference: over the parts both have (the same id), the sum of the
    /// differences of their three edge lengths, |Δx| + |Δy| + |Δz| (m). Parts only one of
    /// the two has count in `parts` and `volume`, not here.
    pub summed_resize: f64,
    /// Of the parts both have, how many are placed elsewhere (another centre or
    /// orientation): a limb turned another way, or moved by a part before it that grew.
    pub moved: usize,
    /// Of the joints both have, how many differ in kind.
    pub joints_of_another_kind: usize,
}

impl PhenotypeDifferences {
    /// Whether the two creatures have the same body and brain, as far as these counts,
    /// sizes and placements tell.
    pub fn is_same(&self) -> bool {
        self.parts.0 == self.parts.1
            && self.joints.0 == self.joints.1
            && self.neurons.0 == self.neurons.1
            && self.links.0 == self.links.1
            && self.resized == 0
            && self.moved == 0
            && self.joints_of_another_kind == 0
    }
}

/// How `b` differs from `a`: parts, joints, neurons and links counted, total volume, and
/// the parts and joints of the same id compared.
pub fn phenotype_differences(a: &Creature, b: &Creature) -> PhenotypeDifferences {
    let (mut resized, mut moved) = (0, 0);
    let (mut largest_resize, mut summed_resize): (f64, f64) = (0.0, 0.0);
    for (pa, pb) in a.parts.iter().zip(&b.parts) {
        let edges = (pa.size - pb.size).abs();
        let change = edges.max();
        if change > SIZE_TOLERANCE {
            resized += 1;
            largest_resize = largest_resize.max(change);
            summed_resize += edges.sum();
        }
        if (pa.position - pb.position).abs().max() > SIZE_TOLERANCE
            || pa.orientation.angle_to(&pb.orientation) > SIZE_TOLERANCE
        {
            moved += 1;
        }
    }
    let volume = |c: &Creature| c.parts.iter().map(|p| p.volume()).sum::<f64>();
    PhenotypeDifferences {
        parts: (a.parts.len(), b.parts.len()),
        joints: (a.joints.len(), b.joints.len()),
        neurons: (a.brain.neurons.len(), b.brain.neurons.len()),
        links: (a.brain.links.len(), b.brain.links.len()),
        volume: (volume(a), volume(b)),
        resized,
        largest_resize,
        summed_resize,
        moved,
        joints_of_another_kind: a
            .joints
            .iter()
            .zip(&b.joints)
            .filter(|(ja, jb)| ja.kind != jb.kind)
            .count(),
    }
}

/// One line: `the same body and brain`, or each count that differs as `parts 3 -> 5`, then
/// the volume, the parts resized and those placed elsewhere.
impl fmt::Display for PhenotypeDifferences {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_same() {
            return write!(f, "the same body and brain");
        }
        let mut said = Vec::new();
        for (name, (x, y)) in [
            ("parts", self.parts),
            ("joints", self.joints),
            ("neurons", self.neurons),
            ("links", self.links),
        ] {
            if x != y {
                said.push(format!("{name} {x} -> {y}"));
            }
        }
        if self.volume.0 != self.volume.1 {
            said.push(format!(
                "volume {} -> {} m³",
                format_number(self.volume.0),
                format_number(self.volume.1)
            ));
        }
        if self.resized > 0 {
            said.push(format!(
                "{} part(s) of the same id resized (by up to {} m)",
                self.resized,
                format_number(self.largest_resize)
            ));
        }
        if self.moved > 0 {
            said.push(format!(
                "{} part(s) of the same id placed elsewhere",
                self.moved
            ));
        }
        if self.joints_of_another_kind > 0 {
            said.push(format!(
                "{} joint(s) of the same id of another kind",
                self.joints_of_another_kind
            ));
        }
        write!(f, "{}", said.join(", "))
    }
}
