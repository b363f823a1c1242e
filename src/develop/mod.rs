//! Development: interpreting a module string as building commands — a 3D turtle that builds
//! the body (Hornby & Pollack's command set with Matos & Arita's maturing `m` twins) and an
//! edge-encoding builder that wires the brain — into a [`Creature`].
//!
//! The turtle carries a frame: its heading is its local x axis, its up its local y, and its
//! right-hand side its local z. It starts at the origin heading along +x, lying on the
//! ground (its up is the world's up, +y); a file's `heading: up` starts it heading up (+y),
//! its up along +z (towards the pictures' camera), its right along +x. Ontogeny's turns (`left(n)`, ...) are quarter turns; the textbook's
//! (`+(δ)`, ...) are in degrees, by default the file's `angle:`.

mod brain;
mod command;
pub mod growth;
mod seedling;
mod shortcut;

use nalgebra::{Unit, UnitQuaternion, Vector3};

use crate::creature::{Creature, Joint, JointKind, Part, Problem, Severity};
use crate::environment::Environment;
use crate::lang::ast::Heading;
use crate::lsystem::{ModuleString, SymbolTable, TurtleHeaders};
use crate::number::format_number;
pub use command::{Action, command_of};
pub use growth::{ATTACHMENT_TOLERANCE, Growth, GrowthEvent, growth_between, growth_from_string};
pub use seedling::Seedling;
pub use shortcut::{LastFrame, Shortcut, grow_last};

use brain::BrainBuilder;

/// Parts shorter than this (in metres) are not built: an `mforward` this short is a bud, a
/// `forward` this short is ignored with a warning. Far above the round-off of continuous
/// development (a bud born at an event a few units of round-off before a frame has grown
/// about 1e-13 by then) and far below any part the simulator can use.
pub const MIN_PART_LENGTH: f64 = 1e-6;

/// The most modules repeat blocks may make the builder interpret beyond the string's own
/// length (a block's second and later passes, over all blocks): past it the creature is
/// invalid and building stops, so that nested blocks of commands that make no part (turns,
/// brain commands) cannot run for years. `{ { ... }(100) }(100)` over 100 modules is this.
pub const MAX_REPEATED_MODULES: usize = 1_000_000;

/// What a bare `!` multiplies the width and thickness of the next parts by.
pub const DIAMETER_FACTOR: f64 = 0.7;

/// The textbook turtle's default angle (degrees) when a file has no `angle:`.
pub const DEFAULT_ANGLE: f64 = 90.0;

/// Builder settings, and the token that stops a growth.
#[derive(Clone, Debug)]
pub struct BuildOptions {
    /// More parts than this is an error (the creature is invalid).
    pub max_parts: usize,
    /// Width of parts before any `width` command (their local z size).
    pub default_width: f64,
    /// Thickness of parts before any `thickness` command (their local y size).
    pub default_thickness: f64,
    /// Length made by `forward` with no parameter.
    pub default_length: f64,
    /// Most repetitions of one `{ ... }(n)` block.
    pub max_repeat: usize,
    /// The most modules repeat blocks may make the builder interpret beyond the string's
    /// own length (a block's second and later passes, over all blocks): past it the creature
    /// is invalid and building stops. [`MAX_REPEATED_MODULES`] by default; a genome sets it
    /// lower, so that its development's work stays within its own budget.
    pub max_repeated_modules: usize,
    /// The textbook turtle's settings (a file's `angle:`, `step:`, `heading:`; see
    /// [`BuildOptions::with_headers`]).
    pub turtle: TurtleHeaders,
    /// Built for a picture, not for physics: parts that overlap and a body in several
    /// pieces (after `f`) are warnings, not errors.
    pub for_picture: bool,
    /// Set, it stops a growth before its next frame ([`for_each_growth_frame`]) with a
    /// diagnostic of kind [`Interrupted`](crate::lang::DiagnosticKind::Interrupted).
    pub cancel: crate::cancel::Cancel,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            max_parts: 200,
            default_width: 0.25,
            default_thickness: 0.25,
            default_length: 1.0,
            max_repeat: 100,
            max_repeated_modules: MAX_REPEATED_MODULES,
            turtle: TurtleHeaders::default(),
            for_picture: false,
            cancel: crate::cancel::Cancel::default(),
        }
    }
}

impl BuildOptions {
    /// These options with the textbook turtle's settings of `lsys`'s file.
    pub fn with_headers(&self, lsys: &crate::lsystem::LSystem) -> BuildOptions {
        BuildOptions {
            turtle: lsys.turtle(),
            ..self.clone()
        }
    }

    /// The textbook turns' default angle, in degrees.
    fn angle(&self) -> f64 {
        self.turtle.angle.unwrap_or(DEFAULT_ANGLE)
    }

    /// The textbook `F` and `f`'s default length.
    fn step(&self) -> f64 {
        self.turtle.step.unwrap_or(self.default_length)
    }

    /// A problem that only physics cares about, as these options report it: an error, or
    /// in a picture a warning that says it is an error for physics.
    fn physics_problem(&self, message: String) -> (Severity, String) {
        if self.for_picture {
            (
                Severity::Warning,
                format!("{message}{}", crate::creature::Problem::PICTURE_ONLY),
            )
        } else {
            (Severity::Error, message)
        }
    }
}

/// The joint the next `forward` makes.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PendingJoint {
    kind: JointKind,
    /// Limits of the single degree of freedom.
    limits: (f64, f64),
    growing: bool,
}

/// Everything `[` saves and `]` restores.
#[derive(Clone, Debug)]
struct TurtleState {
    position: Vector3<f64>,
    orientation: UnitQuaternion<f64>,
    part: Option<usize>,
    pending: Option<PendingJoint>,
    width: f64,
    thickness: f64,
    link: brain::CurrentLink,
    /// `f` moved the turtle: the next part starts a new piece, joined to nothing.
    gap: bool,
}

/// Builds a creature from a module string.
pub struct Builder<'a> {
    symbols: &'a SymbolTable,
    options: &'a BuildOptions,
    /// Developmental time of the string, for problem reports.
    t: Option<f64>,
    creature: Creature,
    /// For each part, the part it grew from.
    parents: Vec<Option<usize>>,
    /// For each part, the point where the turtle left it (its far end).
    ends: Vec<Vector3<f64>>,
    /// For each part, the joint that attaches it to its parent.
    joint_of: Vec<Option<usize>>,
    state: TurtleState,
    stack: Vec<TurtleState>,
    brain: BrainBuilder,
    commands: Vec<Option<Action>>,
    /// For each `{` of the string, the index of its `}` (bracket matching, done once).
    closes: Vec<Option<usize>>,
    /// Modules interpreted so far, and the most allowed (the string's length plus
    /// [`BuildOptions::max_repeated_modules`]).
    interpreted: usize,
    most_interpreted: usize,
    /// Set when the part limit is passed: the creature is invalid and building stops at
    /// once (the rest of the string is not interpreted, so the work stays bounded by the
    /// limit however long the string is).
    stopped: bool,
    /// The pieces the body is in beyond the first (parts after an `f`), and the first `f`
    /// that made one.
    pieces: usize,
    first_gap: Option<String>,
}

/// Builds the creature a frame of `lsys`'s development shows: the frame's string through the
/// interpretation rules, built at the frame's time in its environment.
pub fn build_frame(
    lsys: &crate::lsystem::LSystem,
    frame: &crate::lsystem::Frame<'_>,
    options: &crate::lsystem::DeriveOptions,
    build_options: &BuildOptions,
) -> Result<Creature, crate::lang::Diagnostic> {
    let shown = lsys.interpret(frame.string, frame.t, options)?;
    Ok(build(
        &shown,
        lsys.symbols(),
        frame.env,
        Some(frame.t),
        build_options,
    ))
}

/// Builds the creature a module string describes. `t` is its developmental time (for
/// reports), `env` the environment it grew in.
pub fn build(
    string: &ModuleString,
    symbols: &SymbolTable,
    env: &Environment,
    t: Option<f64>,
    options: &BuildOptions,
) -> Creature {
    let mut builder = Builder::new(symbols, options, t, env.len());
    builder.closes = matching_closes(string, &builder.commands);
    builder.most_interpreted = string.len().saturating_add(options.max_repeated_modules);
    builder.run(string, 0, string.len(), 0);
    let mut creature = builder.finish();
    creature.environment = env.values().to_vec();
    creature
}

impl<'a> Builder<'a> {
    fn new(
        symbols: &'a SymbolTable,
        options: &'a BuildOptions,
        t: Option<f64>,
        environment_len: usize,
    ) -> Self {
        let brain = BrainBuilder::new(environment_len);
        let commands = (0..symbols.len() as u32)
            .map(|id| command_of(symbols.name(id)))
            .collect();
        Builder {
            symbols,
            options,
            t,
            creature: Creature::default(),
            parents: Vec::new(),
            ends: Vec::new(),
            joint_of: Vec::new(),
            state: TurtleState {
                position: Vector3::zeros(),
                orientation: match options.turtle.heading {
                    Heading::Ground => UnitQuaternion::identity(),
                    // Heading +y, up +z, right +x: a plane plant faces the pictures' camera.
                    Heading::Up => UnitQuaternion::from_basis_unchecked(&[
                        Vector3::y(),
                        Vector3::z(),
                        Vector3::x(),
                    ]),
                },
                part: None,
                pending: None,
                width: options.default_width,
                thickness: options.default_thickness,
                link: brain.initial_link(),
                gap: false,
            },
            stack: Vec::new(),
            brain,
            commands,
            closes: Vec::new(),
            interpreted: 0,
            most_interpreted: usize::MAX,
            stopped: false,
            pieces: 0,
            first_gap: None,
        }
    }

    fn problem(&mut self, severity: Severity, string: &ModuleString, i: usize, message: String) {
        let mut one = ModuleString::new();
        one.push(string.sym(i), string.params(i));
        self.creature.problems.push(Problem {
            severity,
            message,
            module: Some(one.display(self.symbols)),
            t: self.t,
        });
    }

    /// Interprets modules `from..to`; `depth` counts enclosing repeat blocks.
    fn run(&mut self, string: &ModuleString, from: usize, to: usize, depth: usize) {
        let mut i = from;
        while i < to && !self.stopped {
            self.interpreted += 1;
            if self.interpreted > self.most_interpreted {
                self.problem(
                    Severity::Error,
                    string,
                    i,
                    format!(
                        "repeat blocks make the builder interpret more than {} \
                         modules beyond the string's own: building stopped here",
                        self.options.max_repeated_modules
                    ),
                );
                self.stopped = true;
                break;
            }
            let Some(command) = self.commands[string.sym(i) as usize] else {
                i += 1;
                continue; // control tokens build nothing
            };
            let params = string.params(i);
            let arg = |default: f64| params.first().copied().unwrap_or(default);
            match command {
                Action::RepeatStart => {
                    let close = self.closes[i].filter(|&close| close < to);
                    let Some(close) = close else {
                        self.problem(
                            Severity::Warning,
                            string,
                            i,
                            "'{' has no matching '}': ignored".to_string(),
                        );
                        i += 1;
                        continue;
                    };
                    let n = string.params(close).first().copied().unwrap_or(1.0);
                    let times = if n.is_finite() && n > 0.0 {
                        n.floor() as usize
                    } else {
                        0
                    };
                    let times = if times > self.options.max_repeat || depth >= 8 {
                        self.problem(
                            Severity::Warning,
                            string,
                            close,
                            format!(
                                "repeat count {} is more than the {} allowed (or blocks nest more than 8 deep): capped",
                                format_number(n),
                                self.options.max_repeat
                            ),
                        );
                        if depth >= 8 {
                            1
                        } else {
                            self.options.max_repeat
                        }
                    } else {
                        times
                    };
                    for _ in 0..times {
                        self.run(string, i + 1, close, depth + 1);
                        if self.stopped {
                            break;
                        }
                    }
                    i = close + 1;
                    continue;
                }
                Action::RepeatEnd => {
                    self.problem(
                        Severity::Warning,
                        string,
                        i,
                        "'}' has no matching '{': ignored".to_string(),
                    );
                }
                Action::Push => self.stack.push(self.state.clone()),
                Action::Pop => match self.stack.pop() {
                    Some(state) => self.state = state,
                    None => self.problem(
                        Severity::Warning,
                        string,
                        i,
                        "']' with nothing to pop: ignored".to_string(),
                    ),
                },
                Action::Forward { maturing, textbook } => {
                    let length = if textbook {
                        arg(self.options.step())
                    } else {
                        arg(self.options.default_length)
                    };
                    self.forward(string, i, length, maturing);
                }
                Action::Move => self.move_without_building(string, i, arg(self.options.step())),
                Action::Backward => self.backward(string, i),
                Action::TurnAround => {
                    self.state.orientation *=
                        UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI);
                }
                Action::Turn {
                    axis,
                    sign,
                    degrees,
                } => {
                    let angle = if degrees {
                        sign * arg(self.options.angle()).to_radians()
                    } else {
                        sign * arg(1.0) * std::f64::consts::FRAC_PI_2
                    };
                    if !angle.is_finite() {
                        self.problem(
                            Severity::Warning,
                            string,
                            i,
                            "turn by a non-finite angle: ignored".into(),
                        );
                    } else {
                        let axis = Unit::new_normalize(axis);
                        self.state.orientation *= UnitQuaternion::from_axis_angle(&axis, angle);
                    }
                }
                Action::Joint {
                    kind,
                    limits,
                    maturing,
                } => {
                    self.state.pending = Some(PendingJoint {
                        kind,
                        limits,
                        growing: maturing,
                    })
                }
                Action::Width | Action::Thickness => {
                    let v = arg(f64::NAN);
                    if !(v.is_finite() && v > 0.0) {
                        self.problem(
                            Severity::Warning,
                            string,
                            i,
                            "width and thickness need a positive parameter: ignored".into(),
                        );
                    } else if command == Action::Width {
                        self.state.width = v;
                    } else {
                        self.state.thickness = v;
                    }
                }
                Action::Diameter => match params.first() {
                    None => {
                        self.state.width *= DIAMETER_FACTOR;
                        self.state.thickness *= DIAMETER_FACTOR;
                    }
                    Some(&w) if w.is_finite() && w > 0.0 => {
                        self.state.width = w;
                        self.state.thickness = w;
                    }
                    Some(_) => self.problem(
                        Severity::Warning,
                        string,
                        i,
                        "'!' needs a positive width: ignored".into(),
                    ),
                },
                Action::Brain(op) => {
                    let joint = self.state.part.and_then(|p| self.joint_of[p]);
                    let joint_info = joint.map(|j| (j, self.creature.joints[j].kind.dof()));
                    let outcome = self.brain.apply(
                        op,
                        params,
                        &mut self.state.link,
                        self.state.part,
                        joint_info,
                    );
                    if let Err(message) = outcome {
                        self.problem(Severity::Warning, string, i, message);
                    }
                }
            }
            i += 1;
        }
    }

    fn forward(&mut self, string: &ModuleString, i: usize, length: f64, maturing: bool) {
        if maturing && length.abs() < MIN_PART_LENGTH {
            return; // a bud that has not started to grow (or has grown only round-off)
        }
        if !(length.is_finite() && length > 0.0) {
            self.problem(
                Severity::Warning,
                string,
                i,
                format!(
                    "forward needs a positive length, not {}: ignored",
                    format_number(length)
                ),
            );
            return;
        }
        if length < MIN_PART_LENGTH {
            self.problem(
                Severity::Warning,
                string,
                i,
                format!(
                    "forward({}) is shorter than the shortest part, {MIN_PART_LENGTH:e} m: ignored",
                    format_number(length)
                ),
            );
            return;
        }
        let heading = self.state.orientation * Vector3::x();
        let start = self.state.position;
        let size = Vector3::new(length, self.state.thickness, self.state.width);
        let centre = start + heading * (length / 2.0);
        let parent = if self.state.gap {
            None
        } else {
            self.state.part.or(if self.creature.parts.is_empty() {
                None
            } else {
                Some(0)
            })
        };

        // An identical part already there: move onto it (Hornby).
        if let Some(existing) = (0..self.creature.parts.len()).find(|&k| {
            let p = &self.creature.parts[k];
            self.parents[k] == parent
                && (p.position - centre).norm() < 1e-9
                && (p.size - size).norm() < 1e-9
                && p.orientation.angle_to(&self.state.orientation) < 1e-9
        }) {
            self.state.part = Some(existing);
            self.state.position = self.ends[existing];
            if self.state.pending.take().is_some() {
                self.problem(
                    Severity::Warning,
                    string,
                    i,
                    "the turtle moved onto an existing part: the pending joint command is ignored"
                        .into(),
                );
            }
            return;
        }

        let index = self.creature.parts.len();
        self.creature.parts.push(Part {
            size,
            position: centre,
            orientation: self.state.orientation,
            density: crate::creature::DEFAULT_DENSITY,
            growing: maturing,
        });
        self.parents.push(parent);
        self.ends.push(start + heading * length);
        self.joint_of.push(None);
        if index == self.options.max_parts {
            self.problem(
                Severity::Error,
                string,
                i,
                format!(
                    "more than {} parts (--max-parts): building stopped here",
                    self.options.max_parts
                ),
            );
            self.stopped = true;
        }
        if let Some(parent) = parent {
            let pending = self.state.pending.take();
            let (kind, axes, limits, growing) = match pending {
                Some(p) => {
                    let local = if p.kind == JointKind::Twist {
                        Vector3::x()
                    } else {
                        Vector3::z()
                    };
                    (
                        p.kind,
                        vec![self.state.orientation * local],
                        vec![p.limits],
                        p.growing,
                    )
                }
                None => (JointKind::Rigid, Vec::new(), Vec::new(), false),
            };
            self.joint_of[index] = Some(self.creature.joints.len());
            self.creature.joints.push(Joint {
                parent,
                child: index,
                kind,
                anchor: start,
                axes,
                limits,
                strength: 1.0,
                growing: growing || maturing,
            });
        } else {
            if index > 0 {
                self.pieces += 1;
            }
            if self.state.pending.take().is_some() {
                self.problem(
                    Severity::Warning,
                    string,
                    i,
                    "the first part of a piece has nothing to be jointed to: its joint command \
                     is ignored"
                        .into(),
                );
            }
        }
        self.state.gap = false;
        self.state.part = Some(index);
        self.state.position = start + heading * length;
    }

    /// `f(l)`: moves the turtle `length` along its heading without building; the next part
    /// starts a new piece of the body.
    fn move_without_building(&mut self, string: &ModuleString, i: usize, length: f64) {
        if !length.is_finite() {
            self.problem(
                Severity::Warning,
                string,
                i,
                "f needs a finite length: ignored".into(),
            );
            return;
        }
        let heading = self.state.orientation * Vector3::x();
        self.state.position += heading * length;
        self.state.gap = true;
        if self.first_gap.is_none() {
            let mut one = ModuleString::new();
            one.push(string.sym(i), string.params(i));
            self.first_gap = Some(one.display(self.symbols));
        }
    }

    fn backward(&mut self, string: &ModuleString, i: usize) {
        match self.state.part.and_then(|p| self.parents[p]) {
            Some(parent) => {
                self.state.part = Some(parent);
                self.state.position = self.ends[parent];
            }
            None => self.problem(
                Severity::Warning,
                string,
                i,
                "backward on the root part: ignored".into(),
            ),
        }
    }

    fn finish(mut self) -> Creature {
        // A build stopped at the part limit leaves branches open: not the string's fault.
        if !self.stack.is_empty() && !self.stopped {
            self.creature.problems.push(Problem {
                severity: Severity::Warning,
                message: format!(
                    "{} '[' without a matching ']': each branch runs to the end of the string",
                    self.stack.len()
                ),
                module: None,
                t: self.t,
            });
        }
        if self.pieces > 0 {
            let (severity, message) = self.options.physics_problem(format!(
                "the body is in {} pieces: 'f' moves the turtle without building and leaves a gap",
                self.pieces + 1
            ));
            self.creature.problems.push(Problem {
                severity,
                message,
                module: self.first_gap.take(),
                t: self.t,
            });
        }
        self.creature.brain = self.brain.finish();
        overlap::report(&mut self.creature, self.t, self.options);
        self.creature
    }
}

/// For each module of `string` that is a `{`, the index of the `}` that closes it (the first
/// `}` after it at the same depth), if any: bracket matching in one pass.
fn matching_closes(string: &ModuleString, commands: &[Option<Action>]) -> Vec<Option<usize>> {
    let mut closes = vec![None; string.len()];
    let mut open = Vec::new();
    for k in 0..string.len() {
        match commands[string.sym(k) as usize] {
            Some(Action::RepeatStart) => open.push(k),
            Some(Action::RepeatEnd) => {
                if let Some(start) = open.pop() {
                    closes[start] = Some(k);
                }
            }
            _ => {}
        }
    }
    closes
}

mod overlap;

/// Builds the creature a string of commands describes (written as an axiom would be, e.g.
/// `"forward(1) revolute2 forward(1) output(1)"`), with default options.
pub fn creature_from_commands(commands: &str) -> Result<Creature, crate::lang::Diagnostic> {
    let lsys = crate::lsystem::LSystem::from_text("commands", &format!("axiom: {commands}\n"))?;
    Ok(build(
        lsys.axiom(),
        lsys.symbols(),
        &Environment::default(),
        None,
        &BuildOptions::default().with_headers(&lsys),
    ))
}

/// One frame of growth: the creature built from the string at one observation time.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GrowthFrame {
    /// The derivation step or observation index.
    pub step: u64,
    /// Developmental time (the step number in discrete mode).
    pub t: f64,
    /// The creature at that time.
    pub creature: Creature,
}

/// The most frames of growth a verb keeps (`grow --out`'s `frames.jsonl` and
/// `growth.gif`, the viewer's page): a growth of more frames is refused before anything is
/// derived, so that what is kept stays bounded whatever the derivation length. Verbs that
/// need only the last creature ([`grow_last`]) keep one frame and have no such limit.
pub const MAX_KEPT_FRAMES: u64 = 10_000;

/// The frames growing `lsys` with these settings shows (see [`LSystem::frame_plan`]),
/// refused when there are more than [`MAX_KEPT_FRAMES`] of them.
///
/// [`LSystem::frame_plan`]: crate::lsystem::LSystem::frame_plan
pub fn kept_frame_plan(
    lsys: &crate::lsystem::LSystem,
    options: &crate::lsystem::DeriveOptions,
    steps: Option<u64>,
) -> Result<crate::lsystem::FramePlan, crate::lang::Diagnostic> {
    let plan = lsys.frame_plan(options, steps)?;
    if plan.frame_count() > MAX_KEPT_FRAMES {
        let how = if options.time.is_some() || lsys.is_continuous() {
            "lower 'time:' or raise 'dt:' (or pass --time, --dt)"
        } else {
            "lower 'derivation length:' (or pass --steps)"
        };
        return Err(crate::lang::Diagnostic::without_location(
            crate::lang::DiagnosticKind::Semantic,
            format!(
                "{}: growing it makes {} frames, more than the {MAX_KEPT_FRAMES} kept for \
                 `grow --out` and the viewer: {how}",
                lsys.source().name(),
                plan.frame_count()
            ),
        ));
    }
    Ok(plan)
}

/// Grows `lsys` frame by frame, as [`grow`] does, keeping nothing: every frame's string is
/// interpreted (an error at any frame is an error), the frames `wanted(step, last)` asks
/// for are built and shown to `visit` in order, and `progress` is told the fraction of the
/// frames done after each one. Memory stays that of one frame whatever the derivation
/// length. `build_options.cancel`, set, stops it before the next frame.
pub fn for_each_growth_frame<E: From<crate::lang::Diagnostic>>(
    lsys: &crate::lsystem::LSystem,
    options: &crate::lsystem::DeriveOptions,
    steps: Option<u64>,
    build_options: &BuildOptions,
    mut wanted: impl FnMut(u64, bool) -> bool,
    progress: &mut dyn FnMut(f64),
    mut visit: impl FnMut(GrowthFrame) -> Result<(), E>,
) -> Result<(), E> {
    let build_options = &build_options.with_headers(lsys);
    lsys.for_each_frame(options, steps, |frame| {
        build_options
            .cancel
            .check()
            .map_err(crate::lang::Diagnostic::from)?;
        let fraction = frame.fraction();
        if wanted(frame.step, frame.last) {
            visit(GrowthFrame {
                step: frame.step,
                t: frame.t,
                creature: build_frame(lsys, &frame, options, build_options)?,
            })?;
        } else {
            // Every frame's string is interpreted: an error at any frame is an error.
            lsys.interpret(frame.string, frame.t, options)?;
        }
        progress(fraction);
        Ok(())
    })
}

/// Grows `lsys` and builds one creature per frame: every derivation step in discrete mode
/// (`steps`, default the file's derivation length), every observation time in continuous
/// mode (a file with `time:`, or `options.time`). The interpretation rules are applied before
/// building. More than [`MAX_KEPT_FRAMES`] frames is refused before deriving (see
/// [`kept_frame_plan`]); [`grow_last`] and [`for_each_growth_frame`] keep no frames and have
/// no such limit.
pub fn grow(
    lsys: &crate::lsystem::LSystem,
    options: &crate::lsystem::DeriveOptions,
    steps: Option<u64>,
    build_options: &BuildOptions,
) -> Result<Vec<GrowthFrame>, crate::lang::Diagnostic> {
    grow_with_progress(lsys, options, steps, build_options, &mut |_| {})
}

/// [`grow`], telling `progress` the fraction of the frames built after each one (1 after
/// the last).
pub fn grow_with_progress(
    lsys: &crate::lsystem::LSystem,
    options: &crate::lsystem::DeriveOptions,
    steps: Option<u64>,
    build_options: &BuildOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Vec<GrowthFrame>, crate::lang::Diagnostic> {
    kept_frame_plan(lsys, options, steps)?;
    let mut frames = Vec::new();
    for_each_growth_frame(
        lsys,
        options,
        steps,
        build_options,
        |_, _| true,
        progress,
        |frame| {
            frames.push(frame);
            Ok::<(), crate::lang::Diagnostic>(())
        },
    )?;
    Ok(frames)
}
