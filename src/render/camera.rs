//! Where pictures look from: the region of the world a picture keeps in view ([`View`]), how an
//! animation's view moves from image to image ([`Framing`]), and the orthographic 3/4 camera
//! that projects world points to pixels.

use nalgebra::{Matrix3, Vector3};

use crate::creature::Creature;

/// What the camera looks at: a world-space box kept in view.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Lower corner of the region to show.
    pub min: Vector3<f64>,
    /// Upper corner of the region to show.
    pub max: Vector3<f64>,
}

impl View {
    /// A view that frames `creature` (with the ground below it).
    pub fn framing(creature: &Creature) -> View {
        let (mut min, mut max) = creature.bounding_box();
        if creature.parts.is_empty() {
            min = Vector3::new(-1.0, 0.0, -1.0);
            max = Vector3::new(1.0, 1.0, 1.0);
        }
        View { min, max }
    }

    /// A view that frames every creature of a sequence (so an animation does not jump).
    pub fn framing_all<'a>(creatures: impl IntoIterator<Item = &'a Creature>) -> View {
        let mut view: Option<View> = None;
        for c in creatures {
            if c.parts.is_empty() {
                continue;
            }
            let v = View::framing(c);
            view = Some(match view {
                None => v,
                Some(w) => View {
                    min: w.min.inf(&v.min),
                    max: w.max.sup(&v.max),
                },
            });
        }
        view.unwrap_or(View {
            min: Vector3::new(-1.0, 0.0, -1.0),
            max: Vector3::new(1.0, 1.0, 1.0),
        })
    }
}

/// How an animation's camera moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Framing {
    /// One view that holds every image (growth: the creature grows in place).
    Still,
    /// The camera follows the first `parts` parts of each image (the creature, not a thrown
    /// projectile drawn after them) and keeps the creature's own size in the picture, so a
    /// creature that travels far stays large; the ground's grid shows the motion.
    Following {
        /// How many leading parts of each image are the creature.
        parts: usize,
    },
}

impl View {
    /// One view per image for `framing`.
    pub(super) fn per_image<'a>(
        creatures: impl IntoIterator<Item = &'a Creature> + Clone,
        framing: Framing,
    ) -> Vec<View> {
        match framing {
            Framing::Still => {
                let view = View::framing_all(creatures.clone());
                creatures.into_iter().map(|_| view).collect()
            }
            Framing::Following { parts } => {
                let boxes: Vec<Option<(Vector3<f64>, Vector3<f64>)>> = creatures
                    .into_iter()
                    .map(|c| {
                        let own = &c.parts[..parts.min(c.parts.len())];
                        let mut corners = own.iter().flat_map(|p| p.corners());
                        let first = corners.next()?;
                        Some(corners.fold((first, first), |(lo, hi), x| (lo.inf(&x), hi.sup(&x))))
                    })
                    .collect();
                // The creature's largest own extent, on each axis, over the images.
                let extent = boxes
                    .iter()
                    .flatten()
                    .fold(Vector3::repeat(0.5), |e, (lo, hi)| e.sup(&(hi - lo)));
                let fallback = View::framing_all(std::iter::empty());
                boxes
                    .into_iter()
                    .map(|b| match b {
                        None => fallback,
                        Some((lo, hi)) => {
                            let centre = (lo + hi) / 2.0;
                            let mut min = centre - extent / 2.0;
                            let mut max = centre + extent / 2.0;
                            // Keep the ground in the picture.
                            min.y = lo.y.min(0.0);
                            max.y = min.y + extent.y.max(hi.y - min.y);
                            View { min, max }
                        }
                    })
                    .collect()
            }
        }
    }
}

/// An orthographic 3/4 camera: world point -> (x, y, depth) in pixels.
pub(super) struct Camera {
    rotation: Matrix3<f64>,
    pub(super) scale: f64,
    offset: (f64, f64),
}

impl Camera {
    pub(super) fn new(view: &View, width: f64, height: f64, margin: f64) -> Camera {
        // Azimuth 35° round the vertical, then 25° down: the classic 3/4 view.
        let yaw = 35f64.to_radians();
        let pitch = 25f64.to_radians();
        let ry = Matrix3::new(
            yaw.cos(),
            0.0,
            -yaw.sin(),
            0.0,
            1.0,
            0.0,
            yaw.sin(),
            0.0,
            yaw.cos(),
        );
        let rx = Matrix3::new(
            1.0,
            0.0,
            0.0,
            0.0,
            pitch.cos(),
            -pitch.sin(),
            0.0,
            pitch.sin(),
            pitch.cos(),
        );
        let rotation = rx * ry;
        // Fit the view box (with the ground plane grid around it) into the picture.
        let ground = view.min.y.min(0.0);
        let pad = 0.25 * (view.max - view.min).norm().max(0.5);
        let lo = Vector3::new(view.min.x - pad, ground, view.min.z - pad);
        let hi = Vector3::new(
            view.max.x + pad,
            view.max.y.max(ground + 0.1),
            view.max.z + pad,
        );
        let mut min = (f64::INFINITY, f64::INFINITY);
        let mut max = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for i in 0..8 {
            let p = Vector3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let q = rotation * p;
            min = (min.0.min(q.x), min.1.min(q.y));
            max = (max.0.max(q.x), max.1.max(q.y));
        }
        let span = ((max.0 - min.0) / (width - 2.0 * margin))
            .max((max.1 - min.1) / (height - 2.0 * margin))
            .max(1e-9);
        let scale = 1.0 / span;
        let offset = (
            width / 2.0 - scale * (min.0 + max.0) / 2.0,
            height / 2.0 + scale * (min.1 + max.1) / 2.0,
        );
        Camera {
            rotation,
            scale,
            offset,
        }
    }

    /// Screen x, y and depth (larger is nearer the viewer).
    pub(super) fn project(&self, p: &Vector3<f64>) -> (f32, f32, f64) {
        let q = self.rotation * p;
        (
            (self.offset.0 + self.scale * q.x) as f32,
            (self.offset.1 - self.scale * q.y) as f32,
            q.z,
        )
    }

    /// The direction towards the viewer, in world coordinates.
    pub(super) fn towards_viewer(&self) -> Vector3<f64> {
        self.rotation.transpose() * Vector3::z()
    }
}
