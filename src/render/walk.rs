//! What a walker's animation shows of its walk: the distance walked so far, measured as the
//! walker task measures D_w (the root part's centre, horizontally, from where the measured walk
//! starts), and the root's path on the ground.

use nalgebra::Vector3;

use crate::task::{Phase, Sample};

/// The most points of the root's path drawn in one image.
const MAX_PATH_POINTS: usize = 400;

/// The sample the measured walk starts from: the last one before the first sample of the
/// measuring phase (the pose the walker task takes D_w from), or the first sample when the
/// recording starts measuring. `None` when no sample is in the measuring phase (a walk that
/// ended before it, or a recording without phases).
pub fn walk_start(samples: &[Sample]) -> Option<usize> {
    let first = samples
        .iter()
        .position(|s| s.phase == Some(Phase::Measuring))?;
    Some(first.saturating_sub(1))
}

/// The root part's centre at `sample`, dropped onto the ground (y = 0).
fn root_on_ground(sample: &Sample) -> Option<Vector3<f64>> {
    sample
        .parts
        .first()
        .map(|(p, _)| Vector3::new(p.x, 0.0, p.z))
}

/// The distance walked at sample `at`: the horizontal distance of the root part's centre from
/// where it stood at [`walk_start`]. `None` before the walk starts or without one; at the last
/// sample of a complete walk it is the evaluation's D_w (to the recording's f32 precision).
pub fn walked(samples: &[Sample], at: usize) -> Option<f64> {
    let start = walk_start(samples)?;
    if at < start {
        return None;
    }
    let from = root_on_ground(samples.get(start)?)?;
    let to = root_on_ground(samples.get(at)?)?;
    Some((to - from).norm())
}

/// The root part's path on the ground from the walk's start to sample `at` (included),
/// oldest first, thinned to at most about 400 points, the latest always kept. Empty before
/// the walk starts or without one.
pub fn root_path(samples: &[Sample], at: usize) -> Vec<Vector3<f64>> {
    let Some(start) = walk_start(samples) else {
        return Vec::new();
    };
    if at < start || at >= samples.len() {
        return Vec::new();
    }
    let walked: Vec<Vector3<f64>> = samples[start..=at]
        .iter()
        .filter_map(root_on_ground)
        .collect();
    thinned(&walked, MAX_PATH_POINTS)
}

/// `points` thinned evenly to about `most` of them (every k-th), the last always kept.
pub(super) fn thinned(points: &[Vector3<f64>], most: usize) -> Vec<Vector3<f64>> {
    let stride = points.len().div_ceil(most).max(1);
    let mut kept: Vec<_> = points.iter().step_by(stride).copied().collect();
    if let Some(last) = points.last()
        && kept.last() != Some(last)
    {
        kept.push(*last);
    }
    kept
}

/// The distance walked as an image's label says it: `"walked 4.21 m"`.
pub fn walked_label(distance: f64) -> String {
    format!("walked {distance:.2} m")
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    fn sample(t: f64, phase: Phase, x: f64, z: f64) -> Sample {
        Sample {
            t,
            phase: Some(phase),
            parts: vec![(Vector3::new(x, 0.4, z), UnitQuaternion::identity())],
            projectile: None,
            projectile_size: None,
            objects: Vec::new(),
            growth: Vec::new(),
        }
    }

    #[test]
    fn the_walk_is_measured_from_the_pose_before_the_first_measuring_sample() {
        let samples = vec![
            sample(0.0, Phase::Settling, 5.0, 5.0),
            sample(0.1, Phase::Settling, 1.0, 1.0),
            sample(0.2, Phase::Measuring, 4.0, 1.0),
            sample(0.3, Phase::Measuring, 4.0, 5.0),
        ];
        assert_eq!(walk_start(&samples), Some(1));
        assert_eq!(walked(&samples, 0), None);
        assert_eq!(walked(&samples, 1), Some(0.0));
        assert_eq!(walked(&samples, 2), Some(3.0));
        // 3 along x and 4 along z: 5 m, whatever the height.
        assert_eq!(walked(&samples, 3), Some(5.0));
        assert_eq!(walked_label(5.0), "walked 5.00 m");
        assert_eq!(walked_label(4.214), "walked 4.21 m");
        assert_eq!(
            root_path(&samples, 3),
            [
                Vector3::new(1.0, 0.0, 1.0),
                Vector3::new(4.0, 0.0, 1.0),
                Vector3::new(4.0, 0.0, 5.0)
            ]
        );
        assert!(root_path(&samples, 0).is_empty());
    }

    #[test]
    fn a_recording_that_never_measures_has_no_walk() {
        let samples = vec![
            sample(0.0, Phase::Settling, 0.0, 0.0),
            sample(0.1, Phase::Throwing, 1.0, 0.0),
        ];
        assert_eq!(walk_start(&samples), None);
        assert_eq!(walked(&samples, 1), None);
        assert!(root_path(&samples, 1).is_empty());
    }

    #[test]
    fn a_long_path_is_thinned_and_ends_at_the_latest_pose() {
        let samples: Vec<Sample> = (0..1201)
            .map(|k| sample(k as f64 / 60.0, Phase::Measuring, k as f64 * 0.01, 0.0))
            .collect();
        let path = root_path(&samples, 1200);
        assert!(path.len() <= 401, "{}", path.len());
        assert_eq!(path[0], Vector3::new(0.0, 0.0, 0.0));
        assert_eq!(*path.last().unwrap(), Vector3::new(12.0, 0.0, 0.0));
    }
}
