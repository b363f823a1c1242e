//! The textbook turtle (*The Algorithmic Beauty of Plants*, chapter 1): its symbols' meaning
//! in the builder, the `angle:`, `step:` and `heading:` headers, the symbols it leaves out,
//! and the shipped plants of figures 1.24 to 1.27 against a turtle written here.

use std::collections::HashMap;

use nalgebra::Vector3;
use ontogeny::creature::{Creature, JointKind, Severity};
use ontogeny::develop::{BuildOptions, grow_last};
use ontogeny::lsystem::{DeriveOptions, LSystem};

use crate::util::{assert_bad_input, lsystem, ontogeny_ok, scratch_dir, stdout};

/// The last creature of `lsys`, built for a picture with room for `max_parts` parts.
fn plant(lsys: &LSystem, max_parts: usize) -> Creature {
    let options = BuildOptions {
        max_parts,
        for_picture: true,
        ..BuildOptions::default()
    };
    grow_last(lsys, &DeriveOptions::default(), None, &options, &mut |_| {})
        .unwrap_or_else(|e| panic!("{e}"))
        .frame
        .creature
}

/// The creature an axiom (with header lines before it) builds, for physics.
fn built(text: &str) -> Creature {
    plant_for_physics(&lsystem(text))
}

fn plant_for_physics(lsys: &LSystem) -> Creature {
    grow_last(
        lsys,
        &DeriveOptions::default(),
        None,
        &BuildOptions::default(),
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .frame
    .creature
}

fn near(a: Vector3<f64>, b: [f64; 3]) -> bool {
    (a - Vector3::from(b)).norm() < 1e-9
}

/// A part's two ends.
fn ends(creature: &Creature, k: usize) -> (Vector3<f64>, Vector3<f64>) {
    let p = &creature.parts[k];
    let half = p.orientation * Vector3::x() * (p.size.x / 2.0);
    (p.position - half, p.position + half)
}

/// A turtle in the plane written for these tests: rewrites `axiom` `n` times by `rules`
/// (one character each), then walks the string heading up (+y), `+` turning left
/// (counterclockwise: towards −x) by `delta` degrees. Returns how many distinct segments it
/// draws (a segment drawn again from the same segment to the same place counts once, as
/// the builder builds it once) and the box of their end points (x, y).
fn textbook_turtle(
    axiom: &str,
    rules: &[(char, &str)],
    n: usize,
    delta: f64,
) -> (usize, [f64; 2], [f64; 2]) {
    let mut s = axiom.to_string();
    for _ in 0..n {
        s = s
            .chars()
            .map(|c| {
                rules
                    .iter()
                    .find(|(p, _)| *p == c)
                    .map_or(c.to_string(), |(_, r)| r.to_string())
            })
            .collect();
    }
    let key = |v: f64| (v * 1e6).round() as i64;
    let (mut x, mut y, mut a) = (0.0f64, 0.0f64, 90.0f64);
    let mut from: Option<usize> = None;
    let mut stack = Vec::new();
    let mut segments: HashMap<(Option<usize>, [i64; 4]), usize> = HashMap::new();
    let (mut lo, mut hi) = ([0.0f64; 2], [0.0f64; 2]);
    for c in s.chars() {
        match c {
            'F' => {
                let (nx, ny) = (x + a.to_radians().cos(), y + a.to_radians().sin());
                let next = segments.len();
                let id = *segments
                    .entry((from, [key(x), key(y), key(nx), key(ny)]))
                    .or_insert(next);
                from = Some(id);
                (x, y) = (nx, ny);
                lo = [lo[0].min(x), lo[1].min(y)];
                hi = [hi[0].max(x), hi[1].max(y)];
            }
            '+' => a += delta,
            '-' => a -= delta,
            '[' => stack.push((x, y, a, from)),
            ']' => (x, y, a, from) = stack.pop().expect("balanced"),
            _ => {}
        }
    }
    (segments.len(), lo, hi)
}

/// One of the shipped figures: its file, and the textbook's axiom, rules, n and δ.
struct Figure {
    file: &'static str,
    axiom: &'static str,
    rules: &'static [(char, &'static str)],
    n: usize,
    delta: f64,
    /// The segments the textbook's string draws (its F's), worked out by hand.
    drawn: usize,
}

const FIGURES: [Figure; 6] = [
    Figure {
        file: "examples/abop-1.24a.lsys",
        axiom: "F",
        rules: &[('F', "F[+F]F[-F]F")],
        n: 5,
        delta: 25.7,
        drawn: 3125, // 5^5
    },
    Figure {
        file: "examples/abop-1.24b.lsys",
        axiom: "F",
        rules: &[('F', "F[+F]F[-F][F]")],
        n: 5,
        delta: 20.0,
        drawn: 3125, // 5^5
    },
    Figure {
        file: "examples/abop-1.24c.lsys",
        axiom: "F",
        rules: &[('F', "FF-[-F+F+F]+[+F-F-F]")],
        n: 4,
        delta: 22.5,
        drawn: 4096, // 8^4
    },
    Figure {
        file: "examples/abop-1.24d.lsys",
        axiom: "X",
        rules: &[('X', "F[+X]F[-X]+X"), ('F', "FF")],
        n: 7,
        delta: 20.0,
        // X_k = 3^k, F_k+1 = 2 F_k + 2 X_k: 0, 2, 10, 38, 130, 422, 1330, 4118.
        drawn: 4118,
    },
    Figure {
        file: "examples/abop-1.24e.lsys",
        axiom: "X",
        rules: &[('X', "F[+X][-X]FX"), ('F', "FF")],
        n: 7,
        delta: 25.7,
        drawn: 4118, // as (d): three X and two F per X
    },
    Figure {
        file: "examples/abop-1.24f.lsys",
        axiom: "X",
        rules: &[('X', "F-[[X]+X]+F[+FX]-X"), ('F', "FF")],
        n: 5,
        delta: 22.5,
        // X_k = 4^k, F_k+1 = 2 F_k + 3 X_k: 0, 3, 18, 84, 360, 1488.
        drawn: 1488,
    },
];

#[test]
fn figure_1_24a_builds_five_to_the_fifth_parts() {
    let lsys = LSystem::from_path(std::path::Path::new("examples/abop-1.24a.lsys")).unwrap();
    let c = plant(&lsys, 10_000);
    assert_eq!(c.parts.len(), 3125);
    // Rigidly joined, as `forward` parts are: one joint per part but the first.
    assert_eq!(c.joints.len(), 3124);
    assert!(c.joints.iter().all(|j| j.kind == JointKind::Rigid));
    // The main axis is 3^5 segments of length 1, standing up.
    let (lo, hi) = c.bounding_box();
    assert!((hi.y - 243.0).abs() < 1e-9, "{hi}");
    assert!(lo.y.abs() < 1e-9, "{lo}");
}

#[test]
fn each_figure_1_24_builds_the_parts_and_box_of_a_turtle_written_here() {
    for figure in &FIGURES {
        let lsys = LSystem::from_path(std::path::Path::new(figure.file)).unwrap();
        assert_eq!(
            lsys.derivation_length(),
            Some(figure.n as u64),
            "{}",
            figure.file
        );
        assert_eq!(lsys.turtle().angle, Some(figure.delta), "{}", figure.file);
        let c = plant(&lsys, 10_000);
        let (distinct, lo, hi) =
            textbook_turtle(figure.axiom, figure.rules, figure.n, figure.delta);
        let string = lsys
            .derivation(&DeriveOptions::default())
            .map(|mut d| {
                for _ in 0..figure.n {
                    d.step().unwrap();
                }
                lsys.display(d.current())
            })
            .unwrap();
        assert_eq!(
            string.matches('F').count(),
            figure.drawn,
            "{}: the F's of the string",
            figure.file
        );
        assert_eq!(c.parts.len(), distinct, "{}: built parts", figure.file);
        assert!(c.is_valid(), "{}: {:?}", figure.file, c.problems);
        // The box of the parts' end points is the turtle's, in the plane z = 0.
        let (mut min, mut max) = (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(-f64::INFINITY),
        );
        for k in 0..c.parts.len() {
            let (a, b) = ends(&c, k);
            min = min.inf(&a).inf(&b);
            max = max.sup(&a).sup(&b);
        }
        let close = |a: f64, b: f64| (a - b).abs() < 1e-6;
        assert!(
            close(min.x, lo[0])
                && close(min.y, lo[1])
                && close(max.x, hi[0])
                && close(max.y, hi[1]),
            "{}: {min} to {max} against ({lo:?}) to ({hi:?})",
            figure.file
        );
        assert!(close(min.z, 0.0) && close(max.z, 0.0), "{}", figure.file);
    }
    // The counts the example files' comments give.
    let counts: Vec<usize> = FIGURES
        .iter()
        .map(|f| textbook_turtle(f.axiom, f.rules, f.n, f.delta).0)
        .collect();
    assert_eq!(counts, [3125, 1760, 3344, 4118, 4118, 1002]);
}

#[test]
fn the_stochastic_plant_and_the_bush_stand_up_and_build() {
    let stochastic =
        LSystem::from_path(std::path::Path::new("examples/stochastic-plant.lsys")).unwrap();
    let c = plant(&stochastic, 10_000);
    assert_eq!(c.parts.len(), 631);
    let (_, hi) = c.bounding_box();
    assert!(hi.y > 50.0, "{hi}");
    let bush = LSystem::from_path(std::path::Path::new("examples/abop-1.25-bush.lsys")).unwrap();
    let c = plant(&bush, 10_000);
    // A_k = 3^k, F_k+1 = A_k + F_k + S_k, S_k+1 = F_k: 3,891 internodes after 7 steps.
    assert_eq!(c.parts.len(), 3891);
    let (lo, hi) = c.bounding_box();
    // In three dimensions: its branches spread along both x and z.
    assert!(hi.x - lo.x > 10.0 && hi.z - lo.z > 10.0, "{lo} to {hi}");
    // Each level of branches is thinner by the documented factor: the seventh, the last
    // that has parts, is 0.4 × 0.7^6 wide.
    let thinnest = c
        .parts
        .iter()
        .map(|p| p.size.z)
        .fold(f64::INFINITY, f64::min);
    assert!(
        (thinnest - 0.4 * 0.7f64.powi(6)).abs() < 1e-12,
        "{thinnest}"
    );
}

#[test]
fn f_plus_f_at_90_degrees_puts_the_second_part_on_the_turtles_left() {
    // Lying on the ground along +x, up +y: the left is −z.
    let c = built("angle: 90\naxiom: F+F\n");
    assert!(
        near(c.parts[1].position, [1.0, 0.0, -0.5]),
        "{}",
        c.parts[1].position
    );
    // Heading up, as in the textbook's pictures: the left is −x.
    let c = built("heading: up\nangle: 90\naxiom: F+F\n");
    assert!(
        near(c.parts[0].position, [0.0, 0.5, 0.0]),
        "{}",
        c.parts[0].position
    );
    assert!(
        near(c.parts[1].position, [-0.5, 1.0, 0.0]),
        "{}",
        c.parts[1].position
    );
    // `-` turns right; an explicit angle overrides the file's.
    let c = built("heading: up\nangle: 10\naxiom: F-(90)F\n");
    assert!(
        near(c.parts[1].position, [0.5, 1.0, 0.0]),
        "{}",
        c.parts[1].position
    );
}

#[test]
fn pitch_roll_and_turn_around_follow_the_textbook() {
    // & pitches down, ^ up (about the turtle's left).
    let c = built("angle: 90\naxiom: F&F\n");
    assert!(
        near(c.parts[1].position, [1.0, -0.5, 0.0]),
        "{}",
        c.parts[1].position
    );
    let c = built("angle: 90\naxiom: F^F\n");
    assert!(
        near(c.parts[1].position, [1.0, 0.5, 0.0]),
        "{}",
        c.parts[1].position
    );
    // / rolls right: the up turns to where the right was, so a left turn then goes up.
    let c = built("angle: 90\naxiom: F/+F\n");
    assert!(
        near(c.parts[1].position, [1.0, 0.5, 0.0]),
        "{}",
        c.parts[1].position
    );
    // \ rolls left: a left turn then goes down.
    let c = built("angle: 90\naxiom: F\\+F\n");
    assert!(
        near(c.parts[1].position, [1.0, -0.5, 0.0]),
        "{}",
        c.parts[1].position
    );
    // | turns around, whatever the angle.
    let c = built("angle: 30\naxiom: F|F\n");
    assert!(
        near(c.parts[1].position, [0.5, 0.0, 0.0]),
        "{}",
        c.parts[1].position
    );
    // Without `angle:` the textbook's turns are quarter turns.
    let c = built("axiom: F+F\n");
    assert!(
        near(c.parts[1].position, [1.0, 0.0, -0.5]),
        "{}",
        c.parts[1].position
    );
}

#[test]
fn step_sets_the_length_of_f_and_not_of_forward() {
    let c = built("step: 2\naxiom: F forward F(0.5)\n");
    let lengths: Vec<f64> = c.parts.iter().map(|p| p.size.x).collect();
    assert_eq!(lengths, [2.0, 1.0, 0.5]);
}

#[test]
fn a_bang_sets_the_width_and_a_bare_bang_makes_it_thinner() {
    let c = built("axiom: !(0.3) F ! F !(0.5) F\n");
    let sizes: Vec<(f64, f64)> = c.parts.iter().map(|p| (p.size.y, p.size.z)).collect();
    assert_eq!(sizes[0], (0.3, 0.3));
    assert!((sizes[1].0 - 0.21).abs() < 1e-12 && (sizes[1].1 - 0.21).abs() < 1e-12);
    assert_eq!(sizes[2], (0.5, 0.5));
}

#[test]
fn f_parts_are_rigid_unless_a_joint_command_comes_before_them() {
    let c = built("axiom: F revolute1 F forward F twist90 F\n");
    let kinds: Vec<JointKind> = c.joints.iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Revolute,
            JointKind::Rigid,
            JointKind::Rigid,
            JointKind::Twist
        ]
    );
    assert!(c.is_valid(), "{:?}", c.problems);
}

#[test]
fn a_gap_left_by_f_is_a_warning_in_a_picture_and_an_error_for_physics() {
    let lsys = lsystem("axiom: F f F\n");
    let message = "the body is in 2 pieces: 'f' moves the turtle without building and leaves \
                   a gap";
    let picture = plant(&lsys, 200);
    assert_eq!(picture.parts.len(), 2);
    assert!(near(picture.parts[1].position, [2.5, 0.0, 0.0]));
    assert!(picture.joints.is_empty());
    assert_eq!(picture.problems.len(), 1, "{:?}", picture.problems);
    assert_eq!(picture.problems[0].severity, Severity::Warning);
    assert_eq!(
        picture.problems[0].message,
        format!("{message} (fine for a picture; an error for eval and evolve)")
    );
    assert_eq!(picture.problems[0].module.as_deref(), Some("f"));
    assert!(picture.is_valid());
    let physics = plant_for_physics(&lsys);
    assert_eq!(physics.problems[0].severity, Severity::Error);
    assert_eq!(physics.problems[0].message, message);
    assert!(!physics.is_valid());
}

#[test]
fn thick_parts_that_overlap_are_a_warning_in_a_picture_and_an_error_for_physics() {
    // Two thick parts from one point at 25.7°: their sides cross.
    let lsys = lsystem("angle: 25.7\naxiom: !(0.5) F [+F] [-F]\n");
    let picture = plant(&lsys, 200);
    let shown: Vec<(Severity, &str)> = picture
        .problems
        .iter()
        .map(|p| (p.severity, p.message.as_str()))
        .collect();
    assert_eq!(
        shown,
        [(
            Severity::Warning,
            "parts 1 and 2 interpenetrate (fine for a picture; an error for eval and evolve)"
        )]
    );
    let physics = plant_for_physics(&lsys);
    assert_eq!(physics.problems[0].severity, Severity::Error);
    assert!(!physics.is_valid());
}

#[test]
fn many_overlapping_pairs_are_one_problem_that_counts_them() {
    let lsys = LSystem::from_path(std::path::Path::new("examples/abop-1.24a.lsys")).unwrap();
    let c = plant(&lsys, 10_000);
    let overlaps: Vec<&str> = c
        .problems
        .iter()
        .filter(|p| p.message.contains("interpenetrate"))
        .map(|p| p.message.as_str())
        .collect();
    assert_eq!(
        overlaps,
        [
            "1562 pairs of parts interpenetrate (parts 1 and 2, 3 and 4, 5 and 10, 6 and 7, 8 \
             and 9, ...) (fine for a picture; an error for eval and evolve)"
        ]
    );
}

#[test]
fn textbook_symbols_left_out_are_refused_by_name_at_their_place() {
    let dir = scratch_dir("textbook-unsupported");
    for (text, message, place) in [
        (
            "axiom: F'F\n",
            "''' is the textbook's symbol for the colour index, which Ontogeny does not support",
            "t.lsys:1:9",
        ),
        (
            "axiom: A\nA --> F$F\n",
            "'$' is the textbook's symbol for rolling the turtle to the horizontal, which \
             Ontogeny does not support",
            "t.lsys:2:8",
        ),
        (
            "axiom: A\nA --> {F-F}\n",
            "'{ … }' without a count is the textbook's polygon, which Ontogeny does not \
             support; a repeat block is written '{ … }(n)'",
            "t.lsys:2:11",
        ),
        (
            "axiom: F }\n",
            "'}' closes no '{': a repeat block is written '{ … }(n)'",
            "t.lsys:1:10",
        ),
    ] {
        let file = dir.join("t.lsys");
        std::fs::write(&file, text).unwrap();
        let path = file.to_str().unwrap();
        for verb in ["check", "grow", "derive"] {
            let said = assert_bad_input(&[verb, path], message);
            assert!(said.contains(place), "{verb} {text:?}: {said}");
        }
    }
    // A repeat block keeps its meaning.
    let c = built("axiom: { F }(3)\n");
    assert_eq!(c.parts.len(), 3);
}

#[test]
fn the_shipped_plants_pass_check_without_findings() {
    for file in [
        "examples/abop-1.24a.lsys",
        "examples/abop-1.24b.lsys",
        "examples/abop-1.24c.lsys",
        "examples/abop-1.24d.lsys",
        "examples/abop-1.24e.lsys",
        "examples/abop-1.24f.lsys",
        "examples/abop-1.25-bush.lsys",
        "examples/stochastic-plant.lsys",
    ] {
        let said = stdout(&ontogeny_ok(&["check", file]));
        assert!(said.contains("findings: none"), "{file}: {said}");
    }
    // The one-letter notation is silent; a word that is no name is still pointed out.
    let dir = scratch_dir("textbook-check");
    let file = dir.join("tial.lsys");
    std::fs::write(&file, "axiom: A\nA --> FF Tial\n").unwrap();
    let said = stdout(&ontogeny_ok(&["check", file.to_str().unwrap()]));
    assert!(
        said.contains("'Tial' is read as the modules T i a l"),
        "{said}"
    );
    assert!(!said.contains("'FF'"), "{said}");
}

#[test]
fn grow_and_view_take_max_parts_for_plants_of_thousands_of_parts() {
    let said = stdout(&ontogeny_ok(&[
        "grow",
        "examples/abop-1.24a.lsys",
        "--max-parts",
        "5000",
    ]));
    assert!(said.contains("parts: 3125 "), "{said}");
    assert!(
        said.contains("valid: as a picture only (eval and evolve refuse it)"),
        "{said}"
    );
    assert!(
        said.contains("warning: 1562 pairs of parts interpenetrate"),
        "{said}"
    );
    // The default limit stops a plant with a clear error.
    let said = stdout(&ontogeny_ok(&["grow", "examples/abop-1.24a.lsys"]));
    assert!(
        said.contains("error: more than 200 parts (--max-parts): building stopped here"),
        "{said}"
    );
    let help = stdout(&ontogeny_ok(&["view", "--help"]));
    assert!(help.contains("--max-parts <MAX_PARTS>"), "{help}");
}

#[test]
fn eval_counts_a_plants_overlapping_pairs_and_names_the_part_limit_it_met() {
    // 1,562 pairs: counted, the first five named, not listed one by one.
    let said = stdout(&ontogeny_ok(&[
        "eval",
        "examples/abop-1.24a.lsys",
        "--max-parts",
        "5000",
    ]));
    assert!(
        said.contains(
            "fitness -999999.000000 (self-intersecting)\n  1562 pairs of parts interpenetrate \
             (parts 1 and 2, 3 and 4, 5 and 10, 6 and 7, 8 and 9, ...)\n"
        ),
        "{said}"
    );
    // At the default limit, the limit it met is said too.
    let said = stdout(&ontogeny_ok(&["eval", "examples/abop-1.24a.lsys"]));
    assert!(
        said.contains("...); more than 200 parts (--max-parts): building stopped here\n"),
        "{said}"
    );
}

#[test]
fn a_part_limit_of_zero_is_refused_by_every_verb_that_builds() {
    for verb in ["grow", "eval", "export", "view"] {
        assert_bad_input(
            &[verb, "examples/abop-1.24a.lsys", "--max-parts", "0"],
            "a creature has at least one part: give 1 or more",
        );
    }
}
