//! A world in the body's 3/4 view: a shaped ground (a slope, a flight of steps, rough ground)
//! as a lit mesh with the ground grid drawn on it, obstacles and box objects as shaded boxes,
//! balls as shaded discs, and water as a blue tint over the scene. A flat world is drawn by
//! [`super::body`]'s level grid, unchanged.

use nalgebra::{UnitQuaternion, Vector3};
use tiny_skia::{PathBuilder, Pixmap, Rect, Transform};

use super::camera::Camera;
use super::palette::paint;
use super::pen::{fill, polygon, stroke_width};
use crate::sim::terrain::Terrain;
use crate::sim::world_spec::ObjectShape;

/// The light that shades the ground, obstacles, objects and the parts.
pub(super) fn light() -> Vector3<f64> {
    Vector3::new(0.4, 0.85, 0.35).normalize()
}

/// The level floor's colour, which a level cell of a shaped ground keeps.
const FLOOR: [f64; 3] = [232.0, 234.0, 228.0];
/// The ground grid's colour.
const GRID: [u8; 3] = [190, 194, 186];
/// Obstacles' colour.
const OBSTACLE: [f64; 3] = [150.0, 135.0, 115.0];
/// Free objects' colour.
const OBJECT: [f64; 3] = [225.0, 170.0, 50.0];
/// The most cells along a side of the drawn ground mesh.
const MAX_CELLS: usize = 64;

/// Whether `terrain` shapes the ground (a slope, steps or rough ground), so that the ground
/// is drawn as a mesh rather than the level grid.
pub(super) fn shapes_ground(terrain: &Terrain) -> bool {
    let spec = terrain.spec();
    spec.slope.is_some() || spec.steps.is_some() || spec.rough.is_some()
}

/// Whether `terrain`'s medium is water: no ground is drawn and the scene is tinted.
pub(super) fn is_water(terrain: &Terrain) -> bool {
    !terrain.spec().medium.is_air()
}

/// `colour` lit by a face of unit `normal`: a level face keeps the colour, faces turned away
/// from the light are darker.
fn lit(colour: [f64; 3], normal: &Vector3<f64>) -> [u8; 3] {
    let level = Vector3::y().dot(&light());
    let shade = (0.35 + 0.65 * normal.dot(&light()).max(0.0) / level).min(1.05);
    colour.map(|c| (c * shade).round().clamp(0.0, 255.0) as u8)
}

/// One polygon of the scene, in world coordinates, with its colour and the grid lines on it.
struct Face {
    points: Vec<Vector3<f64>>,
    colour: [u8; 3],
    lines: Vec<[Vector3<f64>; 2]>,
    outline: bool,
}

/// Fills `faces` far to near (painter's algorithm), each with its grid lines over it.
fn draw_faces(pixmap: &mut Pixmap, camera: &Camera, shift: Transform, mut faces: Vec<Face>) {
    let depth = |f: &Face| {
        let mid = f.points.iter().sum::<Vector3<f64>>() / f.points.len() as f64;
        camera.project(&mid).2
    };
    let mut keyed: Vec<(f64, Face)> = faces.drain(..).map(|f| (depth(&f), f)).collect();
    keyed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let thin = stroke_width(1.0);
    let [gr, gg, gb] = GRID;
    for (_, face) in keyed {
        let points: Vec<(f32, f32)> = face
            .points
            .iter()
            .map(|p| {
                let (x, y, _) = camera.project(p);
                (x, y)
            })
            .collect();
        let [r, g, b] = face.colour;
        if let Some(path) = polygon(&points) {
            fill(pixmap, &path, &paint(r, g, b, 255), shift);
            if face.outline {
                pixmap.stroke_path(&path, &paint(60, 50, 40, 200), &thin, shift, None);
            }
        }
        let mut grid = PathBuilder::new();
        for [a, b] in &face.lines {
            let (ax, ay, _) = camera.project(a);
            let (bx, by, _) = camera.project(b);
            grid.move_to(ax, ay);
            grid.line_to(bx, by);
        }
        if let Some(path) = grid.finish() {
            pixmap.stroke_path(&path, &paint(gr, gg, gb, 255), &thin, shift, None);
        }
    }
}

/// The breaks of `[lo, hi]` every `step` (from a multiple of it), each cut into pieces no
/// longer than `cell`, with the extra breaks `also` inside it.
fn breaks(lo: f64, hi: f64, step: f64, cell: f64, also: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let pieces = (step / cell).ceil().max(1.0);
    let mut k = (lo / step).floor();
    while k * step <= hi + 1e-9 {
        for i in 0..pieces as usize {
            let at = k * step + i as f64 * step / pieces;
            if at >= lo - 1e-9 && at <= hi + 1e-9 {
                out.push(at);
            }
        }
        k += 1.0;
    }
    out.extend(also.iter().copied().filter(|&a| a > lo && a < hi));
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    out
}

/// Whether `at` is on the grid of spacing `step`.
fn on_grid(at: f64, step: f64) -> bool {
    let k = at / step;
    (k - k.round()).abs() < 1e-6
}

/// Draws `terrain`'s shaped ground over the window `x`, `z` (the level grid's window), with
/// grid lines every `step` metres: a lit mesh of the ground's heights; a flight of steps
/// flat treads between the step edges, with their risers, on a grid turned with the steps.
pub(super) fn draw_ground_shape(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    (x, z): ([f64; 2], [f64; 2]),
    step: f64,
    terrain: &Terrain,
) {
    let spec = terrain.spec();
    // The mesh's frame: u along the steps' direction (or +x), v across it.
    let direction = spec
        .steps
        .as_ref()
        .map_or(0.0, |s| s.direction)
        .to_radians();
    let (ux, uz) = (direction.cos(), direction.sin());
    let to_world = |u: f64, v: f64| (u * ux - v * uz, u * uz + v * ux);
    let corners = [(x[0], z[0]), (x[1], z[0]), (x[1], z[1]), (x[0], z[1])];
    let us: Vec<f64> = corners.iter().map(|(a, b)| a * ux + b * uz).collect();
    let vs: Vec<f64> = corners.iter().map(|(a, b)| -a * uz + b * ux).collect();
    let span = |p: &[f64]| {
        (
            p.iter().copied().fold(f64::INFINITY, f64::min),
            p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let ((u0, u1), (v0, v1)) = (span(&us), span(&vs));
    let side = (u1 - u0).max(v1 - v0);
    let cell = match terrain.heightfield() {
        Some(field) => field.spacing().max(side / MAX_CELLS as f64),
        None => step,
    };
    let edges: Vec<f64> = spec
        .steps
        .as_ref()
        .map(|s| (0..s.count).map(|k| s.start + k as f64 * s.depth).collect())
        .unwrap_or_default();
    let ub = breaks(u0, u1, step, cell, &edges);
    let vb = breaks(v0, v1, step, cell, &[]);
    let flat_cells = spec.steps.is_some();
    let point = |u: f64, v: f64, h: Option<f64>| {
        let (wx, wz) = to_world(u, v);
        Vector3::new(wx, h.unwrap_or_else(|| terrain.height(wx, wz)), wz)
    };
    let mut faces = Vec::new();
    for (i, pair_u) in ub.windows(2).enumerate() {
        let (ua, ubb) = (pair_u[0], pair_u[1]);
        for pair_v in vb.windows(2) {
            let (va, vbb) = (pair_v[0], pair_v[1]);
            // A tread is level: its height is the one at its middle.
            let level = flat_cells.then(|| {
                let (wx, wz) = to_world(0.5 * (ua + ubb), 0.5 * (va + vbb));
                terrain.height(wx, wz)
            });
            let p = [
                point(ua, va, level),
                point(ubb, va, level),
                point(ubb, vbb, level),
                point(ua, vbb, level),
            ];
            let mut normal = (p[2] - p[0]).cross(&(p[1] - p[3]));
            if normal.y < 0.0 {
                normal = -normal;
            }
            let normal = normal.try_normalize(1e-12).unwrap_or(Vector3::y());
            let mut lines = Vec::new();
            if on_grid(ua, step) {
                lines.push([p[0], p[3]]);
            }
            if on_grid(va, step) {
                lines.push([p[0], p[1]]);
            }
            if i + 2 == ub.len() && on_grid(ubb, step) {
                lines.push([p[1], p[2]]);
            }
            faces.push(Face {
                points: p.to_vec(),
                colour: lit(FLOOR, &normal),
                lines,
                outline: false,
            });
            // A riser where the next tread is at another height.
            if let (Some(here), Some(&next_u)) = (level, ub.get(i + 2)) {
                let (wx, wz) = to_world(0.5 * (ubb + next_u), 0.5 * (va + vbb));
                let there = terrain.height(wx, wz);
                if (there - here).abs() > 1e-9 {
                    let facing = if there > here { -1.0 } else { 1.0 };
                    let normal = Vector3::new(facing * ux, 0.0, facing * uz);
                    faces.push(Face {
                        points: vec![
                            point(ubb, va, Some(here)),
                            point(ubb, vbb, Some(here)),
                            point(ubb, vbb, Some(there)),
                            point(ubb, va, Some(there)),
                        ],
                        colour: lit(FLOOR, &normal),
                        lines: Vec::new(),
                        outline: false,
                    });
                }
            }
        }
    }
    draw_faces(pixmap, camera, shift, faces);
}

/// The eight corners of a box of half sizes `half` at `centre` turned by `rotation`, corner
/// `i` on the + side of axis x when bit 0 of `i` is set, y bit 1, z bit 2.
fn box_corners(
    centre: Vector3<f64>,
    half: [f64; 3],
    rotation: UnitQuaternion<f64>,
) -> [Vector3<f64>; 8] {
    std::array::from_fn(|i| {
        let sign = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
        centre + rotation * Vector3::new(sign(1) * half[0], sign(2) * half[1], sign(4) * half[2])
    })
}

/// A box's six faces, each by the indices of its four corners in the order [`box_corners`]
/// (and a part's corners, [`Part::corners`](crate::creature::Part::corners)) numbers them.
pub(super) const BOX_FACES: [[usize; 4]; 6] = [
    [0, 2, 6, 4],
    [1, 5, 7, 3],
    [0, 4, 5, 1],
    [2, 3, 7, 6],
    [0, 1, 3, 2],
    [4, 6, 7, 5],
];

/// The faces of a box that the viewer sees, lit, in `colour`.
fn box_faces(
    camera: &Camera,
    centre: Vector3<f64>,
    half: [f64; 3],
    rotation: UnitQuaternion<f64>,
    colour: [f64; 3],
) -> Vec<Face> {
    let corners = box_corners(centre, half, rotation);
    let viewer = camera.towards_viewer();
    BOX_FACES
        .iter()
        .filter_map(|face| {
            let mid = face.iter().map(|&k| corners[k]).sum::<Vector3<f64>>() / 4.0;
            let normal = (mid - centre).try_normalize(1e-12)?;
            (normal.dot(&viewer) > 1e-9).then(|| Face {
                points: face.iter().map(|&k| corners[k]).collect(),
                colour: lit(colour, &normal),
                lines: Vec::new(),
                outline: true,
            })
        })
        .collect()
}

/// Which of the world's solids a call draws: those whose centre lies farther from the
/// viewer than a depth (drawn before the creature, which then hides them), or the others
/// (drawn after it, over it).
#[derive(Clone, Copy)]
pub(super) enum Solids {
    /// Centres farther than this depth ([`Camera::project`]'s third value).
    Behind(f64),
    /// Centres at this depth or nearer.
    InFront(f64),
}

impl Solids {
    fn takes(self, centre: &Vector3<f64>, camera: &Camera) -> bool {
        let depth = camera.project(centre).2;
        match self {
            Solids::Behind(d) => depth < d,
            Solids::InFront(d) => depth >= d,
        }
    }
}

/// Draws those of `terrain`'s obstacles and free objects that `which` takes: the objects at
/// `objects`' poses (in the order of the world's objects), or where they start when there
/// are none. Boxes are drawn far to near; balls are shaded discs drawn after them.
pub(super) fn draw_solids(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    (terrain, which): (&Terrain, Solids),
    objects: &[(Vector3<f64>, UnitQuaternion<f64>)],
) {
    let mut faces = Vec::new();
    for obstacle in terrain
        .obstacle_boxes()
        .into_iter()
        .filter(|o| which.takes(&Vector3::from(o.centre), camera))
    {
        let turn =
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -obstacle.direction.to_radians());
        faces.extend(box_faces(
            camera,
            Vector3::from(obstacle.centre),
            obstacle.half,
            turn,
            OBSTACLE,
        ));
    }
    let placed = terrain.objects();
    let mut balls = Vec::new();
    for (k, object) in placed.iter().enumerate() {
        let (centre, rotation) = objects
            .get(k)
            .copied()
            .unwrap_or((Vector3::from(object.centre), UnitQuaternion::identity()));
        if !which.takes(&centre, camera) {
            continue;
        }
        match object.shape {
            ObjectShape::Box => faces.extend(box_faces(
                camera,
                centre,
                [object.half; 3],
                rotation,
                OBJECT,
            )),
            ObjectShape::Ball => balls.push((centre, object.half)),
        }
    }
    draw_faces(pixmap, camera, shift, faces);
    balls.sort_by(|a, b| camera.project(&a.0).2.total_cmp(&camera.project(&b.0).2));
    for (centre, radius) in balls {
        let (x, y, _) = camera.project(&centre);
        let r = (radius * camera.scale) as f32;
        let [r0, g0, b0] = lit(OBJECT, &Vector3::y());
        if let Some(disc) = PathBuilder::from_circle(x, y, r.max(1.0)) {
            fill(pixmap, &disc, &paint(r0, g0, b0, 255), shift);
            pixmap.stroke_path(
                &disc,
                &paint(60, 50, 40, 200),
                &stroke_width(1.0),
                shift,
                None,
            );
        }
        // A highlight towards the light.
        if let Some(spot) = PathBuilder::from_circle(x - 0.3 * r, y - 0.3 * r, (0.3 * r).max(0.5)) {
            fill(pixmap, &spot, &paint(255, 245, 210, 200), shift);
        }
    }
}

/// Tints the region `(x, y, w, h)` blue: the scene is under water.
pub(super) fn tint_water(pixmap: &mut Pixmap, (x, y, w, h): (f32, f32, f32, f32)) {
    if let Some(rect) = Rect::from_xywh(x, y, w, h) {
        pixmap.fill_rect(rect, &paint(40, 120, 220, 60), Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::creature::Creature;
    use crate::develop::creature_from_commands;
    use crate::render::{Overlay, View, picture};
    use crate::sim::WorldSpec;
    use std::sync::Arc;

    fn walker() -> Creature {
        creature_from_commands("forward(1) revolute2 forward(1)").unwrap()
    }

    /// The picture of the walker in the world `toml` (none: no world at all), as RGBA.
    fn drawn(toml: Option<&str>) -> Vec<u8> {
        let c = walker();
        let overlay = Overlay {
            world: toml.map(|t| Arc::new(Terrain::new(&toml::from_str::<WorldSpec>(t).unwrap()))),
            ..Overlay::default()
        };
        picture(&c, &View::framing(&c), 480, 300, &overlay)
            .unwrap()
            .data()
            .to_vec()
    }

    fn count(data: &[u8], colour: [u8; 3]) -> usize {
        data.chunks_exact(4)
            .filter(|p| p[..3] == colour[..])
            .count()
    }

    #[test]
    fn a_flat_world_is_drawn_pixel_for_pixel_as_no_world() {
        assert!(drawn(None) == drawn(Some("")));
    }

    #[test]
    fn a_slope_tilts_the_floor_and_steps_show_their_risers() {
        let flat = drawn(None);
        let slope = drawn(Some("slope = { degrees = 20, direction = 0 }"));
        let tilted = Terrain::new(&toml::from_str("slope = { degrees = 20 }").unwrap())
            .slope_normal()
            .unwrap();
        let tilted_floor = lit(FLOOR, &Vector3::from(tilted));
        assert_eq!(count(&flat, tilted_floor), 0);
        assert!(count(&slope, tilted_floor) > 1000);
        // A riser faces back down the flight: along -z for a flight along +z, +z for one
        // along -z; one of the two faces the viewer.
        let risers: usize = [(90, -1.0), (270, 1.0)]
            .into_iter()
            .map(|(direction, facing)| {
                let steps = drawn(Some(&format!(
                    "steps = {{ height = 0.2, depth = 0.5, count = 4, start = 0.5, direction = {direction} }}"
                )));
                let riser = lit(FLOOR, &Vector3::new(0.0, 0.0, facing));
                assert_eq!(count(&flat, riser), 0);
                count(&steps, riser)
            })
            .sum();
        assert!(risers > 50, "{risers} pixels of risers");
    }

    #[test]
    fn rough_ground_is_shaded_by_its_slopes() {
        let flat = drawn(None);
        let rough = drawn(Some(
            "rough = { amplitude = 0.3, wavelength = 1, seed = 7, size = 8 }",
        ));
        // Level floor covers less of the picture: the bumps are lit lighter and darker.
        assert!(count(&rough, [232, 234, 228]) < count(&flat, [232, 234, 228]) / 2);
    }

    #[test]
    fn obstacles_are_boxes_objects_are_balls_and_water_tints_the_scene() {
        let flat = drawn(None);
        // Beside the walker, where the camera frames it.
        let (lo, hi) = walker().bounding_box();
        let cx = 0.5 * (lo.x + hi.x);
        let world = drawn(Some(&format!(
            "obstacles = {{ size = [0.4, 0.3, 0.4], at = [[{cx}, {}]] }}\n\
             objects = [{{ shape = \"ball\", size = 0.2, mass = 1, position = [{cx}, 0.2, {}] }}]",
            hi.z + 0.4,
            lo.z - 0.4
        )));
        // The boxes' and the ball's tops face up: their colour unshaded.
        assert_eq!(count(&flat, [150, 135, 115]), 0);
        assert!(count(&world, [150, 135, 115]) > 20);
        assert!(count(&world, [225, 170, 50]) > 20);
        let water = drawn(Some("medium = { kind = \"water\", viscosity = 5 }"));
        // The top left corner: white in air, blue under water, with no floor drawn.
        assert_eq!(flat[..3], [255, 255, 255]);
        assert!(water[2] > water[0] + 30);
        assert_eq!(count(&water, [232, 234, 228]), 0);
    }
}
