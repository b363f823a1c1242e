//! The pen the pictures draw with: a plain stroke of a width, a filled path, a polyline.

use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap, Stroke, Transform};

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
