//! Pictures of creatures, headless and in pure Rust: a shaded 3/4 view of the body on a
//! ground grid with joints and growing parts marked, a drawing of the neural network beside
//! it, and animations of growth and behaviour. Drawing is done with tiny-skia, text with the
//! public-domain 8×8 bitmap font of `font8x8`; GIFs are encoded with `gif`, on a palette that
//! keeps the colours that carry meaning exact.

use std::collections::HashMap;

use nalgebra::{Matrix3, Vector3};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

use crate::creature::{Creature, NeuronFunction, Role, Severity};

/// Sensor neurons.
const SENSOR: [u8; 3] = [40, 170, 70];
/// Actuator neurons.
const ACTUATOR: [u8; 3] = [210, 50, 50];
/// Oscillator neurons.
const OSCILLATOR: [u8; 3] = [140, 70, 190];
/// Other neurons.
const NEURON: [u8; 3] = [60, 110, 200];
/// Movable joints' discs.
const JOINT: [u8; 3] = [215, 40, 40];
/// Growing joints' discs.
const GROWING_JOINT: [u8; 3] = [255, 120, 0];
/// Hinge axes.
const AXIS: [u8; 3] = [25, 25, 25];
/// The aim task's target.
const TARGET: [u8; 3] = [225, 0, 200];
/// A projectile's trail.
const TRAIL: [u8; 3] = [190, 90, 0];
/// What makes a creature invalid: interpenetrating parts, problem text.
const MARK: [u8; 3] = [255, 0, 0];
/// Text.
const INK: [u8; 3] = [20, 20, 20];
/// The brain panel's background.
const PANEL: [u8; 3] = [248, 248, 250];

/// The colours a GIF's palette holds exactly, whatever else the frame needs.
const KEY_COLOURS: [[u8; 3]; 13] = [
    SENSOR,
    ACTUATOR,
    OSCILLATOR,
    NEURON,
    JOINT,
    GROWING_JOINT,
    AXIS,
    TARGET,
    TRAIL,
    MARK,
    INK,
    PANEL,
    [255, 255, 255],
];

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
    /// The output file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
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

fn solid(c: [u8; 3]) -> Paint<'static> {
    paint(c[0], c[1], c[2], 255)
}

/// What is drawn over a picture besides the creature.
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// Lines of text at the top left (a behaviour frame's time and phase, say).
    pub label: Vec<String>,
    /// A target, in world coordinates (the aim task's): a bullseye with a line down to the
    /// ground.
    pub target: Option<Vector3<f64>>,
    /// A projectile's past positions, oldest first, drawn as its trail. With a target or a
    /// trail, a top view in the corner shows them even when they are out of the camera's
    /// view.
    pub trail: Vec<Vector3<f64>>,
}

/// Whether a picture checks the creature: marks interpenetrating parts, numbers the parts and
/// writes its validity and problems.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Checks {
    On,
    Off,
}

/// Text that fits the 8×8 font: ASCII, with the symbols messages use spelt out.
fn ascii(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '−' | '–' | '—' => '-',
            '·' | '×' => '*',
            '²' => '2',
            '³' => '3',
            '°' => 'o',
            c if c.is_ascii() && !c.is_ascii_control() => c,
            _ => '?',
        })
        .collect()
}

/// The width in pixels of `text` drawn at `scale`.
fn text_width(text: &str, scale: f32) -> f32 {
    text.chars().count() as f32 * 8.0 * scale
}

/// `text`, cut with "..." to fit `width` pixels at `scale`.
fn fit(text: &str, width: f32, scale: f32) -> String {
    let text = ascii(text);
    let room = (width / (8.0 * scale)).floor().max(0.0) as usize;
    if text.len() <= room {
        text
    } else if room > 3 {
        format!("{}...", &text[..room - 3])
    } else {
        String::new()
    }
}

/// Draws `text` with its top left at `(x, y)`, each font pixel `scale` pixels square, on a
/// pale backing when `backing` is set.
fn draw_text(
    pixmap: &mut Pixmap,
    (x, y): (f32, f32),
    text: &str,
    scale: f32,
    colour: [u8; 3],
    backing: bool,
) {
    let text = ascii(text);
    if text.is_empty() {
        return;
    }
    let (x, y) = (x.round(), y.round());
    if backing
        && let Some(rect) = Rect::from_xywh(
            x - 2.0,
            y - 2.0,
            text_width(&text, scale) + 4.0,
            8.0 * scale + 4.0,
        )
    {
        pixmap.fill_rect(
            rect,
            &paint(255, 255, 255, 215),
            Transform::identity(),
            None,
        );
    }
    let mut pb = PathBuilder::new();
    for (i, c) in text.bytes().enumerate() {
        let glyph = font8x8::legacy::BASIC_LEGACY[c as usize & 0x7f];
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits >> col & 1 == 1
                    && let Some(r) = Rect::from_xywh(
                        x + (i * 8 + col) as f32 * scale,
                        y + row as f32 * scale,
                        scale,
                        scale,
                    )
                {
                    pb.push_rect(r);
                }
            }
        }
    }
    if let Some(path) = pb.finish() {
        let mut p = solid(colour);
        p.anti_alias = false;
        pixmap.fill_path(&path, &p, FillRule::Winding, Transform::identity(), None);
    }
}

/// The round length (1, 2 or 5 × a power of ten, in metres) whose bar is at most `room`
/// pixels long at `scale` pixels per metre.
fn scale_bar_length(scale: f64, room: f64) -> f64 {
    let mut best = 1e-3;
    for exponent in -3..=4 {
        for m in [1.0, 2.0, 5.0] {
            let length = m * 10f64.powi(exponent);
            if length * scale <= room {
                best = length;
            }
        }
    }
    best
}

/// A length for a scale bar's label: "1 m", "50 cm", "5 mm".
fn length_label(metres: f64) -> String {
    if metres >= 1.0 {
        format!("{} m", crate::lsystem::format_number(metres))
    } else if metres >= 0.01 {
        format!("{} cm", (metres * 100.0).round())
    } else {
        format!("{} mm", (metres * 1000.0).round())
    }
}

/// The radius of a joint's disc in metres: half the smaller joined part's middle dimension
/// (its width, for a bar), so that a disc is as wide as the parts it joins.
fn joint_radius(creature: &Creature, parent: usize, child: usize) -> f64 {
    let middle = |i: usize| {
        creature.parts.get(i).map(|p| {
            let mut d = [p.size.x, p.size.y, p.size.z];
            d.sort_by(f64::total_cmp);
            d[1]
        })
    };
    let sizes: Vec<f64> = [middle(parent), middle(child)]
        .into_iter()
        .flatten()
        .collect();
    sizes.into_iter().fold(f64::INFINITY, f64::min).min(1e6) / 2.0
}

/// Draws the body into the region `(x, y, w, h)` of `pixmap`, with `overlay` and, when
/// `checks` is on, the marks of what makes the creature invalid and part numbers.
fn draw_body(
    pixmap: &mut Pixmap,
    creature: &Creature,
    view: &View,
    region: (f32, f32, f32, f32),
    overlay: &Overlay,
    checks: Checks,
) {
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

    // The target's foot on the ground and the line up to it.
    if let Some(target) = overlay.target {
        let (fx, fy, _) = camera.project(&Vector3::new(target.x, ground, target.z));
        let (tx, ty, _) = camera.project(&target);
        let mut pb = PathBuilder::new();
        pb.push_oval(Rect::from_xywh(fx - 8.0, fy - 3.5, 16.0, 7.0).expect("finite"));
        pb.move_to(fx, fy);
        pb.line_to(tx, ty);
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: 1.5,
                ..Stroke::default()
            };
            pixmap.stroke_path(&path, &solid(TARGET), &stroke, shift, None);
        }
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

    // Interpenetrating parts: outlined in the marking colour.
    let pairs = if checks == Checks::On {
        creature.interpenetrating_pairs()
    } else {
        Vec::new()
    };
    let mut marked: Vec<usize> = pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
    marked.sort_unstable();
    marked.dedup();
    for &index in &marked {
        let mut pts: Vec<(f32, f32)> = creature.parts[index]
            .corners()
            .iter()
            .map(|c| {
                let (sx, sy, _) = camera.project(c);
                (sx, sy)
            })
            .collect();
        if let Some(path) = convex_hull_path(&mut pts) {
            let stroke = Stroke {
                width: 3.0,
                ..Stroke::default()
            };
            pixmap.stroke_path(&path, &solid(MARK), &stroke, shift, None);
        }
    }

    // Joints on top: a disc in the plane each movable joint turns in (red, orange while
    // growing), its size following the parts it joins, with a line along each axis ending
    // in a dot at the axis's positive end; fused joints are grey dots.
    let most = 0.05 * rw.min(rh);
    for joint in &creature.joints {
        let (sx, sy, _) = camera.project(&joint.anchor);
        let radius = joint_radius(creature, joint.parent, joint.child);
        let pixels = ((radius * camera.scale) as f32).clamp(4.0, most.max(4.0));
        let radius = pixels as f64 / camera.scale;
        if joint.kind.dof() == 0 || joint.axes.is_empty() {
            let dot = (0.4 * pixels).clamp(2.0, 6.0);
            if let Some(path) = PathBuilder::from_circle(sx, sy, dot) {
                pixmap.fill_path(
                    &path,
                    &paint(90, 90, 90, 220),
                    FillRule::Winding,
                    shift,
                    None,
                );
                pixmap.stroke_path(&path, &solid([255; 3]), &outline, shift, None);
            }
            continue;
        }
        let colour = if joint.growing { GROWING_JOINT } else { JOINT };
        let axis = joint.axes[0].try_normalize(1e-12).unwrap_or(Vector3::x());
        let helper = if axis.y.abs() < 0.9 {
            Vector3::y()
        } else {
            Vector3::x()
        };
        let u = axis.cross(&helper).normalize();
        let v = axis.cross(&u);
        let rim: Vec<(f32, f32)> = (0..24)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 24.0;
                let p = joint.anchor + (u * a.cos() + v * a.sin()) * radius;
                let (px, py, _) = camera.project(&p);
                (px, py)
            })
            .collect();
        if let Some(path) = polygon(&rim) {
            pixmap.fill_path(&path, &solid(colour), FillRule::Winding, shift, None);
            pixmap.stroke_path(&path, &solid([255; 3]), &outline, shift, None);
        }
        if let Some(path) = PathBuilder::from_circle(sx, sy, 2.5) {
            pixmap.fill_path(&path, &solid(colour), FillRule::Winding, shift, None);
        }
        let stroke = Stroke {
            width: 2.0,
            ..Stroke::default()
        };
        for axis in &joint.axes {
            let Some(axis) = axis.try_normalize(1e-12) else {
                continue;
            };
            let (ax, ay, _) = camera.project(&(joint.anchor - axis * 1.6 * radius));
            let (bx, by, _) = camera.project(&(joint.anchor + axis * 1.6 * radius));
            let mut pb = PathBuilder::new();
            pb.move_to(ax, ay);
            pb.line_to(bx, by);
            pb.push_circle(bx, by, 2.5);
            if let Some(path) = pb.finish() {
                pixmap.stroke_path(&path, &solid(AXIS), &stroke, shift, None);
            }
        }
    }

    // The projectile's trail and the target's bullseye.
    if overlay.trail.len() >= 2 {
        let mut pb = PathBuilder::new();
        for (k, p) in overlay.trail.iter().enumerate() {
            let (px, py, _) = camera.project(p);
            if k == 0 {
                pb.move_to(px, py);
            } else {
                pb.line_to(px, py);
            }
        }
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: 2.0,
                ..Stroke::default()
            };
            pixmap.stroke_path(&path, &solid(TRAIL), &stroke, shift, None);
        }
    }
    if let Some(target) = overlay.target {
        let (tx, ty, _) = camera.project(&target);
        draw_bullseye(pixmap, (rx + tx, ry + ty), 7.0);
    }

    // Part numbers, red for marked parts: every marked part's, and the others' where the part
    // is large enough in the picture to hold its number and no other number is in the way.
    if checks == Checks::On {
        let mut taken: Vec<Rect> = Vec::new();
        let order = marked
            .iter()
            .copied()
            .chain((0..creature.parts.len()).filter(|i| !marked.contains(i)));
        for index in order {
            let part = &creature.parts[index];
            let (px, py, _) = camera.project(&part.position);
            let text = index.to_string();
            let half = text_width(&text, 1.0) / 2.0;
            let is_marked = marked.contains(&index);
            let (mut lo, mut hi) = (
                (f32::INFINITY, f32::INFINITY),
                (f32::NEG_INFINITY, f32::NEG_INFINITY),
            );
            for c in part.corners() {
                let (sx, sy, _) = camera.project(&c);
                lo = (lo.0.min(sx), lo.1.min(sy));
                hi = (hi.0.max(sx), hi.1.max(sy));
            }
            let roomy = hi.0 - lo.0 >= 2.0 * half + 8.0 && hi.1 - lo.1 >= 16.0;
            let Some(boxed) = Rect::from_xywh(px - half - 2.0, py - 6.0, 2.0 * half + 4.0, 12.0)
            else {
                continue;
            };
            let clear = !taken.iter().any(|t| t.intersect(&boxed).is_some());
            if !(is_marked || roomy && clear) {
                continue;
            }
            taken.push(boxed);
            let colour = if is_marked { MARK } else { INK };
            draw_text(
                pixmap,
                (rx + px - half, ry + py - 4.0),
                &text,
                1.0,
                colour,
                true,
            );
        }
    }

    let text_scale = if rh >= 500.0 { 2.0 } else { 1.0 };
    // The scale bar, bottom left.
    let length = scale_bar_length(camera.scale, 0.25 * rw as f64);
    let bar = (length * camera.scale) as f32;
    let (bx, by) = ((rx + 12.0).round() + 0.5, (ry + rh - 10.0).round() + 0.5);
    let mut pb = PathBuilder::new();
    pb.move_to(bx, by - 4.0);
    pb.line_to(bx, by);
    pb.line_to(bx + bar, by);
    pb.line_to(bx + bar, by - 4.0);
    if let Some(path) = pb.finish() {
        let stroke = Stroke {
            width: 2.0,
            ..Stroke::default()
        };
        let mut p = solid(INK);
        p.anti_alias = false;
        pixmap.stroke_path(&path, &p, &stroke, Transform::identity(), None);
    }
    draw_text(
        pixmap,
        (bx + bar + 6.0, by - 8.0 * text_scale),
        &length_label(length),
        text_scale,
        INK,
        true,
    );

    // The top view of projectile and target, in the top right corner.
    let mut room = rw - 16.0;
    if overlay.target.is_some() || !overlay.trail.is_empty() {
        let side = (0.34 * rw.min(rh)).round();
        draw_top_view(
            pixmap,
            creature,
            overlay,
            (rx + rw - side - 6.0, ry + 6.0, side, side),
        );
        room -= side + 6.0;
    }

    // Lines of text, top left; with checks, the creature's validity and problems after them.
    let line = 10.0 * text_scale + 2.0;
    let mut y = ry + 6.0;
    for text in &overlay.label {
        draw_text(
            pixmap,
            (rx + 8.0, y),
            &fit(text, room, text_scale),
            text_scale,
            INK,
            true,
        );
        y += line;
    }
    if checks == Checks::On {
        let mut problems: Vec<(String, [u8; 3])> = Vec::new();
        if creature.parts.is_empty() {
            problems.push(("error: no part".to_string(), MARK));
        }
        for p in &creature.problems {
            let (level, colour) = match p.severity {
                Severity::Error => ("error", MARK),
                Severity::Warning => ("warning", TRAIL),
            };
            problems.push((format!("{level}: {}", p.message), colour));
        }
        for (a, b) in &pairs {
            let message = format!("parts {a} and {b} interpenetrate");
            if !creature.problems.iter().any(|p| p.message == message) {
                problems.push((format!("error: {message}"), MARK));
            }
        }
        let valid = creature.is_valid() && pairs.is_empty();
        let summary = format!(
            "{} parts, {} joints, {} neurons: {}",
            creature.parts.len(),
            creature.joints.len(),
            creature.brain.neurons.len(),
            if valid { "valid" } else { "INVALID" }
        );
        draw_text(
            pixmap,
            (rx + 8.0, y),
            &fit(&summary, room, text_scale),
            text_scale,
            if valid { INK } else { MARK },
            true,
        );
        y += line;
        let shown = ((rh - y - 24.0) / line).floor().max(0.0) as usize;
        let total = problems.len();
        for (k, (text, colour)) in problems.into_iter().enumerate() {
            if k + 1 == shown && total > shown {
                let rest = format!("... and {} more", total - k);
                draw_text(pixmap, (rx + 8.0, y), &rest, text_scale, colour, true);
                break;
            }
            if k >= shown {
                break;
            }
            draw_text(
                pixmap,
                (rx + 8.0, y),
                &fit(&text, room, text_scale),
                text_scale,
                colour,
                true,
            );
            y += line;
        }
        if !valid && let Some(rect) = Rect::from_xywh(rx + 1.5, ry + 1.5, rw - 3.0, rh - 3.0) {
            let stroke = Stroke {
                width: 3.0,
                ..Stroke::default()
            };
            let mut p = solid(MARK);
            p.anti_alias = false;
            pixmap.stroke_path(
                &PathBuilder::from_rect(rect),
                &p,
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }
}

/// A target's bullseye centred on `(x, y)` (pixels), `radius` across its outer ring.
fn draw_bullseye(pixmap: &mut Pixmap, (x, y): (f32, f32), radius: f32) {
    for (r, colour) in [
        (radius, TARGET),
        (radius * 0.62, [255; 3]),
        (radius * 0.3, TARGET),
    ] {
        if let Some(path) = PathBuilder::from_circle(x, y, r) {
            pixmap.fill_path(
                &path,
                &solid(colour),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
}

/// A top view (x right, z down) of the creature's parts, the trail, the projectile and the
/// target in the square `(x, y, side, side)`, fitted to hold them all, with its scale.
fn draw_top_view(
    pixmap: &mut Pixmap,
    creature: &Creature,
    overlay: &Overlay,
    (x, y, side, _): (f32, f32, f32, f32),
) {
    let Some(rect) = Rect::from_xywh(x, y, side, side) else {
        return;
    };
    pixmap.fill_rect(
        rect,
        &paint(255, 255, 255, 225),
        Transform::identity(),
        None,
    );
    let thin = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    pixmap.stroke_path(
        &PathBuilder::from_rect(rect),
        &paint(120, 120, 120, 255),
        &thin,
        Transform::identity(),
        None,
    );
    let points: Vec<Vector3<f64>> = creature
        .parts
        .iter()
        .flat_map(|p| p.corners())
        .chain(overlay.trail.iter().copied())
        .chain(overlay.target)
        .collect();
    let Some(first) = points.first() else {
        return;
    };
    let (lo, hi) = points
        .iter()
        .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let inner = side as f64 - 16.0;
    let span = (hi.x - lo.x).max(hi.z - lo.z).max(0.5);
    let scale = inner / span;
    let (cx, cz) = ((lo.x + hi.x) / 2.0, (lo.z + hi.z) / 2.0);
    let place = |p: &Vector3<f64>| {
        (
            x + side / 2.0 + ((p.x - cx) * scale) as f32,
            y + side / 2.0 + ((p.z - cz) * scale) as f32,
        )
    };
    for part in &creature.parts {
        let mut pts: Vec<(f32, f32)> = part.corners().iter().map(place).collect();
        if let Some(path) = convex_hull_path(&mut pts) {
            let colour = if part.growing {
                paint(240, 150, 40, 255)
            } else {
                paint(100, 150, 220, 255)
            };
            pixmap.fill_path(
                &path,
                &colour,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
    if overlay.trail.len() >= 2 {
        let mut pb = PathBuilder::new();
        for (k, p) in overlay.trail.iter().enumerate() {
            let (px, py) = place(p);
            if k == 0 {
                pb.move_to(px, py);
            } else {
                pb.line_to(px, py);
            }
        }
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: 1.5,
                ..Stroke::default()
            };
            pixmap.stroke_path(&path, &solid(TRAIL), &stroke, Transform::identity(), None);
        }
    }
    if let Some(last) = overlay.trail.last() {
        let (px, py) = place(last);
        if let Some(path) = PathBuilder::from_circle(px, py, 3.0) {
            pixmap.fill_path(
                &path,
                &solid(TRAIL),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
    if let Some(target) = overlay.target {
        draw_bullseye(pixmap, place(&target), 5.0);
    }
    let length = scale_bar_length(scale, 0.5 * inner);
    draw_text(pixmap, (x + 3.0, y + 3.0), "top", 1.0, INK, false);
    let label = length_label(length);
    let bar = (length * scale) as f32;
    let (bx, by) = ((x + 4.0).round() + 0.5, (y + side - 5.0).round() + 0.5);
    let mut pb = PathBuilder::new();
    pb.move_to(bx, by);
    pb.line_to(bx + bar, by);
    if let Some(path) = pb.finish() {
        let stroke = Stroke {
            width: 2.0,
            ..Stroke::default()
        };
        pixmap.stroke_path(&path, &solid(INK), &stroke, Transform::identity(), None);
    }
    draw_text(pixmap, (bx + bar + 3.0, by - 8.0), &label, 1.0, INK, false);
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
        pixmap.fill_rect(rect, &solid(PANEL), Transform::identity(), None);
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
        let colour = solid(match (neuron.role, neuron.function) {
            (Role::Sensor { .. }, _) => SENSOR,
            (Role::Actuator { .. }, _) => ACTUATOR,
            (_, NeuronFunction::Oscillator) => OSCILLATOR,
            _ => NEURON,
        });
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

/// A picture of the creature: the body in a 3/4 view on the left, its brain on the right,
/// with `overlay` drawn over the body.
pub fn picture(
    creature: &Creature,
    view: &View,
    width: u32,
    height: u32,
    overlay: &Overlay,
) -> Result<Pixmap, RenderError> {
    compose(creature, view, width, height, overlay, Checks::Off)
}

fn compose(
    creature: &Creature,
    view: &View,
    width: u32,
    height: u32,
    overlay: &Overlay,
    checks: Checks,
) -> Result<Pixmap, RenderError> {
    if width < 64 || height < 64 || width > 8192 || height > 8192 {
        return Err(RenderError::Size(width, height));
    }
    let mut pixmap = Pixmap::new(width, height).ok_or(RenderError::Size(width, height))?;
    pixmap.fill(Color::from_rgba8(255, 255, 255, 255));
    let (w, h) = (width as f32, height as f32);
    let brain_w = (w * 0.3).round();
    draw_body(
        &mut pixmap,
        creature,
        view,
        (0.0, 0.0, w - brain_w, h),
        overlay,
        checks,
    );
    draw_brain(&mut pixmap, creature, (w - brain_w, 0.0, brain_w, h));
    Ok(pixmap)
}

/// The `creature.png` picture: the body and brain with the creature checked — parts that
/// interpenetrate outlined red, every part numbered, `title`, the counts and validity and
/// every problem written at the top left (a red frame round an invalid creature) — and a
/// scale bar.
pub fn checked_picture(
    creature: &Creature,
    title: &str,
    width: u32,
    height: u32,
) -> Result<Pixmap, RenderError> {
    let overlay = Overlay {
        label: if title.is_empty() {
            Vec::new()
        } else {
            vec![title.to_string()]
        },
        ..Overlay::default()
    };
    compose(
        creature,
        &View::framing(creature),
        width,
        height,
        &overlay,
        Checks::On,
    )
}

/// Writes the `creature.png` picture of one creature (see [`checked_picture`]).
pub fn write_png(
    creature: &Creature,
    title: &str,
    path: &std::path::Path,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    let pixmap = checked_picture(creature, title, width, height)?;
    let png = pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))?;
    Ok(crate::output::write(path, png)?)
}

/// One GIF frame of an opaque picture: a palette of the colours that carry meaning
/// ([`KEY_COLOURS`], exact) and 243 more that NeuQuant fits to the rest of the picture;
/// each pixel takes the nearest of the two candidates (its NeuQuant colour or the nearest
/// key colour), so a red actuator stays the red of the legend.
fn gif_frame(pixmap: &Pixmap) -> gif::Frame<'static> {
    let rgba = pixmap.data(); // opaque background: premultiplied = straight
    let quant = color_quant::NeuQuant::new(10, 256 - KEY_COLOURS.len(), rgba);
    let mut palette = quant.color_map_rgb();
    let learned = palette.len() / 3;
    palette.extend(KEY_COLOURS.iter().flatten());
    let distance = |a: &[u8], b: &[u8]| -> u32 {
        (0..3)
            .map(|k| (a[k] as i32 - b[k] as i32).pow(2) as u32)
            .sum()
    };
    let mut chosen: HashMap<[u8; 3], u8> = HashMap::new();
    let indices: Vec<u8> = rgba
        .chunks_exact(4)
        .map(|p| {
            *chosen.entry([p[0], p[1], p[2]]).or_insert_with(|| {
                let own = quant.index_of(p);
                let mut best = (distance(p, &palette[3 * own..3 * own + 3]), own);
                for (k, key) in KEY_COLOURS.iter().enumerate() {
                    let d = distance(p, key);
                    if d < best.0 {
                        best = (d, learned + k);
                    }
                }
                best.1 as u8
            })
        })
        .collect();
    gif::Frame::from_palette_pixels(
        pixmap.width() as u16,
        pixmap.height() as u16,
        indices,
        palette,
        None,
    )
}

/// A looping GIF encoder writing to `out`.
fn gif_encoder<W: std::io::Write>(
    out: W,
    width: u32,
    height: u32,
) -> Result<gif::Encoder<W>, RenderError> {
    let w = u16::try_from(width).map_err(|_| RenderError::Size(width, height))?;
    let h = u16::try_from(height).map_err(|_| RenderError::Size(width, height))?;
    let mut encoder =
        gif::Encoder::new(out, w, h, &[]).map_err(|e| RenderError::Gif(e.to_string()))?;
    encoder
        .set_repeat(gif::Repeat::Infinite)
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    Ok(encoder)
}

/// Writes a GIF of one frame: the creature as built, checked as in [`checked_picture`]
/// (interpenetrating parts outlined red, its validity and problems written), under the lines
/// of `label`. It stands in for an animation when there is nothing to animate (an
/// evaluation refused before simulating), so that the file opens and says why.
pub fn write_still_gif(
    creature: &Creature,
    label: &[String],
    path: &std::path::Path,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    let overlay = Overlay {
        label: label.to_vec(),
        ..Overlay::default()
    };
    let pixmap = compose(
        creature,
        &View::framing(creature),
        width,
        height,
        &overlay,
        Checks::On,
    )?;
    crate::output::write_with(path, |out| {
        let mut encoder = gif_encoder(out, width, height)?;
        encoder
            .write_frame(&gif_frame(&pixmap))
            .map_err(|e| RenderError::Gif(e.to_string()))?;
        finish_gif(encoder)
    })
}

/// Writes a GIF's trailer and flushes it, reporting a failure (dropping the encoder would
/// hide it).
fn finish_gif<W: std::io::Write>(encoder: gif::Encoder<W>) -> Result<(), RenderError> {
    let mut out = encoder
        .into_inner()
        .map_err(|e| RenderError::Gif(e.to_string()))?;
    Ok(out.flush()?)
}

/// Writes an animated GIF of a sequence of creatures, framed as `framing` says, looping:
/// frame i is drawn with `overlays[i]` (none beyond the slice) and lasts `delays_cs[i]`
/// hundredths of a second (the last delay for frames beyond the slice, 10 if it is empty).
pub fn write_gif<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    overlays: &[Overlay],
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
) -> Result<(), RenderError> {
    write_gif_with_progress(
        creatures,
        overlays,
        path,
        width,
        height,
        delays_cs,
        framing,
        &mut |_| {},
    )
}

/// [`write_gif`], calling `progress` with the fraction of frames written (0 to 1) after
/// each one, so that the caller can show how far drawing has got.
#[allow(clippy::too_many_arguments)]
pub fn write_gif_with_progress<'a>(
    creatures: impl IntoIterator<Item = &'a Creature> + Clone,
    overlays: &[Overlay],
    path: &std::path::Path,
    width: u32,
    height: u32,
    delays_cs: &[u16],
    framing: Framing,
    progress: &mut dyn FnMut(f64),
) -> Result<(), RenderError> {
    let views = View::per_frame(creatures.clone(), framing);
    let count = views.len().max(1);
    crate::output::write_with(path, |out| {
        let mut encoder = gif_encoder(out, width, height)?;
        let none = Overlay::default();
        for (i, creature) in creatures.into_iter().enumerate() {
            let overlay = overlays.get(i).unwrap_or(&none);
            let pixmap = picture(creature, &views[i], width, height, overlay)?;
            let mut frame = gif_frame(&pixmap);
            frame.delay = delays_cs.get(i).or(delays_cs.last()).copied().unwrap_or(10);
            encoder
                .write_frame(&frame)
                .map_err(|e| RenderError::Gif(e.to_string()))?;
            progress((i + 1) as f64 / count as f64);
        }
        finish_gif(encoder)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::creature::Role;
    use crate::develop::creature_from_commands;

    fn creature(commands: &str) -> Creature {
        creature_from_commands(commands).unwrap()
    }

    /// How many pixels of straight RGBA `data` are exactly `colour`.
    fn count(data: &[u8], colour: [u8; 3]) -> usize {
        data.chunks_exact(4)
            .filter(|p| p[..3] == colour[..])
            .count()
    }

    /// Every frame of the GIF at `path`, as straight RGBA.
    fn gif_frames(path: &std::path::Path) -> Vec<Vec<u8>> {
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(path).unwrap())
            .unwrap();
        let mut frames = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            frames.push(frame.buffer.to_vec());
        }
        frames
    }

    fn temp(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("ontogeny-render-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    /// A thrower-like creature with an actuator, posed with a projectile-like growing part.
    fn arm() -> Creature {
        let c = creature("forward(1) revolute2 forward(1) output(1)");
        assert!(
            c.brain
                .neurons
                .iter()
                .any(|n| matches!(n.role, Role::Actuator { .. }))
        );
        c
    }

    #[test]
    fn legend_colours_survive_the_gif_palette() {
        let c = arm();
        let view = View::framing(&c);
        let pixmap = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let path = temp("legend.gif");
        write_gif([&c], &[], &path, 480, 300, &[10], Framing::Still).unwrap();
        let frames = gif_frames(&path);
        assert_eq!(frames.len(), 1);
        // Every pixel that is exactly a legend colour in the picture is that colour in the
        // GIF: the actuator's red, the joint's red, the panel.
        for colour in [ACTUATOR, JOINT, PANEL, OSCILLATOR] {
            let drawn: Vec<usize> = pixmap
                .data()
                .chunks_exact(4)
                .enumerate()
                .filter(|(_, p)| p[..3] == colour[..])
                .map(|(i, _)| i)
                .collect();
            if colour != OSCILLATOR {
                assert!(drawn.len() > 20, "{colour:?} drawn: {}", drawn.len());
            }
            for i in drawn {
                assert_eq!(&frames[0][4 * i..4 * i + 3], &colour[..], "pixel {i}");
            }
        }
        // The actuator disc is solid red in the GIF (dot radius >= 3 px: at least 9 pixels).
        assert!(count(&frames[0], ACTUATOR) >= 9);
    }

    #[test]
    fn a_target_and_a_trail_are_drawn_and_shown_in_the_top_view() {
        let c = arm();
        let view = View::framing(&c);
        let trail: Vec<Vector3<f64>> = (0..20)
            .map(|k| Vector3::new(2.0 + 0.2 * k as f64, 1.0 - 0.002 * (k * k) as f64, 0.0))
            .collect();
        let plain = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let thrown = Overlay {
            trail: trail.clone(),
            ..Overlay::default()
        };
        let aimed = Overlay {
            trail,
            target: Some(Vector3::new(12.0, 0.0, 3.0)),
            ..Overlay::default()
        };
        let thrown_pic = picture(&c, &view, 480, 300, &thrown).unwrap();
        let aimed_pic = picture(&c, &view, 480, 300, &aimed).unwrap();
        assert_eq!(count(plain.data(), TARGET), 0);
        assert_eq!(count(plain.data(), TRAIL), 0);
        assert!(count(thrown_pic.data(), TRAIL) > 30);
        assert_eq!(count(thrown_pic.data(), TARGET), 0);
        // The target, 12 m off, is outside the camera's view but in the top view.
        assert!(count(aimed_pic.data(), TARGET) > 20);
        // Through a GIF: the target's colour in the aim animation only.
        let (a, b) = (temp("aim.gif"), temp("catapult.gif"));
        write_gif([&c], &[aimed], &a, 480, 300, &[10], Framing::Still).unwrap();
        write_gif([&c], &[thrown], &b, 480, 300, &[10], Framing::Still).unwrap();
        assert!(count(&gif_frames(&a)[0], TARGET) > 20);
        assert_eq!(count(&gif_frames(&b)[0], TARGET), 0);
    }

    #[test]
    fn a_label_is_written_in_the_top_left_corner() {
        let c = arm();
        let view = View::framing(&c);
        let plain = picture(&c, &view, 480, 300, &Overlay::default()).unwrap();
        let label = Overlay {
            label: vec!["t = 1.50 s  measuring".to_string()],
            ..Overlay::default()
        };
        let labelled = picture(&c, &view, 480, 300, &label).unwrap();
        // The label's box: 21 characters of 8 px from x = 8, y = 6.
        let ink = |p: &Pixmap| {
            (6..14)
                .flat_map(|y| (8..8 + 21 * 8).map(move |x| (x, y)))
                .filter(|&(x, y)| {
                    let i = 4 * (y * 480 + x) as usize;
                    p.data()[i..i + 3] == INK[..]
                })
                .count()
        };
        assert_eq!(ink(&plain), 0);
        assert!(ink(&labelled) > 150, "{}", ink(&labelled));
    }

    #[test]
    fn an_invalid_creature_is_marked_and_a_valid_one_is_not() {
        let valid = arm();
        let pic = checked_picture(&valid, "arm", 960, 600).unwrap();
        assert_eq!(count(pic.data(), MARK), 0);
        // Two parts laid one inside the other (a creature.json may hold anything).
        let mut overlapping = valid.clone();
        overlapping.parts[1].position = overlapping.parts[0].position;
        assert!(!overlapping.interpenetrating_pairs().is_empty());
        let pic = checked_picture(&overlapping, "arm", 960, 600).unwrap();
        // The red frame alone is 2 × (960 × 0.7 + 600) × 3 px; the outlines and the text add.
        assert!(
            count(pic.data(), MARK) > 6000,
            "{}",
            count(pic.data(), MARK)
        );
        // A problem listed by development marks it too, with no geometry to outline.
        let mut listed = valid.clone();
        listed.problems.push(crate::creature::Problem {
            severity: Severity::Error,
            message: "too many parts".to_string(),
            module: None,
            t: None,
        });
        let pic = checked_picture(&listed, "", 960, 600).unwrap();
        assert!(count(pic.data(), MARK) > 6000);
    }

    #[test]
    fn joint_discs_follow_the_parts_and_show_the_axis() {
        // Parts 0.1 m wide and thick and 1 m long: discs 0.05 m in radius.
        let thin = creature("width(0.1) thickness(0.1) forward(1) revolute2 forward(1)");
        assert!((joint_radius(&thin, 0, 1) - 0.05).abs() < 1e-12);
        // Twice as wide: twice the radius, about four times the red pixels (less the
        // anti-aliased rim, where the colour is not exact).
        let wide = creature("width(0.2) thickness(0.2) forward(1) revolute2 forward(1)");
        assert!((joint_radius(&wide, 0, 1) - 0.1).abs() < 1e-12);
        let view = View::framing(&wide);
        let red = |c: &Creature| {
            let pic = picture(c, &view, 960, 600, &Overlay::default()).unwrap();
            count(pic.data(), JOINT)
        };
        let (a, b) = (red(&thin), red(&wide));
        assert!(
            a > 10 && (2.5..6.0).contains(&(b as f64 / a as f64)),
            "{a} {b}"
        );
        // The axis is drawn: some pixels of the axis colour near the anchor.
        let pic = picture(&thin, &view, 960, 600, &Overlay::default()).unwrap();
        assert!(count(pic.data(), AXIS) > 5);
    }

    #[test]
    fn scale_bars_take_round_lengths() {
        // 100 px per metre and 120 px of room: 1 m; 90 px: 50 cm; 1000 px: 10 m.
        assert_eq!(scale_bar_length(100.0, 120.0), 1.0);
        assert_eq!(scale_bar_length(100.0, 90.0), 0.5);
        assert_eq!(scale_bar_length(100.0, 1000.0), 10.0);
        assert_eq!(length_label(1.0), "1 m");
        assert_eq!(length_label(0.5), "50 cm");
        assert_eq!(length_label(0.005), "5 mm");
        assert_eq!(fit("a long label", 48.0, 1.0), "a l...");
        assert_eq!(ascii("D_p − D_t · 2"), "D_p - D_t * 2");
    }
}
