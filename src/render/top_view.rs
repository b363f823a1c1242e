//! The top view in a picture's corner: the creature's parts, the projectile's trail and the aim
//! task's target seen from above, fitted to hold them all, with a scale bar, so that a throw
//! stays visible when it leaves the camera's view.

use nalgebra::Vector3;
use tiny_skia::{PathBuilder, Pixmap, Rect, Transform};

use super::Overlay;
use super::palette::{INK, TRAIL, paint, solid};
use super::pen::{convex_hull_path, draw_bullseye, fill, polyline, stroke_width};
use super::text::{draw_text, length_label, scale_bar_length};
use crate::creature::Creature;

/// A top view (x right, z down) of the creature's parts, the trail, the projectile and the
/// target in the square `(x, y, side, side)`, fitted to hold them all, with its scale.
pub(super) fn draw_top_view(
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
    let thin = stroke_width(1.0);
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
            fill(pixmap, &path, &colour, Transform::identity());
        }
    }
    if let Some(path) = polyline(overlay.trail.iter().map(place)) {
        let stroke = stroke_width(1.5);
        pixmap.stroke_path(&path, &solid(TRAIL), &stroke, Transform::identity(), None);
    }
    if let Some(last) = overlay.trail.last() {
        let (px, py) = place(last);
        if let Some(path) = PathBuilder::from_circle(px, py, 3.0) {
            fill(pixmap, &path, &solid(TRAIL), Transform::identity());
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
        let stroke = stroke_width(2.0);
        pixmap.stroke_path(&path, &solid(INK), &stroke, Transform::identity(), None);
    }
    draw_text(pixmap, (bx + bar + 3.0, by - 8.0), &label, 1.0, INK, false);
}
