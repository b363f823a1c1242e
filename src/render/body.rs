//! The body's 3/4 view: the ground grid, shadows, shaded parts, joints with their axes, the
//! target and the projectile's trail, and, when the picture checks the creature, what makes it
//! invalid (interpenetrating parts outlined, part numbers, problems written) and a scale bar.

use nalgebra::Vector3;
use tiny_skia::{PathBuilder, Pixmap, Rect, Transform};

use super::Overlay;
use super::camera::{Camera, View};
use super::palette::{AXIS, GROWING_JOINT, INK, JOINT, MARK, PATH, TARGET, TRAIL, paint, solid};
use super::pen::{convex_hull_path, draw_bullseye, fill, polygon, polyline, stroke_width};
use super::text::{draw_text, fit, length_label, listed_lines, scale_bar_length, text_width};
use super::top_view::draw_top_view;
use super::world::{
    BOX_FACES, Solids, draw_ground_shape, draw_solids, is_water, light, shapes_ground, tint_water,
};
use crate::creature::{Creature, Severity, counted};

/// Whether a picture checks the creature: marks interpenetrating parts, numbers the parts and
/// writes its validity and problems.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Checks {
    /// Checked.
    On,
    /// Not checked.
    Off,
}

/// The radius of a joint's disc in metres: half the smaller joined part's middle dimension
/// (its width, for a bar), so that a disc is as wide as the parts it joins.
pub(super) fn joint_radius(creature: &Creature, parent: usize, child: usize) -> f64 {
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
/// `checks` is on, the marks of what makes the creature invalid and part numbers: the ground,
/// the target's stem, shadows, the parts, the marks, the joints, the trail and the target,
/// the part numbers, the scale bar, the top view and the text, in that order (later ones on
/// top).
pub(super) fn draw_body(
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
    let level = view.min.y.min(0.0);
    let world = overlay.world.as_deref();
    let shaped = world.filter(|t| shapes_ground(t) && !is_water(t));
    let water = world.is_some_and(is_water);
    // The ground's height under a point: the world's shaped ground, or level.
    let ground = |x: f64, z: f64| shaped.map_or(level, |t| t.height(x, z));
    match shaped {
        _ if water => {}
        Some(terrain) => {
            let (step, x, z) = ground_window(view);
            draw_ground_shape(pixmap, &camera, shift, (x, z), step, terrain);
        }
        None => draw_ground(pixmap, &camera, shift, view, level),
    }
    if let Some(target) = overlay.target {
        draw_target_stem(pixmap, &camera, shift, &ground, target);
    }
    draw_path(pixmap, &camera, shift, &ground, &overlay.path);
    if !water {
        draw_shadows(pixmap, &camera, shift, &ground, creature);
    }
    // The world's solids behind the creature's centre are drawn before it, the others over it.
    let (lo, hi) = creature.bounding_box();
    let depth = camera.project(&(0.5 * (lo + hi))).2;
    if let Some(terrain) = world {
        let behind = (terrain, Solids::Behind(depth));
        draw_solids(pixmap, &camera, shift, behind, &overlay.objects);
    }
    draw_parts(pixmap, &camera, shift, creature);
    if let Some(terrain) = world {
        let in_front = (terrain, Solids::InFront(depth));
        draw_solids(pixmap, &camera, shift, in_front, &overlay.objects);
    }
    // Parts that the builder found overlapping and reported as a warning (a picture of a
    // plant) are not marked again.
    let overlaps_warned = creature
        .problems
        .iter()
        .any(|p| p.severity == Severity::Warning && p.message.contains("interpenetrate"));
    let pairs = if checks == Checks::On && !overlaps_warned {
        creature.interpenetrating_pairs()
    } else {
        Vec::new()
    };
    let marked = outline_marked(pixmap, &camera, shift, creature, &pairs);
    draw_joints(pixmap, &camera, shift, creature, 0.05 * rw.min(rh));
    draw_trail_and_target(pixmap, &camera, region, overlay);
    if checks == Checks::On {
        number_parts(pixmap, &camera, region, creature, &marked);
    }
    if water {
        tint_water(pixmap, region);
    }
    let text_scale = if rh >= 500.0 { 2.0 } else { 1.0 };
    draw_scale_bar(pixmap, &camera, region, text_scale);
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
    let text = Lines {
        region,
        room,
        scale: text_scale,
    };
    write_text(pixmap, &text, overlay, creature, checks, &pairs);
}

/// The ground grid's spacing and the window of the ground drawn round `view`, its x and z
/// ranges on the grid.
fn ground_window(view: &View) -> (f64, [f64; 2], [f64; 2]) {
    let extent = (view.max - view.min).norm().max(1.0);
    let step = if extent > 8.0 {
        1.0
    } else if extent > 2.0 {
        0.5
    } else {
        0.25
    };
    let pad = 0.25 * extent;
    (
        step,
        [
            ((view.min.x - pad) / step).floor() * step,
            ((view.max.x + pad) / step).ceil() * step,
        ],
        [
            ((view.min.z - pad) / step).floor() * step,
            ((view.max.z + pad) / step).ceil() * step,
        ],
    )
}

/// The ground grid on the plane y = `ground`, one line per metre (or finer for small
/// creatures), on a pale floor.
fn draw_ground(pixmap: &mut Pixmap, camera: &Camera, shift: Transform, view: &View, ground: f64) {
    let (step, [x0, x1], [z0, z1]) = ground_window(view);
    let floor: Vec<(f32, f32)> = [(x0, z0), (x1, z0), (x1, z1), (x0, z1)]
        .iter()
        .map(|c| {
            let (sx, sy, _) = camera.project(&Vector3::new(c.0, ground, c.1));
            (sx, sy)
        })
        .collect();
    if let Some(path) = polygon(&floor) {
        fill(pixmap, &path, &paint(232, 234, 228, 255), shift);
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
        let stroke = stroke_width(1.0);
        pixmap.stroke_path(&path, &paint(190, 194, 186, 255), &stroke, shift, None);
    }
}

/// The aim task's target's foot on the ground and the line up to it.
fn draw_target_stem(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    ground: &dyn Fn(f64, f64) -> f64,
    target: Vector3<f64>,
) {
    let (fx, fy, _) = camera.project(&Vector3::new(
        target.x,
        ground(target.x, target.z),
        target.z,
    ));
    let (tx, ty, _) = camera.project(&target);
    let mut pb = PathBuilder::new();
    pb.push_oval(Rect::from_xywh(fx - 8.0, fy - 3.5, 16.0, 7.0).expect("finite"));
    pb.move_to(fx, fy);
    pb.line_to(tx, ty);
    if let Some(path) = pb.finish() {
        let stroke = stroke_width(1.5);
        pixmap.stroke_path(&path, &solid(TARGET), &stroke, shift, None);
    }
}

/// A walker's path on the ground (at y = `ground`), with a dot where it started.
fn draw_path(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    ground: &dyn Fn(f64, f64) -> f64,
    path: &[Vector3<f64>],
) {
    let projected: Vec<(f32, f32)> = path
        .iter()
        .map(|p| {
            let (sx, sy, _) = camera.project(&Vector3::new(p.x, ground(p.x, p.z), p.z));
            (sx, sy)
        })
        .collect();
    if let Some(line) = polyline(projected.iter().copied()) {
        pixmap.stroke_path(&line, &solid(PATH), &stroke_width(3.0), shift, None);
    }
    if let Some(&(x, y)) = projected.first()
        && let Some(dot) = PathBuilder::from_circle(x, y, 4.0)
    {
        fill(pixmap, &dot, &solid(PATH), shift);
    }
}

/// Shadows: each part's footprint dropped onto the ground.
fn draw_shadows(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    ground: &dyn Fn(f64, f64) -> f64,
    creature: &Creature,
) {
    for part in &creature.parts {
        let corners = part.corners();
        let mut pts: Vec<(f32, f32)> = corners
            .iter()
            .map(|c| {
                let (sx, sy, _) = camera.project(&Vector3::new(c.x, ground(c.x, c.z), c.z));
                (sx, sy)
            })
            .collect();
        if let Some(path) = convex_hull_path(&mut pts) {
            fill(pixmap, &path, &paint(0, 0, 0, 40), shift);
        }
    }
}

/// The faces of every part, far to near (painter's algorithm), lit from above and to the
/// side: the root part darker, growing parts orange.
fn draw_parts(pixmap: &mut Pixmap, camera: &Camera, shift: Transform, creature: &Creature) {
    let light = light();
    let viewer = camera.towards_viewer();
    let mut faces = Vec::new();
    for (index, part) in creature.parts.iter().enumerate() {
        let corners = part.corners();
        let centre = part.position;
        for face in BOX_FACES {
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
    let outline = stroke_width(1.0);
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
        let colour = paint(
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
            fill(pixmap, &path, &colour, shift);
            pixmap.stroke_path(&path, &paint(30, 40, 60, 200), &outline, shift, None);
        }
    }
}

/// Outlines in the marking colour the parts of the interpenetrating `pairs`; returns them,
/// each once, in order.
fn outline_marked(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    creature: &Creature,
    pairs: &[(usize, usize)],
) -> Vec<usize> {
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
            let stroke = stroke_width(3.0);
            pixmap.stroke_path(&path, &solid(MARK), &stroke, shift, None);
        }
    }
    marked
}

/// The joints, on top of the parts: a disc in the plane each movable joint turns in (red,
/// orange while growing), its size following the parts it joins and never larger (at most
/// `most` pixels), with
/// a line along each axis ending in a dot at the axis's positive end; fused joints are grey
/// dots, unless the creature has more than [`MOST_PARTS_WITH_FUSED_DOTS`] parts.
/// The most parts a creature may have for its fused joints to be drawn (as grey dots).
const MOST_PARTS_WITH_FUSED_DOTS: usize = 100;

fn draw_joints(
    pixmap: &mut Pixmap,
    camera: &Camera,
    shift: Transform,
    creature: &Creature,
    most: f32,
) {
    let outline = stroke_width(1.0);
    // A plant of hundreds of parts would be covered in the dots of its fused joints.
    let fused_dots = creature.parts.len() <= MOST_PARTS_WITH_FUSED_DOTS;
    for joint in &creature.joints {
        if !fused_dots && (joint.kind.dof() == 0 || joint.axes.is_empty()) {
            continue;
        }
        let (sx, sy, _) = camera.project(&joint.anchor);
        let radius = joint_radius(creature, joint.parent, joint.child);
        // No larger than the parts joined (nor than `most`), and at least a visible dot.
        let pixels = ((radius * camera.scale) as f32).min(most).max(1.5);
        let radius = pixels as f64 / camera.scale;
        if joint.kind.dof() == 0 || joint.axes.is_empty() {
            let dot = (0.4 * pixels).clamp(2.0, 6.0);
            if let Some(path) = PathBuilder::from_circle(sx, sy, dot) {
                fill(pixmap, &path, &paint(90, 90, 90, 220), shift);
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
            fill(pixmap, &path, &solid(colour), shift);
            pixmap.stroke_path(&path, &solid([255; 3]), &outline, shift, None);
        }
        if let Some(path) = PathBuilder::from_circle(sx, sy, 2.5) {
            fill(pixmap, &path, &solid(colour), shift);
        }
        let stroke = stroke_width(2.0);
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
}

/// The projectile's trail and the target's bullseye.
fn draw_trail_and_target(
    pixmap: &mut Pixmap,
    camera: &Camera,
    region: (f32, f32, f32, f32),
    overlay: &Overlay,
) {
    let (rx, ry, _, _) = region;
    let shift = Transform::from_translate(rx, ry);
    let projected = overlay.trail.iter().map(|p| {
        let (px, py, _) = camera.project(p);
        (px, py)
    });
    if let Some(path) = polyline(projected) {
        pixmap.stroke_path(&path, &solid(TRAIL), &stroke_width(2.0), shift, None);
    }
    if let Some(target) = overlay.target {
        let (tx, ty, _) = camera.project(&target);
        draw_bullseye(pixmap, (rx + tx, ry + ty), 7.0);
    }
}

/// Part numbers, red for `marked` parts: every marked part's, and the others' where the part
/// is large enough in the picture to hold its number and no other number is in the way.
fn number_parts(
    pixmap: &mut Pixmap,
    camera: &Camera,
    region: (f32, f32, f32, f32),
    creature: &Creature,
    marked: &[usize],
) {
    let (rx, ry, _, _) = region;
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
        let Some(boxed) = Rect::from_xywh(px - half - 2.0, py - 6.0, 2.0 * half + 4.0, 12.0) else {
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

/// The scale bar, bottom left, with its length written at `text_scale`.
fn draw_scale_bar(
    pixmap: &mut Pixmap,
    camera: &Camera,
    region: (f32, f32, f32, f32),
    text_scale: f32,
) {
    let (rx, ry, rw, rh) = region;
    let length = scale_bar_length(camera.scale, 0.25 * rw as f64);
    let bar = (length * camera.scale) as f32;
    let (bx, by) = ((rx + 12.0).round() + 0.5, (ry + rh - 10.0).round() + 0.5);
    let mut pb = PathBuilder::new();
    pb.move_to(bx, by - 4.0);
    pb.line_to(bx, by);
    pb.line_to(bx + bar, by);
    pb.line_to(bx + bar, by - 4.0);
    if let Some(path) = pb.finish() {
        let stroke = stroke_width(2.0);
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
}

/// Where a picture's lines of text go: the region, the width they may take, and the font's
/// scale.
struct Lines {
    region: (f32, f32, f32, f32),
    room: f32,
    scale: f32,
}

/// The line that gives the size of the projectile a creature throws when it has one of its
/// own (an evolved one, or a file's `projectile` line), in centimetres: the picture draws
/// the body only, and where the task holds the projectile is the task's.
pub(crate) fn projectile_line(creature: &Creature) -> Option<String> {
    creature.projectile.map(|[x, y, z]| {
        format!(
            "projectile {:.1} x {:.1} x {:.1} cm",
            x * 100.0,
            y * 100.0,
            z * 100.0
        )
    })
}

/// Lines of text, top left: the overlay's label; with checks, the creature's counts and
/// validity, the size of its own projectile (if it has one), and its problems after them
/// (wrapped, repeated ones once, at most a few, then how many more), and a red frame round an
/// invalid creature.
fn write_text(
    pixmap: &mut Pixmap,
    text: &Lines,
    overlay: &Overlay,
    creature: &Creature,
    checks: Checks,
    pairs: &[(usize, usize)],
) {
    let (rx, ry, rw, rh) = text.region;
    let (room, text_scale) = (text.room, text.scale);
    let line = 10.0 * text_scale + 2.0;
    // Writes one line at height `y`, cut to the room, and returns the next line's height.
    let write_line = |pixmap: &mut Pixmap, y: f32, text: &str, colour: [u8; 3]| {
        draw_text(
            pixmap,
            (rx + 8.0, y),
            &fit(text, room, text_scale),
            text_scale,
            colour,
            true,
        );
        y + line
    };
    let mut y = ry + 6.0;
    for text in &overlay.label {
        y = write_line(pixmap, y, text, INK);
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
        for (a, b) in pairs {
            let message = format!("parts {a} and {b} interpenetrate");
            if !creature.problems.iter().any(|p| p.message == message) {
                problems.push((format!("error: {message}"), MARK));
            }
        }
        let valid = creature.is_valid() && pairs.is_empty();
        let summary = format!(
            "{}, {}, {}: {}",
            counted(creature.parts.len(), "part"),
            counted(creature.joints.len(), "joint"),
            counted(creature.brain.neurons.len(), "neuron"),
            match (valid, creature.problems.iter().any(|p| p.is_picture_only())) {
                (false, _) => "INVALID",
                (true, false) => "valid",
                (true, true) => "valid as a picture only",
            }
        );
        y = write_line(pixmap, y, &summary, if valid { INK } else { MARK });
        if let Some(text) = projectile_line(creature) {
            y = write_line(pixmap, y, &text, INK);
        }
        let room_lines = ((rh - y - 24.0) / line).floor().max(0.0) as usize;
        let columns = (room / (8.0 * text_scale)).floor().max(8.0) as usize;
        for (text, colour) in listed_lines(problems, columns, room_lines) {
            y = write_line(pixmap, y, &text, colour);
        }
        if !valid && let Some(rect) = Rect::from_xywh(rx + 1.5, ry + 1.5, rw - 3.0, rh - 3.0) {
            let stroke = stroke_width(3.0);
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
