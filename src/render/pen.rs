//! The pen the pictures draw with: a plain stroke of a width, a filled path, a polyline, a
//! closed polygon and a convex hull, and a target's bullseye.

use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap, Stroke, Transform};

use super::palette::{TARGET, solid};

/// A plain stroke `width` pixels wide.
pub(super) fn stroke_width(width: f32) -> Stroke {
    Stroke {
        width,
        ..Stroke::default()
    }
}

/// Fills `path` (non-zero winding), moved by `transform`, with `paint`.
pub(super) fn fill(pixmap: &mut Pixmap, path: &Path, paint: &Paint<'_>, transform: Transform) {
    pixmap.fill_path(path, paint, FillRule::Winding, transform, None);
}

/// The open path through `points` in order; `None` for fewer than two.
pub(super) fn polyline(points: impl IntoIterator<Item = (f32, f32)>) -> Option<Path> {
    let mut pb = PathBuilder::new();
    for (k, (x, y)) in points.into_iter().enumerate() {
        if k == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
    }
    pb.finish()
}

/// A target's bullseye centred on `(x, y)` (pixels), `radius` across its outer ring.
pub(super) fn draw_bullseye(pixmap: &mut Pixmap, (x, y): (f32, f32), radius: f32) {
    for (r, colour) in [
        (radius, TARGET),
        (radius * 0.62, [255; 3]),
        (radius * 0.3, TARGET),
    ] {
        if let Some(path) = PathBuilder::from_circle(x, y, r) {
            fill(pixmap, &path, &solid(colour), Transform::identity());
        }
    }
}

/// The convex hull of `pts` as a closed path (gift wrapping; at most 8 points here).
pub(super) fn convex_hull_path(pts: &mut [(f32, f32)]) -> Option<tiny_skia::Path> {
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
pub(super) fn polygon(points: &[(f32, f32)]) -> Option<tiny_skia::Path> {
    let (first, rest) = points.split_first()?;
    let mut pb = PathBuilder::new();
    pb.move_to(first.0, first.1);
    for p in rest {
        pb.line_to(p.0, p.1);
    }
    pb.close();
    pb.finish()
}
