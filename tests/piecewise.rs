//! Series of many harmonics evaluate through Taylor polynomials on slices of
//! the period (docs/model.md section 8, "Evaluating a series of many
//! harmonics"). They must agree with the series itself to rounding.
//!
//! Reference: at the phases `tau = (j / M) T` the angle of harmonic `k` is
//! `2 pi ((k j) mod M) / M`, an exact rational fraction of a turn, so each
//! term is one correctly rounded `sin_cos` and the sum is compensated: the
//! reference is good to a few ulps of the sum of the terms' magnitudes. The
//! slices and the recurrence (`FourierSignal::from_coefficients`, which
//! never uses slices) are both measured against it.

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::TAU;
use stickslip::numerics::CompensatedSum;
use stickslip::{MotorParams, SignalSpec, motor::Motor, signal::FourierSignal, signal::Signal};

/// Harmonics signal of random amplitudes `u_k k^(-decay)` and phases.
fn random_series(rng: &mut StdRng, n: usize, decay: f64) -> Signal {
    let amplitudes = (1..=n)
        .map(|k| rng.random_range(0.0..1.0) * (k as f64).powf(-decay) * 1e-5)
        .collect();
    let phases = (0..n).map(|_| rng.random_range(0.0..TAU)).collect();
    let spec = SignalSpec::Harmonics {
        frequency: rng.random_range(100.0..1e5),
        amplitudes,
        phases,
        scale_to_stroke: None,
        shift_to_minimum: false,
    };
    let motor = Motor::new(MotorParams::default()).expect("paper motor");
    Signal::build(&spec, &motor).expect("valid series")
}

/// Reference value of derivative `q` (0 position .. 3 jerk) at phase
/// `(j / m) T`, and the sum of its terms' magnitudes.
fn reference(s: &FourierSignal, q: u32, j: u64, m: u64) -> (f64, f64) {
    let c = s.coefficients();
    let (a, b) = (c.cosines, c.sines);
    let mut sum = CompensatedSum::default();
    let mut mass = 0.0;
    if q == 0 {
        sum.add(s.offset());
        mass += s.offset().abs();
    }
    for (i, (&ak, &bk)) in a.iter().zip(b).enumerate() {
        let k = (i + 1) as u64;
        let angle = TAU * ((k * j) % m) as f64 / m as f64;
        let (sn, cs) = angle.sin_cos();
        let w = (k as f64 * s.omega()).powi(q as i32);
        // d^q/dtheta^q of a cos + b sin cycles through 4 forms
        let term = match q % 4 {
            0 => ak * cs + bk * sn,
            1 => bk * cs - ak * sn,
            2 => -(ak * cs + bk * sn),
            _ => ak * sn - bk * cs,
        } * w;
        sum.add(term);
        mass += (ak.abs() + bk.abs()) * w;
    }
    (sum.value(), mass)
}

fn evaluate(s: &FourierSignal, q: u32, tau: f64) -> f64 {
    match q {
        0 => s.position(tau),
        1 => s.velocity(tau),
        2 => s.acceleration(tau),
        _ => s.jerk(tau),
    }
}

#[test]
fn slices_agree_with_the_series_to_rounding() {
    let mut rng = StdRng::seed_from_u64(0x5eed_0008);
    let m: u64 = 1 << 20;
    // worst |error| / (eps * mass) of the slices and of the recurrence
    let mut worst_slices = [0.0_f64; 4];
    let mut worst_recurrence = [0.0_f64; 4];
    let mut points = 0;
    for case in 0..120 {
        let n = [16, 17, 40, 64, 100, 128, 200, 256][case % 8];
        let decay = [0.0, 1.0, 2.0][case % 3];
        let signal = random_series(&mut rng, n, decay);
        let Signal::Fourier(fast) = &signal else {
            panic!("a harmonics scene builds a series");
        };
        let c = fast.coefficients();
        let (a, b) = (c.cosines, c.sines);
        let plain =
            FourierSignal::from_coefficients(fast.period(), fast.offset(), a.to_vec(), b.to_vec());
        for _ in 0..100 {
            let j = rng.random_range(0..m);
            let tau = j as f64 / m as f64 * fast.period();
            for q in 0..4 {
                let (exact, mass) = reference(fast, q, j, m);
                // the phase tau itself carries one rounding: the slope
                // (next derivative's mass) times eps * theta
                let slope = reference(fast, q + 1, j, m).1 / fast.omega();
                let scale = f64::EPSILON * (mass + slope * TAU);
                let e_fast = (evaluate(fast, q, tau) - exact).abs() / scale;
                let e_plain = (evaluate(&plain, q, tau) - exact).abs() / scale;
                let qi = q as usize;
                worst_slices[qi] = worst_slices[qi].max(e_fast);
                worst_recurrence[qi] = worst_recurrence[qi].max(e_plain);
            }
            points += 1;
        }
    }
    println!(
        "{points} points; worst error / (eps x terms' magnitude), \
         position..jerk: slices {worst_slices:?}, recurrence {worst_recurrence:?}"
    );
    for q in 0..4 {
        // Both stay within a few ulps of the terms' magnitude (measured:
        // below 1 for both); the slices' bound in the engine
        // (`velocity_rounding`) is far above this.
        assert!(
            worst_slices[q] <= 4.0,
            "derivative {q}: slices off by {} eps x mass",
            worst_slices[q]
        );
        assert!(
            worst_recurrence[q] <= 4.0,
            "derivative {q}: recurrence off by {} eps x mass",
            worst_recurrence[q]
        );
    }
}

#[test]
fn few_harmonics_keep_the_recurrence_and_many_use_slices() {
    // Below 16 harmonics a built series is evaluated by the recurrence,
    // bit for bit the same as `from_coefficients`; from 16 on by the
    // slices, whose values differ from it by rounding (so somewhere they
    // differ in the last bits, which shows the slices are in use).
    let mut rng = StdRng::seed_from_u64(0x5eed_0009);
    for (n, uses_slices) in [(15, false), (16, true), (64, true)] {
        let signal = random_series(&mut rng, n, 1.0);
        let Signal::Fourier(built) = &signal else {
            panic!("a harmonics scene builds a series");
        };
        let c = built.coefficients();
        let (a, b) = (c.cosines, c.sines);
        let plain = FourierSignal::from_coefficients(
            built.period(),
            built.offset(),
            a.to_vec(),
            b.to_vec(),
        );
        let differs = (0..1000).any(|i| {
            let tau = i as f64 / 1000.0 * built.period();
            built.velocity(tau) != plain.velocity(tau)
        });
        assert_eq!(differs, uses_slices, "n = {n}");
    }
}
