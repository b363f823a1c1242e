//! Every neuron function on known inputs (Hornby & Pollack, Matos & Arita, Chaumont et al.'s
//! Table I, Walking with Dinosaurs section 3.2).

use ontogeny::creature::{Actuator, Brain, Link, Neuron, NeuronFunction, Role, Sensor};
use ontogeny::sim::{BrainRuntime, SimOptions};
use ontogeny::task::{self, Status, WalkerOptions};
use proptest::prelude::*;

const DT: f64 = 1.0 / 60.0;

/// Neurons 0..inputs are sensors feeding neuron `inputs` (of `function`) with `weights`.
fn brain(function: NeuronFunction, params: &[f64], weights: &[f64]) -> Brain {
    biased_brain(function, params, 0.0, weights)
}

/// As [`brain`], the last neuron holding `bias`.
fn biased_brain(function: NeuronFunction, params: &[f64], bias: f64, weights: &[f64]) -> Brain {
    let sensor = |i| Neuron {
        function: NeuronFunction::Linear,
        params: vec![],
        bias: 0.0,
        role: Role::Sensor {
            sensor: Sensor::Chemical { slot: i },
        },
        part: None,
    };
    let mut neurons: Vec<Neuron> = (0..weights.len()).map(sensor).collect();
    neurons.push(Neuron {
        function,
        params: params.to_vec(),
        bias,
        role: Role::Hidden,
        part: None,
    });
    let target = weights.len();
    let links = weights
        .iter()
        .enumerate()
        .map(|(i, &w)| Link {
            from: i,
            to: target,
            weight: w,
        })
        .collect();
    Brain { neurons, links }
}

/// The neuron's output after one update with sensor readings `values` (weights 1).
fn output(function: NeuronFunction, params: &[f64], values: &[f64]) -> f64 {
    weighted_output(function, params, 0.0, values, &vec![1.0; values.len()])
}

/// The neuron's output after one update with sensor readings `values`, `weights` and `bias`.
fn weighted_output(
    function: NeuronFunction,
    params: &[f64],
    bias: f64,
    values: &[f64],
    weights: &[f64],
) -> f64 {
    let b = biased_brain(function, params, bias, weights);
    let mut run = BrainRuntime::new(&b);
    for (i, v) in values.iter().enumerate() {
        run.set_sensor(i, *v);
    }
    run.step(0.5, DT);
    run.outputs()[values.len()]
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

#[test]
fn hornby_and_matos_functions() {
    use NeuronFunction::*;
    assert!(near(output(Linear, &[], &[0.3, 0.4]), 0.7));
    assert!(
        near(output(Linear, &[], &[0.8, 0.9]), 1.0),
        "clipped to [-1, 1]"
    );
    assert!(near(output(Sigmoid, &[], &[0.3, 0.2]), 0.5f64.tanh()));
    // The oscillator's phase advances at pi (1 + x) per second.
    let b = brain(Oscillator, &[], &[1.0]);
    let mut run = BrainRuntime::new(&b);
    run.set_sensor(0, 0.5);
    for _ in 0..3 {
        run.step(0.0, DT);
    }
    let phase = 3.0 * std::f64::consts::PI * 1.5 * DT;
    assert!(near(run.outputs()[1], phase.sin()));
}

#[test]
fn chaumont_table_i_functions() {
    use NeuronFunction::*;
    assert!(near(output(Threshold, &[0.5], &[0.3, 0.4]), 0.7));
    assert!(near(output(Threshold, &[0.8], &[0.3, 0.4]), 0.0));
    assert!(near(output(Divide, &[], &[0.3, 0.6]), 0.5));
    assert!(
        near(output(Divide, &[], &[0.3, 0.0]), 1.0),
        "b <= epsilon gives 1"
    );
    assert!(near(output(Divide, &[], &[0.3, -0.5]), 1.0));
    // cst: O = V, V = params[0].
    assert!(near(output(Constant, &[0.3], &[]), 0.3));
    // wav: b sin(a t + c) at t = 0.5.
    assert!(near(
        output(Wave, &[], &[0.4, 0.9, 0.2]),
        0.9 * (0.4f64 * 0.5 + 0.2).sin()
    ));
    // mem: the input n steps later.
    let b = brain(Memory, &[3.0], &[1.0]);
    let mut run = BrainRuntime::new(&b);
    let mut seen = Vec::new();
    for k in 0..6 {
        run.set_sensor(0, 0.1 * (k + 1) as f64);
        run.step(0.0, DT);
        seen.push(run.outputs()[1]);
    }
    let expected = [0.0, 0.0, 0.0, 0.1, 0.2, 0.3];
    for (s, e) in seen.iter().zip(expected) {
        assert!(near(*s, e), "{seen:?}");
    }
}

#[test]
fn walking_with_dinosaurs_functions() {
    use NeuronFunction::*;
    let cases: &[(NeuronFunction, &[f64], f64)] = &[
        (Sum, &[0.2, 0.3], 0.5),
        (Product, &[0.5, -0.4], -0.2),
        (Quotient, &[0.2, 0.4], 0.5),
        (Quotient, &[0.2, 0.0], 0.0),
        (SumGreater, &[0.2, 0.3, 0.4], 1.0),
        (SumGreater, &[0.2, 0.1, 0.4], 0.0),
        (GreaterThan, &[0.5, 0.2], 1.0),
        (GreaterThan, &[0.1, 0.2], 0.0),
        (Sign, &[-0.3], -1.0),
        (Sign, &[0.0], 0.0),
        (Min, &[0.3, -0.2, 0.1], -0.2),
        (Max, &[0.3, -0.2, 0.1], 0.3),
        (Abs, &[-0.4], 0.4),
        (If, &[0.6, 0.1], 0.6),
        (If, &[0.6, 0.0], 0.0),
        (Interpolate, &[0.3, 0.6, 0.9], 0.6),
        (Sin, &[0.5], 0.479425538604203),
        (Cos, &[0.5], 0.8775825618903728),
        (Atan, &[0.5], 0.4636476090008061),
        (Log, &[0.5], -std::f64::consts::LN_2),
        (Log, &[-0.5], -0.5),
        (Power, &[0.25, 0.5], 0.5),
        (Logistic, &[0.0], 0.5),
    ];
    for (function, inputs, expected) in cases {
        let got = output(*function, &[], inputs);
        assert!(
            near(got, *expected),
            "{function:?}{inputs:?} = {got}, not {expected}"
        );
    }
    // wave and saw count the neuron's updates.
    let b = brain(Saw, &[], &[]);
    let mut run = BrainRuntime::new(&b);
    let mut seen = Vec::new();
    for _ in 0..4 {
        run.step(0.0, DT);
        seen.push(run.outputs()[0].round());
    }
    assert_eq!(seen, [1.0, 0.0, -1.0, 0.0]);
    let b = brain(StepWave, &[], &[]);
    let mut run = BrainRuntime::new(&b);
    for _ in 0..90 {
        run.step(0.0, DT);
    }
    assert!(near(run.outputs()[0], 1.0));
}

#[test]
fn updates_are_synchronous() {
    // A chain sensor -> A -> B: B sees A's previous output, so the signal takes two steps.
    let mut b = brain(NeuronFunction::Linear, &[], &[1.0]);
    b.neurons.push(Neuron {
        function: NeuronFunction::Linear,
        params: vec![],
        bias: 0.0,
        role: Role::Hidden,
        part: None,
    });
    b.links.push(Link {
        from: 1,
        to: 2,
        weight: 1.0,
    });
    let mut run = BrainRuntime::new(&b);
    run.set_sensor(0, 0.5);
    run.step(0.0, DT);
    assert_eq!(run.outputs()[1..], [0.5, 0.0]);
    run.step(0.0, DT);
    assert_eq!(run.outputs()[1..], [0.5, 0.5]);
}

#[test]
fn cst_outputs_its_constant_whatever_its_inputs_and_bias() {
    use NeuronFunction::Constant;
    assert_eq!(output(Constant, &[-0.7], &[]), -0.7);
    assert_eq!(
        weighted_output(Constant, &[-0.7], 0.5, &[0.9, 0.2], &[3.0, 1.0]),
        -0.7
    );
    assert_eq!(output(Constant, &[], &[0.9]), 0.0, "V defaults to 0");
    assert_eq!(
        output(Constant, &[2.5], &[]),
        1.0,
        "clipped like every output"
    );
    // It holds its value step after step.
    let b = brain(Constant, &[0.4], &[]);
    let mut run = BrainRuntime::new(&b);
    for _ in 0..3 {
        run.step(0.0, DT);
        assert_eq!(run.outputs()[0], 0.4);
    }
}

#[test]
fn a_bias_shifts_a_linear_neuron_by_exactly_b() {
    use NeuronFunction::*;
    let (values, weights) = ([0.3, -0.1], [1.0, 0.5]);
    let plain = weighted_output(Linear, &[], 0.0, &values, &weights);
    assert!(near(plain, 0.25));
    for b in [0.5, -0.125, 0.3] {
        let biased = weighted_output(Linear, &[], b, &values, &weights);
        assert_eq!(biased, plain + b, "bias {b}");
    }
    // With no input the output is the bias itself (a constant, clipped).
    assert_eq!(weighted_output(Linear, &[], 0.25, &[], &[]), 0.25);
    assert_eq!(weighted_output(Linear, &[], -3.0, &[], &[]), -1.0);
    // x: tanh of the biased sum.
    assert!(near(
        weighted_output(Sigmoid, &[], 0.2, &[0.3], &[1.0]),
        0.5f64.tanh()
    ));
    // For functions of a, b, c the bias enters a only: (0.2 + 0.3) * 0.5, not 0.2 * (0.5 + 0.3).
    assert!(near(
        weighted_output(Product, &[], 0.3, &[0.2, 0.5], &[1.0, 1.0]),
        0.25
    ));
    assert!(near(weighted_output(Abs, &[], 0.1, &[-0.3], &[1.0]), 0.2));
    assert_eq!(
        weighted_output(GreaterThan, &[], 0.3, &[0.1, 0.3], &[1.0, 1.0]),
        1.0,
        "0.1 + 0.3 > 0.3"
    );
    // a is the bias alone when there is no input: min, max and mean of nothing but a.
    assert!(near(weighted_output(Min, &[], -0.4, &[], &[]), -0.4));
    assert!(near(weighted_output(Max, &[], -0.4, &[], &[]), -0.4));
    assert!(near(
        weighted_output(Interpolate, &[], 0.3, &[0.6], &[1.0]),
        0.9
    ));
    assert!(near(
        weighted_output(Interpolate, &[], 0.3, &[0.0, 0.6], &[1.0, 1.0]),
        0.45
    ));
    // Functions that ignore their inputs ignore the bias.
    assert_eq!(
        weighted_output(Saw, &[], 0.5, &[], &[]),
        output(Saw, &[], &[])
    );
}

#[test]
fn power_has_a_real_value_for_every_base_and_exponent() {
    use NeuronFunction::Power;
    // (a, b) as sensor reading x weight, so that a can be -8 although readings are in [-1, 1].
    let power = |a: f64, b: f64| {
        let (sa, sb) = (a.abs().max(1.0), b.abs().max(1.0));
        weighted_output(Power, &[], 0.0, &[a / sa, b / sb], &[sa, sb])
    };
    // A negative base with a non-integer exponent: the signed power -|a|^b.
    assert!(near(power(-0.125, 1.0 / 3.0), -0.5), "the real cube root");
    assert!(near(power(-0.25, 0.5), -0.5));
    assert_eq!(power(-8.0, 1.0 / 3.0), -1.0, "-2, clipped");
    assert_eq!(power(-2.0, 0.5), -1.0, "-sqrt(2), clipped");
    // Integer exponents keep their ordinary sign.
    assert!(near(power(-0.5, 2.0), 0.25));
    assert!(near(power(-0.5, 3.0), -0.125));
    assert!(near(power(0.25, 0.5), 0.5));
    // 0 to a negative power is +infinity, so 1; 0^0 is 1; an overflow saturates.
    assert_eq!(power(0.0, -1.0), 1.0);
    assert_eq!(power(0.0, 0.0), 1.0);
    assert_eq!(power(-8.0, 501.0), -1.0);
}

#[test]
fn divisions_logarithms_and_overflows_give_numbers() {
    use NeuronFunction::*;
    let huge = f64::MAX;
    // Sums saturate instead of overflowing to infinity (and infinity - infinity to NaN):
    // MAX + MAX is MAX, and MAX + MAX - MAX is then 0.
    assert_eq!(
        weighted_output(Linear, &[], 0.0, &[1.0, 1.0], &[huge, huge]),
        1.0
    );
    assert_eq!(
        weighted_output(Linear, &[], 0.0, &[1.0, 1.0, -1.0], &[huge, huge, huge]),
        0.0
    );
    assert_eq!(weighted_output(Linear, &[], -huge, &[1.0], &[-huge]), -1.0);
    // sin of a saturated argument is a number.
    let wave = weighted_output(Wave, &[], huge, &[1.0, 1.0, 1.0], &[huge, 1.0, huge]);
    assert!(wave.is_finite());
    assert_eq!(
        weighted_output(Product, &[], 0.0, &[1.0, 1.0], &[huge, huge]),
        1.0
    );
    assert_eq!(
        weighted_output(Quotient, &[], 0.0, &[1.0, 1.0], &[1.0, 1e-320]),
        1.0
    );
    assert_eq!(weighted_output(Log, &[], 0.0, &[1.0], &[1e-320]), -1.0);
    assert_eq!(weighted_output(Logistic, &[], 0.0, &[-1.0], &[huge]), 0.0);
    assert_eq!(
        weighted_output(Divide, &[], 0.0, &[-1.0, 1.0], &[huge, 1e-5]),
        -1.0
    );
    // A delay that is not a number counts as 1 (one step late), rather than panicking.
    let b = brain(Memory, &[f64::NAN], &[1.0]);
    let mut run = BrainRuntime::new(&b);
    run.set_sensor(0, 0.5);
    run.step(0.0, DT);
    run.step(0.0, DT);
    assert_eq!(run.outputs()[1], 0.5);
    // A reading that is not a number counts as 0.
    let b = brain(Linear, &[], &[1.0]);
    let mut run = BrainRuntime::new(&b);
    run.set_sensor(0, f64::NAN);
    run.step(0.0, DT);
    assert_eq!(run.outputs(), [0.0, 0.0]);
}

/// Any finite value, from the subnormal to the largest, of either sign, or an ordinary one.
fn finite() -> impl Strategy<Value = f64> {
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    prop_oneof![
        -3.0..3.0f64,
        POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO,
        prop::sample::select(vec![0.0, -1.0, 1.0, 0.5, -0.5, 1.0 / 3.0, 2.0, -8.0]),
    ]
}

fn any_function() -> impl Strategy<Value = NeuronFunction> {
    prop::sample::select(NeuronFunction::ALL.to_vec())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// Every function, alone, on every combination of finite inputs, weights, parameters and
    /// bias, gives a number in [-1, 1].
    #[test]
    fn every_function_gives_a_number_in_range(
        function in any_function(),
        values in prop::collection::vec(finite(), 0..5),
        weights in prop::collection::vec(finite(), 5),
        params in prop::collection::vec(finite(), 0..3),
        bias in finite(),
        t in finite(),
    ) {
        let b = biased_brain(function, &params, bias, &weights[..values.len()]);
        let mut run = BrainRuntime::new(&b);
        for step in 0..3 {
            for (i, v) in values.iter().enumerate() {
                run.set_sensor(i, *v);
            }
            run.step(t, DT);
            let o = run.outputs()[values.len()];
            prop_assert!((-1.0..=1.0).contains(&o), "{function:?} step {step}: {o}");
        }
    }

    /// Random networks of random functions, with feedback, stay numbers step after step.
    #[test]
    fn random_networks_stay_numbers(
        functions in prop::collection::vec(any_function(), 1..6),
        params in prop::collection::vec(prop::collection::vec(finite(), 0..2), 6),
        biases in prop::collection::vec(finite(), 6),
        links in prop::collection::vec((0..8usize, 0..6usize, finite()), 0..16),
        readings in prop::collection::vec(finite(), 2),
        dt in finite(),
    ) {
        let sensor = |slot| Neuron {
            function: NeuronFunction::Linear,
            params: vec![],
            bias: 0.0,
            role: Role::Sensor { sensor: Sensor::Chemical { slot } },
            part: None,
        };
        let mut neurons = vec![sensor(0), sensor(1)];
        for (k, f) in functions.iter().enumerate() {
            neurons.push(Neuron {
                function: *f,
                params: params[k].clone(),
                bias: biases[k],
                role: Role::Hidden,
                part: None,
            });
        }
        let n = neurons.len();
        let links = links
            .iter()
            .map(|&(from, to, weight)| Link { from: from % n, to: 2 + to % (n - 2), weight })
            .collect();
        let mut run = BrainRuntime::new(&Brain { neurons, links });
        for step in 0..8 {
            run.set_sensor(0, readings[0]);
            run.set_sensor(1, readings[1]);
            run.step((step as f64 * dt).clamp(-f64::MAX, f64::MAX), dt);
            for (i, o) in run.outputs().iter().enumerate() {
                prop_assert!((-1.0..=1.0).contains(o), "neuron {i} step {step}: {o}");
            }
        }
    }
}

#[test]
fn a_brain_that_used_to_give_nan_now_walks() {
    // Two cst neurons feed a power neuron: (-0.5)^0.5, NaN before, now -sqrt(0.5); it drives
    // the hinge of `forward(1) revolute2 forward(1)`.
    let mut c =
        ontogeny::develop::creature_from_commands("forward(1) revolute2 forward(1)").unwrap();
    let neuron = |function, params: Vec<f64>, role| Neuron {
        function,
        params,
        bias: 0.0,
        role,
        part: None,
    };
    c.brain = Brain {
        neurons: vec![
            neuron(NeuronFunction::Constant, vec![-0.5], Role::Hidden),
            neuron(NeuronFunction::Constant, vec![0.5], Role::Hidden),
            neuron(NeuronFunction::Power, vec![], Role::Hidden),
            neuron(
                NeuronFunction::Linear,
                vec![],
                Role::Actuator {
                    actuator: Actuator::Joint { joint: 0, dof: 0 },
                },
            ),
        ],
        links: vec![
            Link {
                from: 0,
                to: 2,
                weight: 1.0,
            },
            Link {
                from: 1,
                to: 2,
                weight: 1.0,
            },
            Link {
                from: 2,
                to: 3,
                weight: 1.0,
            },
        ],
    };
    assert_eq!(c.check_consistency(), Ok(()));
    let mut run = BrainRuntime::new(&c.brain);
    run.step(0.0, DT);
    run.step(0.0, DT);
    assert!(near(run.outputs()[2], -(0.5f64.sqrt())));
    let options = WalkerOptions {
        seconds: 1.0,
        ..WalkerOptions::default()
    };
    let e = task::walker(&c, &SimOptions::default(), &options, false);
    assert_eq!(e.status, Status::Ok, "{:?}", e.message);
    assert!(e.fitness.is_finite());
}

/// The text of the reference page `page` (under `docs/reference/`) around `marker`, up to the
/// next blank line.
fn reference_paragraph(page: &str, marker: &str) -> String {
    let path = format!("{}/docs/reference/{page}", env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(path).unwrap();
    let start = readme
        .find(marker)
        .unwrap_or_else(|| panic!("{marker} in docs/reference/{page}"));
    let rest = &readme[start..];
    rest[..rest.find("\n\n").unwrap_or(rest.len())].to_string()
}

#[test]
fn the_reference_names_every_neuron_function_and_setfuncs_choices() {
    let name = |f: &NeuronFunction| {
        serde_json::to_value(f)
            .unwrap()
            .as_str()
            .unwrap()
            .to_string()
    };
    let paragraph = reference_paragraph("tasks.md", "Every control step: sensors are read");
    for f in NeuronFunction::ALL {
        assert!(
            paragraph.contains(&format!("`{}`", name(&f))),
            "the reference's brain paragraph does not name `{}`",
            name(&f)
        );
    }
    let choices: Vec<String> = NeuronFunction::SETFUNC
        .iter()
        .enumerate()
        .map(|(n, f)| format!("{n} `{}`", name(f)))
        .collect();
    let row = reference_paragraph("commands.md", "| `setfunc` |");
    let row = row.lines().next().unwrap();
    for choice in &choices {
        assert!(
            row.contains(choice),
            "the reference's setfunc row does not list {choice}: {row}"
        );
    }
    assert!(row.contains(&format!("modulo {}", NeuronFunction::SETFUNC.len())));
}
