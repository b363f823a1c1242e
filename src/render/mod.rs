//! Pictures of creatures, headless and in pure Rust: a shaded 3/4 view of the body on a
//! ground grid with joints and growing parts marked, a drawing of the neural network beside
//! it, and animations of growth. Drawing is done with tiny-skia; GIFs are encoded with `gif`.

use nalgebra::{Matrix3, Vector3};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::creature::{Creature, NeuronFunction, Role};

/// Why a picture could not be made or written.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The requested picture size is zero or too large.
    #[error("cannot make a {0}x{1} picture")]
    Size(u32, u32),
    /// PNG encoding or writing failed.
    #[error("cannot write the PNG: {0}")]
    Png(String),
    /// GIF encoding or writing failed.
    #[error("cannot write the GIF: {0}")]
    Gif(String),
    /// A file could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

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
    /// One view that holds every frame (growth: the creature grows in place).
    Still,
    /// The camera follows the first `parts` parts of each frame (the creature, not a thrown
    /// projectile drawn after them) and keeps the creature's own size in the picture, so a
    /// creature that travels far stays large; the ground's grid shows the motion.
    Following {
        /// How many leading parts of each frame are the creature.
        parts: usize,
    },
}

impl View {
    /// One view per frame for `framing`.
    fn per_frame<'a>(
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
                // The creature's largest own extent, on each axis, over the frames.
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
struct Camera {
    rotation: Matrix3<f64>,
    scale: f64,
    offset: (f64, f64),
}

impl Camera {
    fn new(view: &View, width: f64, height: f64, margin: f64) -> Camera {
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
    fn project(&self, p: &Vector3<f64>) -> (f32, f32, f64) {
        let q = self.rotation * p;
        (
            (self.offset.0 + self.scale * q.x) as f32,
            (self.offset.1 - self.scale * q.y) as f32,
            q.z,
        )
    }

    /// The direction towards the viewer, in world coordinates.
    fn towards_viewer(&self) -> Vector3<f64> {
        self.rotation.transpose() * Vector3::z()
    }
}

fn paint(r: u8, g: u8, b: u8, a: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(r, g, b, a));
    p.anti_alias = true;
    p
}

/// Draws the body into the region `(x, y, w, h)` of `pixmap`.
fn draw_body(pixmap: &mut Pixmap, creature: &Creature, view: &View, region: (f32, f32, f32, f32)) {
    let (rx, ry, rw, rh) = region;
    let camera = Camera::new(view, rw as f64, rh as f64, 12.0);
    let shift = Transform::from_translate(rx, ry);

    // Ground grid on the plane y = ground, one line per metre (or finer for small creatures).
    let ground = view.min.y.min(0.0);
    let extent = (view.max - view.min).norm().max(1.0);
    let step = if extent > 8.0 {
        1.0
    } else if extent > 2.0 {
        0.5
    } else {
        0.25
    };
    let pad = 0.25 * extent;
    let (x0, x1) = (
        ((view.min.x - pad) / step).floor() * step,
        ((view.max.x + pad) / step).ceil() * step,
    );
    let (z0, z1) = (
        ((view.min.z - pad) / step).floor() * step,
        ((view.max.z + pad) / step).ceil() * step,
    );
    let floor: Vec<(f32, f32)> = [(x0, z0), (x1, z0), (x1, z1), (x0, z1)]
        .iter()
        .map(|c| {
            let (sx, sy, _) = camera.project(&Vector3::new(c.0, ground, c.1));
            (sx, sy)
        })
        .collect();
    if let Some(path) = polygon(&floor) {
        pixmap.fill_path(
            &path,
            &paint(232, 234, 228, 255),
            FillRule::Winding,
            shift,
            None,
        );
    }
    let mut grid = PathBuilder::new();
    let mut segment = |from: (f64, f64), to: (f64, f64)| {
        let (ax, ay, _) = camera.project(&Vector3::new(from.0, ground, from.1));
        let (bx, by, _) = camera.project(&Vector3::new(to.0, ground, to.1));
        grid.move_to(ax, ay);
        grid.line_to(bx, by);
    };
    let mut x = x0;
    while x <= x1 + 1e-9 {
        segment((x, z0), (x, z1));
        x += step;
    }
    let mut z = z0;
    while z <= z1 + 1e-9 {
        segment((x0, z), (x1, z));
        z += step;
    }
    if let Some(path) = grid.finish() {
        let stroke = Stroke {
            width: 1.0,
            ..Stroke::default()
        };
        pixmap.stroke_path(&path, &paint(190, 194, 186, 255), &stroke, shift, None);
    }

    // Shadows: each part's footprint dropped onto the ground.
    for part in &creature.parts {
        let corners = part.corners();
        let mut pts: Vec<(f32, f32)> = corners
            .iter()
            .map(|c| {
                let (sx, sy, _) = camera.project(&Vector3::new(c.x, ground, c.z));
                (sx, sy)
            })
            .collect();
        if let Some(path) = convex_hull_path(&mut pts) {
            pixmap.fill_path(&path, &paint(0, 0, 0, 40), FillRule::Winding, shift, None);
        }
    }

    // Faces of every part, far to near (painter's algorithm), lit from above and to the side.
    const FACES: [[usize; 4]; 6] = [
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 6, 7, 5],
    ];
    let light = Vector3::new(0.4, 0.85, 0.35).normalize();
    let viewer = camera.towards_viewer();
    let mut faces = Vec::new();
    for (index, part) in creature.parts.iter().enumerate() {
        let corners = part.corners();
        let centre = part.position;
        for face in FACES {
            let mid = face.iter().map(|&k| corners[k]).sum::<Vector3<f64>>() / 4.0;
            let normal = (mid - centre).normalize();
            if normal.dot(&viewer) <= 1e-9 {
                continue;
            }
            let depth = camera.project(&mid).2;
            faces.push((depth, index, face, normal));
        }
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0));
    let outline = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    for (_, index, face, normal) in faces {
        let part = &creature.parts[index];
        let corners = part.corners();
        let shade = 0.45 + 0.55 * normal.dot(&light).max(0.0);
        let base = if part.growing {
            (240.0, 150.0, 40.0)
        } else if index == 0 {
            (70.0, 110.0, 190.0)
        } else {
            (100.0, 150.0, 220.0)
        };
        let fill = paint(
            (base.0 * shade) as u8,
            (base.1 * shade) as u8,
            (base.2 * shade) as u8,
            255,
        );
        let points: Vec<(f32, f32)> = face
            .iter()
            .map(|&k| {
                let (sx, sy, _) = camera.project(&corners[k]);
                (sx, sy)
            })
            .collect();
        if let Some(path) = polygon(&points) {
            pixmap.fill_path(&path, &fill, FillRule::Winding, shift, None);
            pixmap.stroke_path(&path, &paint(30, 40, 60, 200), &outline, shift, None);
        }
    }

    // Joints on top: red discs for movable joints (orange while growing), grey dots for fused.
    for joint in &creature.joints {
        let (sx, sy, _) = camera.project(&joint.anchor);
        let (radius, colour) = match (joint.kind.dof(), joint.growing) {
            (0, _) => (2.5, paint(90, 90, 90, 220)),
            (_, true) => (5.0, paint(255, 120, 0, 255)),
            _ => (5.0, paint(215, 40, 40, 255)),
        };
        if let Some(path) = PathBuilder::from_circle(sx, sy, radius) {
            pixmap.fill_path(&path, &colour, FillRule::Winding, shift, None);
            pixmap.stroke_path(&path, &paint(255, 255, 255, 255), &outline, shift, None);
        }
    }
}

/// The convex hull of `pts` as a closed path (gift wrapping; at most 8 points here).
fn convex_hull_path(pts: &mut [(f32, f32)]) -> Option<tiny_skia::Path> {
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let cross = |o: (f32, f32), a: (f32, f32), b: (f32, f32)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f32, f32)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f32, f32)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 3 {
        return None;
    }
    polygon(&hull)
}

/// A closed polygon through `points`.
fn polygon(points: &[(f32, f32)]) -> Option<tiny_skia::Path> {
    let (first, rest) = points.split_first()?;
    let mut pb = PathBuilder::new();
    pb.move_to(first.0, first.1);
    for p in rest {
        pb.line_to(p.0, p.1);
    }
    pb.close();
    pb.finish()
}

/// Draws the brain into `(x, y, w, h)`: neurons on a circle — sensors green, actuators red,
/// oscillators purple, other neurons blue — and links as lines, dark for positive weights and
/// red for negative, thicker for larger weights, with a dot at the receiving end.
fn draw_brain(pixmap: &mut Pixmap, creature: &Creature, region: (f32, f32, f32, f32)) {
    let (rx, ry, rw, rh) = region;
    if let Some(rect) = tiny_skia::Rect::from_xywh(rx, ry, rw, rh) {
        pixmap.fill_rect(
            rect,
            &paint(248, 248, 250, 255),
            Transform::identity(),
            None,
        );
    }
    let neurons = &creature.brain.neurons;
    if neurons.is_empty() {
        return;
    }
    let (cx, cy) = (rx + rw / 2.0, ry + rh / 2.0);
    let radius = 0.36 * rw.min(rh);
    let n = neurons.len();
    let place = |i: usize| {
        if n == 1 {
            return (cx, cy);
        }
        let a = std::f32::consts::TAU * i as f32 / n as f32 - std::f32::consts::FRAC_PI_2;
        (cx + radius * a.cos(), cy + radius * a.sin())
    };
    let dot = (0.3 * radius / (n as f32).sqrt()).clamp(3.0, 9.0);
    for link in &creature.brain.links {
        let (ax, ay) = place(link.from);
        let (bx, by) = place(link.to);
        let width = (1.0 + 1.5 * link.weight.abs().min(3.0)) as f32;
        let colour = if link.weight >= 0.0 {
            paint(40, 40, 60, 160)
        } else {
            paint(210, 50, 50, 170)
        };
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        let mut pb = PathBuilder::new();
        if link.from == link.to {
            pb.push_circle(ax, ay - dot * 1.6, dot * 1.2);
        } else {
            pb.move_to(ax, ay);
            pb.line_to(bx, by);
        }
        if let Some(path) = pb.finish() {
            pixmap.stroke_path(&path, &colour, &stroke, Transform::identity(), None);
        }
        if link.from != link.to {
            // A small dot near the receiving neuron shows the direction.
            let (dx, dy) = (bx - ax, by - ay);
            let len = (dx * dx + dy * dy).sqrt().max(1e-3);
            let (px, py) = (bx - dx / len * dot * 1.6, by - dy / len * dot * 1.6);
            if let Some(path) = PathBuilder::from_circle(px, py, width.max(2.0)) {
                pixmap.fill_path(
                    &path,
                    &colour,
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
    for (i, neuron) in neurons.iter().enumerate() {
        let (x, y) = place(i);
        let colour = match (neuron.role, neuron.function) {
            (Role::Sensor { .. }, _) => paint(40, 170, 70, 255),
            (Role::Actuator { .. }, _) => paint(210, 50, 50, 255),
            (_, NeuronFunction::Oscillator) => paint(140, 70, 190, 255),
            _ => paint(60, 110, 200, 255),
        };
        if let Some(path) = PathBuilder::from_circle(x, y, dot) {
            pixmap.fill_path(
                &path,
                &colour,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
            let stroke = Stroke {
                width: 1.0,
                ..Stroke::default()
            };
            pixmap.stroke_path(
                &path,
                &paint(20, 20, 20, 255),
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }
}

/// A picture of the creature: the body in a 3/4 view on the left, its brain on the right.
pub fn picture(
    creature: &Creature,
    view: &View,
    width: u32,
    height: u32,
) -> Result<Pixmap, RenderError> {
    if width < 64 || height < 64 || width > 8192 || height > 8192 {
        return Err(RenderError::Size(width, height));
    }
    let mut pixmap = Pixmap::new(width, height).ok_or(RenderError::Size(width, height))?;
    pixmap.fill(Color::from_rgba8(255, 255, 255, 255));
    let (w, h) = (width as f32, height as f32);
    let brain_w = (w * 0.3).round();
    draw_body(&mut pixmap, creature, view, (0.0, 0.0, w - brain_w, h));
    draw_brain(&mut pixmap, creature, (w - brain_w, 0.0, brain_w, h));
    Ok(pixmap)
}

/// Writes `creature.png`-style picture of one creature.
pub fn write_png(
    creature: &Creature,
    path: &std::path::Path,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    let pixmap = picture(creature, &View::framing(creature), width, height)?;
    pixmap
        .save_png(path)
        .map_err(|e| RenderError::Png(e.to_string()))
}

/// Writes an animated GIF of a sequence of creatures, framed as `framing` says, looping:
/// frame i lasts
/// `delays_cs[i]` hundredths of a second (the last delay for frames beyond the slice, 10 if
/// it is empty).
pub fn write_gif<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
) -> Result<(), RenderError> {
    let views = View::per_frame(creatures.clone(), framing);
    let w = u16::try_from(width).map_err(|_| RenderError::Size(width, height))?;
    let h = u16::try_from(height).map_err(|_| RenderError::Size(width, height))?;
    let file = std::fs::File::create(path)?;
    let mut encoder = gif::Encoder::new(std::io::BufWriter::new(file), w, h, &[])
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    encoder
        .set_repeat(gif::Repeat::Infinite)
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    for (i, creature) in creatures.into_iter().enumerate() {
        let pixmap = picture(creature, &views[i], width, height)?;
        let mut rgba = pixmap.data().to_vec(); // opaque background: premultiplied = straight
        let mut frame = gif::Frame::from_rgba_speed(w, h, &mut rgba, 10);
        frame.delay = delays_cs.get(i).or(delays_cs.last()).copied().unwrap_or(10);
        encoder
            .write_frame(&frame)
            .map_err(|e| RenderError::Gif(e.to_string()))?;
    }
    Ok(())
}
