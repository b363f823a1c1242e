//! A recording's world for the page: the geometry of its `[task.world]` worked out by
//! [`Terrain`], so that the page draws the same ground, obstacles and objects as the pictures
//! (the objects' poses over time are in the recording's samples).

use serde_json::{Value, json};

use crate::sim::WorldSpec;
use crate::sim::terrain::{Cuboid, Terrain};
use crate::sim::world_spec::ObjectShape;

/// A box as the page reads it: centre, half sizes and direction (degrees about +y from +x
/// towards +z).
fn cuboid(c: &Cuboid) -> Value {
    json!({ "centre": c.centre, "half": c.half, "direction": c.direction })
}

/// The page's `scene` for `world`: `ground` (`level`, `slope`, `steps`, `rough` or `none` in
/// water), the slope's upward `normal`, the ground's `boxes` (steps, or the level slabs round
/// rough ground), the rough ground's `heightfield` (`samples`, `side`, `heights` row by row
/// along +z), the `obstacles`' boxes, the `objects` where they start (`shape`, `half`,
/// `centre`) and `water`.
pub fn scene(world: &WorldSpec) -> Value {
    let terrain = Terrain::new(world);
    let water = !world.medium.is_air();
    let ground = if water {
        "none"
    } else if world.slope.is_some() {
        "slope"
    } else if world.steps.is_some() {
        "steps"
    } else if world.rough.is_some() {
        "rough"
    } else {
        "level"
    };
    let heightfield = terrain
        .heightfield()
        .map(|f| json!({ "samples": f.samples, "side": f.side, "heights": f.heights }));
    let objects: Vec<Value> = terrain
        .objects()
        .iter()
        .map(|o| {
            json!({
                "shape": match o.shape {
                    ObjectShape::Ball => "ball",
                    ObjectShape::Box => "box",
                },
                "half": o.half,
                "centre": o.centre,
            })
        })
        .collect();
    json!({
        "ground": ground,
        "normal": terrain.slope_normal(),
        "boxes": if water { Vec::new() } else { terrain.ground_boxes().iter().map(cuboid).collect() },
        "heightfield": if water { None } else { heightfield },
        "obstacles": terrain.obstacle_boxes().iter().map(cuboid).collect::<Vec<_>>(),
        "objects": objects,
        "water": water,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world(text: &str) -> WorldSpec {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn a_slope_is_sent_as_its_tilted_ground_and_normal() {
        let s = scene(&world("slope = { degrees = 30, direction = 0 }"));
        assert_eq!(s["ground"], "slope");
        let n: Vec<f64> = serde_json::from_value(s["normal"].clone()).unwrap();
        assert!((n[0] + 0.5).abs() < 1e-12 && (n[1] - 0.75f64.sqrt()).abs() < 1e-12);
        assert_eq!(s["boxes"], json!([]));
        assert_eq!(s["water"], false);
    }

    #[test]
    fn steps_obstacles_and_objects_are_sent_as_boxes_and_balls() {
        let s = scene(&world(
            "steps = { height = 0.1, depth = 0.5, count = 3, way = \"up\", start = 1, direction = 0 }\n\
             obstacles = { size = [0.2, 0.3, 0.2], at = [[2, 1]] }\n\
             objects = [{ shape = \"ball\", size = 0.1, mass = 1, position = [0, 0.5, 2] }]",
        ));
        assert_eq!(s["ground"], "steps");
        assert_eq!(s["boxes"].as_array().unwrap().len(), 3);
        assert_eq!(s["boxes"][0]["half"][0], 0.25);
        assert_eq!(s["boxes"][0]["centre"][1], -0.45);
        // On the edge of the third step: it reaches down to the second's tread.
        assert_eq!(s["obstacles"][0]["half"], json!([0.1, 0.2, 0.1]));
        assert_eq!(s["obstacles"][0]["centre"][0], 2.0);
        assert_eq!(s["objects"][0]["shape"], "ball");
        assert_eq!(s["objects"][0]["half"], 0.1);
        assert_eq!(s["objects"][0]["centre"], json!([0.0, 0.5, 2.0]));
    }

    #[test]
    fn rough_ground_is_sent_as_its_samples_and_water_as_no_ground() {
        let rough = scene(&world(
            "rough = { amplitude = 0.05, wavelength = 1, seed = 3, size = 4 }",
        ));
        assert_eq!(rough["ground"], "rough");
        let field = &rough["heightfield"];
        let n = field["samples"].as_u64().unwrap() as usize;
        assert_eq!(field["heights"].as_array().unwrap().len(), n * n);
        assert_eq!(field["side"], 4.0);
        assert_eq!(rough["boxes"].as_array().unwrap().len(), 4);
        let water = scene(&world("medium = { kind = \"water\", viscosity = 5 }"));
        assert_eq!(water["ground"], "none");
        assert_eq!(water["water"], true);
        assert_eq!(water["heightfield"], Value::Null);
    }
}
