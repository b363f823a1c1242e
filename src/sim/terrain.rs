//! A world's geometry, worked out from its [`WorldSpec`] without any physics engine, so that the
//! simulator, pictures and exports all see the same ground: the ground's height at any point
//! (a tilted plane, a flight of steps, a rough heightfield, or level), the boxes the steps are
//! made of, the heightfield's samples, the obstacles' boxes, where the free objects start and
//! the ground's friction at any point.
//!
//! Every world is deterministic given its seeds: the heightfield's bumps and the obstacles'
//! scatter are drawn from ChaCha8 generators seeded with the spec's seeds, whose output is the
//! same on every platform.
//!
//! **Rough ground** is value noise: a grid of nodes `wavelength` apart covering the
//! heightfield's square, each given a height drawn uniformly from [−1, 1] (row by row along +z,
//! each row along +x, from the corner at −x, −z), blended between nodes with the quintic fade
//! 6t⁵ − 15t⁴ + 10t³ (smooth to its second derivative), times `amplitude`, and brought down
//! to level ground over the outermost `wavelength` of the square (the same fade), so the
//! heightfield meets the level ground round it without a ledge. It is sampled every quarter
//! `wavelength` (at most [`MAX_SAMPLES`] samples a side); between samples the ground is the
//! triangles through them.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::world_spec::{
    FAR, MAX_SAMPLES, ObjectShape, Obstacles, Rough, Slope, Steps, StepsWay, WorldSpec,
};

/// A box, possibly turned about the vertical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    /// Its centre, [x, y, z] (m).
    pub centre: [f64; 3],
    /// Its half sizes along its own axes, [x, y, z] (m).
    pub half: [f64; 3],
    /// The horizontal direction its own +x axis points in, in degrees about +y from +x
    /// towards +z (0: unturned).
    pub direction: f64,
}

impl Cuboid {
    /// Its top's height (m).
    pub fn top(&self) -> f64 {
        self.centre[1] + self.half[1]
    }
}

/// A rough ground's samples: `samples` × `samples` heights, `spacing` apart, row by row
/// along +z, each row along +x, from the corner at (−side/2, −side/2).
#[derive(Clone, Debug, PartialEq)]
pub struct Heightfield {
    /// Samples along each side.
    pub samples: usize,
    /// The side of the square it covers, centred on the origin (m).
    pub side: f64,
    /// The heights (m), `heights[row * samples + column]`, row along z, column along x.
    pub heights: Vec<f64>,
}

impl Heightfield {
    /// The distance between neighbouring samples (m).
    pub fn spacing(&self) -> f64 {
        self.side / (self.samples - 1) as f64
    }

    /// The height at (x, z) inside the square, interpolated on the triangles through the
    /// samples as the simulator splits each cell; `None` outside.
    pub fn height(&self, x: f64, z: f64) -> Option<f64> {
        let half = self.side / 2.0;
        if !(x.abs() <= half && z.abs() <= half) {
            return None;
        }
        let cells = (self.samples - 1) as f64;
        let u = ((x + half) / self.spacing()).clamp(0.0, cells);
        let v = ((z + half) / self.spacing()).clamp(0.0, cells);
        let (j, i) = (
            (u.floor() as usize).min(self.samples - 2),
            (v.floor() as usize).min(self.samples - 2),
        );
        let (fu, fv) = (u - j as f64, v - i as f64);
        let at = |i: usize, j: usize| self.heights[i * self.samples + j];
        let (h00, h01, h10, h11) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
        // Bilinear: within the two triangles' hull, exact at the samples.
        Some(
            h00 * (1.0 - fu) * (1.0 - fv)
                + h01 * fu * (1.0 - fv)
                + h10 * (1.0 - fu) * fv
                + h11 * fu * fv,
        )
    }

    /// The highest and lowest sample within one spacing of the rectangle `[x0, x1] × [z0, z1]`
    /// (level ground, 0, where the rectangle reaches beyond the square).
    fn extremes_under(&self, x: [f64; 2], z: [f64; 2]) -> (f64, f64) {
        let half = self.side / 2.0;
        let s = self.spacing();
        let index = |v: f64| ((v + half) / s).clamp(0.0, (self.samples - 1) as f64);
        let (j0, j1) = (
            index(x[0] - s).floor() as usize,
            index(x[1] + s).ceil() as usize,
        );
        let (i0, i1) = (
            index(z[0] - s).floor() as usize,
            index(z[1] + s).ceil() as usize,
        );
        let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in i0..=i1 {
            for j in j0..=j1 {
                let h = self.heights[i * self.samples + j];
                hi = hi.max(h);
                lo = lo.min(h);
            }
        }
        let beyond = x[0] < -half || x[1] > half || z[0] < -half || z[1] > half;
        if beyond {
            hi = hi.max(0.0);
            lo = lo.min(0.0);
        }
        (hi, lo)
    }
}

/// The quintic fade 6t⁵ − 15t⁴ + 10t³ of t in [0, 1].
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The samples of rough ground (see the module's notes).
pub fn rough_samples(rough: &Rough) -> Heightfield {
    let half = rough.size / 2.0;
    let nodes = (rough.size / rough.wavelength).ceil() as usize + 1;
    let mut rng = ChaCha8Rng::seed_from_u64(rough.seed);
    let grid: Vec<f64> = (0..nodes * nodes)
        .map(|_| rng.random_range(-1.0..=1.0))
        .collect();
    let noise = |x: f64, z: f64| {
        let u = ((x + half) / rough.wavelength).clamp(0.0, (nodes - 1) as f64);
        let v = ((z + half) / rough.wavelength).clamp(0.0, (nodes - 1) as f64);
        let (j, i) = (
            (u.floor() as usize).min(nodes - 2),
            (v.floor() as usize).min(nodes - 2),
        );
        let (fu, fv) = (fade(u - j as f64), fade(v - i as f64));
        let at = |i: usize, j: usize| grid[i * nodes + j];
        let low = at(i, j) + (at(i, j + 1) - at(i, j)) * fu;
        let high = at(i + 1, j) + (at(i + 1, j + 1) - at(i + 1, j)) * fu;
        low + (high - low) * fv
    };
    let samples =
        ((4.0 * rough.size / rough.wavelength).round() as usize + 1).clamp(2, MAX_SAMPLES);
    let spacing = rough.size / (samples - 1) as f64;
    let mut heights = Vec::with_capacity(samples * samples);
    for i in 0..samples {
        for j in 0..samples {
            let (x, z) = (-half + j as f64 * spacing, -half + i as f64 * spacing);
            let edge = (half - x.abs()).min(half - z.abs()).max(0.0);
            let taper = fade((edge / rough.wavelength).min(1.0));
            heights.push(rough.amplitude * taper * noise(x, z));
        }
    }
    Heightfield {
        samples,
        side: rough.size,
        heights,
    }
}

/// The unit vector of a horizontal direction in degrees about +y from +x: (x, z).
fn heading(degrees: f64) -> (f64, f64) {
    let a = degrees.to_radians();
    (a.cos(), a.sin())
}

/// The ground's height along a flight of steps, `s` metres along its direction.
fn steps_height(steps: &Steps, s: f64) -> f64 {
    if s < steps.start {
        return 0.0;
    }
    let k = (((s - steps.start) / steps.depth).floor() + 1.0).min(steps.count as f64);
    match steps.way {
        StepsWay::Up => k * steps.height,
        StepsWay::Down => -k * steps.height,
    }
}

/// The boxes a flight of steps is made of, on a level halfspace at [`Terrain::base`]: going
/// up, step k (from 1) is a box from below the base up to k·height, `depth` deep, the last
/// one reaching [`FAR`]; going down, a platform at 0 reaches back [`FAR`] to the first edge,
/// then steps at −k·height, down to the base at −count·height.
fn step_boxes(steps: &Steps) -> Vec<Cuboid> {
    let (ux, uz) = heading(steps.direction);
    let n = steps.count as usize;
    let floor = match steps.way {
        StepsWay::Up => -1.0,
        StepsWay::Down => -(n as f64) * steps.height - 1.0,
    };
    // (from, to, top) along the direction.
    let spans: Vec<(f64, f64, f64)> = match steps.way {
        StepsWay::Up => (1..=n)
            .map(|k| {
                let from = steps.start + (k - 1) as f64 * steps.depth;
                let to = if k == n { FAR } else { from + steps.depth };
                (from, to, k as f64 * steps.height)
            })
            .collect(),
        StepsWay::Down => (0..n)
            .map(|k| {
                let to = steps.start + k as f64 * steps.depth;
                let from = if k == 0 { -FAR } else { to - steps.depth };
                (from, to, -(k as f64) * steps.height)
            })
            .collect(),
    };
    spans
        .into_iter()
        .map(|(from, to, top)| {
            let mid = 0.5 * (from + to);
            Cuboid {
                centre: [mid * ux, 0.5 * (top + floor), mid * uz],
                half: [0.5 * (to - from), 0.5 * (top - floor), FAR],
                direction: steps.direction,
            }
        })
        .collect()
}

/// Where the obstacles' centres fall in the horizontal plane: the given points, or `count`
/// points drawn uniformly in the square of half-side `reach`, each drawn again until no part
/// of its box's footprint is within `clear` of the origin ([`WorldSpec::check`] makes sure
/// the square reaches past that).
pub fn obstacle_places(obstacles: &Obstacles) -> Vec<[f64; 2]> {
    if !obstacles.at.is_empty() {
        return obstacles.at.clone();
    }
    let keep_out = obstacles.clear + 0.5 * obstacles.size[0].hypot(obstacles.size[2]);
    let mut rng = ChaCha8Rng::seed_from_u64(obstacles.seed);
    let r = obstacles.reach;
    (0..obstacles.count)
        .map(|_| {
            loop {
                let x = rng.random_range(-r..=r);
                let z = rng.random_range(-r..=r);
                if x.hypot(z) >= keep_out {
                    break [x, z];
                }
            }
        })
        .collect()
}

/// A free object where it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedObject {
    /// Ball or box.
    pub shape: ObjectShape,
    /// A ball's radius, a box's half side (m).
    pub half: f64,
    /// Its mass (kg).
    pub mass: f64,
    /// Its centre, [x, y, z] (m), y now measured from 0.
    pub centre: [f64; 3],
    /// Its velocity when it is let go, [x, y, z] (m/s).
    pub velocity: [f64; 3],
}

/// A world's geometry (see the module's notes).
#[derive(Clone, Debug)]
pub struct Terrain {
    spec: WorldSpec,
    heightfield: Option<Heightfield>,
}

impl Terrain {
    /// The geometry of `spec`, which [`WorldSpec::check`] has passed.
    pub fn new(spec: &WorldSpec) -> Terrain {
        Terrain {
            spec: spec.clone(),
            heightfield: spec.rough.as_ref().map(rough_samples),
        }
    }

    /// The world it describes.
    pub fn spec(&self) -> &WorldSpec {
        &self.spec
    }

    /// The ground's height at (x, z) (m): the slope's plane, the steps' treads, the
    /// heightfield, or 0. Obstacles are not ground.
    pub fn height(&self, x: f64, z: f64) -> f64 {
        if let Some(slope) = &self.spec.slope {
            let (ux, uz) = heading(slope.direction);
            return slope.degrees.to_radians().tan() * (x * ux + z * uz);
        }
        if let Some(steps) = &self.spec.steps {
            let (ux, uz) = heading(steps.direction);
            return steps_height(steps, x * ux + z * uz);
        }
        match &self.heightfield {
            Some(field) => field.height(x, z).unwrap_or(0.0),
            None => 0.0,
        }
    }

    /// The highest and lowest ground under the rectangle `[x0, x1] × [z0, z1]` (m): exact for
    /// level ground, a slope and steps; for rough ground, the extreme samples within one
    /// sample spacing of it.
    pub fn extremes_under(&self, x: [f64; 2], z: [f64; 2]) -> (f64, f64) {
        if let Some(field) = &self.heightfield {
            return field.extremes_under(x, z);
        }
        if self.spec.slope.is_none() && self.spec.steps.is_none() {
            return (0.0, 0.0);
        }
        if let Some(steps) = &self.spec.steps {
            // The ground is monotonic along the flight: its extremes are at the rectangle's
            // nearest and farthest points along the direction.
            let (ux, uz) = heading(steps.direction);
            let along = [
                x[0] * ux + z[0] * uz,
                x[1] * ux + z[0] * uz,
                x[0] * ux + z[1] * uz,
                x[1] * ux + z[1] * uz,
            ];
            let lo = along.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = along.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let (a, b) = (steps_height(steps, lo), steps_height(steps, hi));
            return (a.max(b), a.min(b));
        }
        let corners = [(x[0], z[0]), (x[1], z[0]), (x[0], z[1]), (x[1], z[1])];
        let heights = corners.map(|(x, z)| self.height(x, z));
        (
            heights.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            heights.iter().copied().fold(f64::INFINITY, f64::min),
        )
    }

    /// The slope's plane through the origin as its upward unit normal [x, y, z], when the
    /// ground is a slope.
    pub fn slope_normal(&self) -> Option<[f64; 3]> {
        self.spec
            .slope
            .as_ref()
            .map(|Slope { degrees, direction }| {
                let (ux, uz) = heading(*direction);
                let t = degrees.to_radians();
                [-t.sin() * ux, t.cos(), -t.sin() * uz]
            })
    }

    /// The height of the level halfspace under everything else, when there is one: 0 for
    /// level ground and steps going up, −count·height for steps going down; none for a
    /// slope (its plane is tilted) or rough ground (level ground round the heightfield is
    /// [`Terrain::ground_boxes`]).
    pub fn base(&self) -> Option<f64> {
        if self.spec.slope.is_some() || self.spec.rough.is_some() {
            return None;
        }
        Some(match &self.spec.steps {
            Some(steps) if steps.way == StepsWay::Down => -(steps.count as f64) * steps.height,
            _ => 0.0,
        })
    }

    /// The boxes that are ground: a flight of steps' (see [`Terrain::base`]), or the four
    /// level slabs (top at 0, 1 m thick) round a heightfield, reaching [`FAR`].
    pub fn ground_boxes(&self) -> Vec<Cuboid> {
        if let Some(steps) = &self.spec.steps {
            return step_boxes(steps);
        }
        let Some(field) = &self.heightfield else {
            return Vec::new();
        };
        let h = field.side / 2.0;
        let slab = |x0: f64, x1: f64, z0: f64, z1: f64| Cuboid {
            centre: [0.5 * (x0 + x1), -0.5, 0.5 * (z0 + z1)],
            half: [0.5 * (x1 - x0), 0.5, 0.5 * (z1 - z0)],
            direction: 0.0,
        };
        vec![
            slab(h, FAR, -FAR, FAR),
            slab(-FAR, -h, -FAR, FAR),
            slab(-h, h, h, FAR),
            slab(-h, h, -FAR, -h),
        ]
    }

    /// The rough ground's samples, when the ground is rough.
    pub fn heightfield(&self) -> Option<&Heightfield> {
        self.heightfield.as_ref()
    }

    /// The obstacles' boxes: at [`obstacle_places`], each box's underside `raised` above the
    /// ground at its centre; a box on the ground (`raised` 0) reaches down to the lowest
    /// ground under it, so that nothing passes under its edge on a slope.
    pub fn obstacle_boxes(&self) -> Vec<Cuboid> {
        let Some(obstacles) = &self.spec.obstacles else {
            return Vec::new();
        };
        let [sx, sy, sz] = obstacles.size;
        obstacle_places(obstacles)
            .into_iter()
            .map(|[x, z]| {
                let ground = self.height(x, z);
                let (_, lo) =
                    self.extremes_under([x - sx / 2.0, x + sx / 2.0], [z - sz / 2.0, z + sz / 2.0]);
                // How far a box on the ground reaches below the ground at its centre.
                let below = if obstacles.raised > 0.0 {
                    0.0
                } else {
                    (ground - lo).max(0.0)
                };
                let half_height = 0.5 * (sy + below);
                Cuboid {
                    centre: [x, ground + obstacles.raised - below + half_height, z],
                    half: [sx / 2.0, half_height, sz / 2.0],
                    direction: 0.0,
                }
            })
            .collect()
    }

    /// The free objects where they start: each centre's height given above the ground at it.
    pub fn objects(&self) -> Vec<PlacedObject> {
        self.spec
            .objects
            .iter()
            .map(|object| {
                let [x, y, z] = object.position;
                PlacedObject {
                    shape: object.shape,
                    half: match object.shape {
                        ObjectShape::Ball => object.size,
                        ObjectShape::Box => object.size / 2.0,
                    },
                    mass: object.mass,
                    centre: [x, self.height(x, z) + y, z],
                    velocity: object.velocity,
                }
            })
            .collect()
    }

    /// The ground's friction coefficient at (x, z): the first patch holding the point, else
    /// the ground's coefficient; `None` when the world sets no ground friction (the
    /// simulator's `friction` then applies, combined as for any two colliders).
    pub fn friction(&self, x: f64, z: f64) -> Option<f64> {
        let friction = self.spec.friction.as_ref()?;
        Some(
            friction
                .patches
                .iter()
                .find(|p| (p.x[0]..=p.x[1]).contains(&x) && (p.z[0]..=p.z[1]).contains(&z))
                .map_or(friction.coefficient, |p| p.coefficient),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::world_spec::{FrictionPatch, GroundFriction};

    fn world(text: &str) -> Terrain {
        let spec: WorldSpec = toml::from_str(text).unwrap();
        spec.check().unwrap();
        Terrain::new(&spec)
    }

    #[test]
    fn one_seed_makes_one_rough_ground_and_another_seed_another() {
        let a = world("rough = { amplitude = 0.1, wavelength = 1.0, seed = 3, size = 8 }");
        let b = world("rough = { amplitude = 0.1, wavelength = 1.0, seed = 3, size = 8 }");
        let c = world("rough = { amplitude = 0.1, wavelength = 1.0, seed = 4, size = 8 }");
        let (a, b, c) = (
            a.heightfield().unwrap(),
            b.heightfield().unwrap(),
            c.heightfield().unwrap(),
        );
        assert_eq!(a.samples, 33);
        assert_eq!(a.heights, b.heights);
        assert_ne!(a.heights, c.heights);
        assert!(a.heights.iter().all(|h| h.abs() <= 0.1));
        assert!(a.heights.iter().any(|h| h.abs() > 0.02));
        // Level at the square's edge, to meet the level ground round it.
        assert_eq!(a.heights[0], 0.0);
        assert_eq!(a.heights[33 * 33 - 1], 0.0);
    }

    #[test]
    fn the_heightfield_reads_back_its_samples_and_is_level_outside() {
        let t = world("rough = { amplitude = 0.2, wavelength = 2.0, seed = 1, size = 10 }");
        let field = t.heightfield().unwrap();
        let s = field.spacing();
        assert_eq!(s, 0.5);
        let (i, j) = (7, 12);
        let (x, z) = (-5.0 + j as f64 * s, -5.0 + i as f64 * s);
        assert_eq!(t.height(x, z), field.heights[i * field.samples + j]);
        assert_eq!(t.height(6.0, 0.0), 0.0);
        assert_eq!(t.base(), None);
        assert_eq!(t.ground_boxes().len(), 4);
    }

    #[test]
    fn scattered_obstacles_keep_clear_of_the_start_and_stay_in_reach() {
        let t = world(
            "obstacles = { size = [0.4, 0.3, 0.2], count = 200, seed = 9, reach = 4, clear = 1.5 }",
        );
        let boxes = t.obstacle_boxes();
        assert_eq!(boxes.len(), 200);
        let half_diagonal = 0.5 * 0.4f64.hypot(0.2);
        for b in &boxes {
            let [x, _, z] = b.centre;
            assert!(x.hypot(z) >= 1.5 + half_diagonal, "{x}, {z}");
            assert!(x.abs() <= 4.0 && z.abs() <= 4.0);
            assert_eq!(b.half, [0.2, 0.15, 0.1]);
            assert_eq!(b.centre[1], 0.15);
        }
        let again = world(
            "obstacles = { size = [0.4, 0.3, 0.2], count = 200, seed = 9, reach = 4, clear = 1.5 }",
        );
        assert_eq!(again.obstacle_boxes(), boxes);
    }

    #[test]
    fn a_raised_obstacle_is_a_bar_above_the_ground() {
        let t = world("obstacles = { size = [0.2, 0.1, 3], at = [[2, 0]], raised = 0.5 }");
        let bar = t.obstacle_boxes()[0];
        assert_eq!(bar.centre, [2.0, 0.55, 0.0]);
        assert_eq!(bar.half, [0.1, 0.05, 1.5]);
    }

    #[test]
    fn steps_up_rise_a_height_each_and_the_last_tread_runs_on() {
        let t = world("steps = { height = 0.1, depth = 0.5, count = 3 }");
        assert_eq!(t.height(0.99, 0.0), 0.0);
        assert_eq!(t.height(1.0, 4.0), 0.1);
        assert_eq!(t.height(1.6, 0.0), 0.2);
        assert!((t.height(2.2, 0.0) - 0.3).abs() < 1e-12);
        assert!((t.height(50.0, 0.0) - 0.3).abs() < 1e-12);
        assert_eq!(t.base(), Some(0.0));
        let boxes = t.ground_boxes();
        assert_eq!(boxes.len(), 3);
        let tops: Vec<f64> = boxes.iter().map(Cuboid::top).collect();
        assert!((tops[0] - 0.1).abs() < 1e-12 && (tops[1] - 0.2).abs() < 1e-12);
        assert!((tops[2] - 0.3).abs() < 1e-12);
        assert_eq!(boxes[0].centre[0], 1.25);
        assert_eq!(boxes[2].centre[0] + boxes[2].half[0], FAR);
        assert_eq!(t.extremes_under([0.5, 1.2], [-1.0, 1.0]), (0.1, 0.0));
    }

    #[test]
    fn steps_down_fall_a_height_each_from_a_platform_at_zero() {
        let t = world(
            "steps = { height = 0.2, depth = 1, count = 2, way = \"down\", start = 0.5, direction = 90 }",
        );
        assert_eq!(t.height(0.0, 0.0), 0.0);
        assert_eq!(t.height(0.0, 0.6), -0.2);
        assert_eq!(t.height(0.0, 3.0), -0.4);
        assert_eq!(t.height(7.0, 0.4), 0.0);
        assert_eq!(t.base(), Some(-0.4));
        let boxes = t.ground_boxes();
        assert_eq!(boxes.len(), 2);
        assert!((boxes[0].top() - 0.0).abs() < 1e-12);
        assert!((boxes[1].top() + 0.2).abs() < 1e-12);
        assert_eq!(boxes[1].direction, 90.0);
    }

    #[test]
    fn a_slope_rises_by_the_tangent_of_its_angle_towards_its_direction() {
        let t = world("slope = { degrees = 30, direction = 180 }");
        let tan = 30f64.to_radians().tan();
        assert!((t.height(-2.0, 5.0) - 2.0 * tan).abs() < 1e-12);
        assert!((t.height(1.0, 0.0) + tan).abs() < 1e-12);
        let n = t.slope_normal().unwrap();
        assert!((n[0] - 0.5).abs() < 1e-12 && (n[1] - 0.75f64.sqrt()).abs() < 1e-12);
        let (hi, lo) = t.extremes_under([-1.0, 1.0], [0.0, 1.0]);
        assert!((hi - tan).abs() < 1e-12 && (lo + tan).abs() < 1e-12);
    }

    #[test]
    fn the_first_patch_holding_a_point_sets_its_friction() {
        let mut spec = WorldSpec::default();
        assert_eq!(Terrain::new(&spec).friction(0.0, 0.0), None);
        spec.friction = Some(GroundFriction {
            coefficient: 0.8,
            patches: vec![
                FrictionPatch {
                    x: [1.0, 2.0],
                    z: [-1.0, 1.0],
                    coefficient: 0.1,
                },
                FrictionPatch {
                    x: [1.5, 3.0],
                    z: [-1.0, 1.0],
                    coefficient: 0.3,
                },
            ],
        });
        let t = Terrain::new(&spec);
        assert_eq!(t.friction(0.0, 0.0), Some(0.8));
        assert_eq!(t.friction(1.7, 0.0), Some(0.1));
        assert_eq!(t.friction(2.5, 0.5), Some(0.3));
        assert_eq!(t.friction(2.5, 1.5), Some(0.8));
    }

    #[test]
    fn objects_start_their_height_above_the_ground_beneath_them() {
        let t = world(
            "slope = { degrees = 45 }\n\
             objects = [{ size = 0.5, mass = 3, position = [2, 1, 0], velocity = [0, 0, 1] }]",
        );
        let o = t.objects()[0];
        assert_eq!(o.half, 0.5);
        assert!((o.centre[1] - 3.0).abs() < 1e-12);
        assert_eq!(o.velocity, [0.0, 0.0, 1.0]);
    }
}
