//! Every neuron function on known inputs (Hornby & Pollack, Matos & Arita, Chaumont et al.'s
//! Table I, Walking with Dinosaurs section 3.2).

use ontogeny::creature::{Brain, Link, Neuron, NeuronFunction, Role, Sensor};
use ontogeny::sim::BrainRuntime;

const DT: f64 = 1.0 / 60.0;

/// Neurons 0..inputs are sensors feeding neuron `inputs` (of `function`) with `weights`.
fn brain(function: NeuronFunction, params: &[f64], weights: &[f64]) -> Brain {
    let sensor = |i| Neuron {
        function: NeuronFunction::Linear,
        params: vec![],
        role: Role::Sensor {
            sensor: Sensor::Chemical { slot: i },
        },
        part: None,
    };
    let mut neurons: Vec<Neuron> = (0..weights.len()).map(sensor).collect();
    neurons.push(Neuron {
        function,
        params: params.to_vec(),
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
    let b = brain(function, params, &vec![1.0; values.len()]);
    let mut run = BrainRuntime::new(&b);
    for (i, v) in values.iter().enumerate() {
        run.set_sensor(i, *v);
    }
    assert!(run.step(0.5, DT));
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
fn nan_is_caught() {
    let b = brain(NeuronFunction::Power, &[], &[1.0, 1.0]);
    let mut run = BrainRuntime::new(&b);
    run.set_sensor(0, -0.5);
    run.set_sensor(1, 0.5);
    assert!(!run.step(0.0, DT), "(-0.5)^0.5 is NaN");
}
