//! Electrical input power (the paper's section 6.3, (29)-(36), Table 1).
//!
//! Where the expected numbers come from:
//! * single harmonics: the paper's (29), (30) written out by hand below, and
//!   independently the phasor solution of (23), (21) in complex arithmetic;
//! * scaling: (31)-(35) are linear in the amplitudes (`U, I ∝ x_Rmax`), and
//!   their limits far below and far above the resonance (module docs of
//!   `stickslip::power`);
//! * the Table 1 resonance: docs/model.md section 4;
//! * `S = v_inf / velocity_per_power` of the independent reference grid
//!   (`tests/data/section7_grid.csv`, docs/model.md section 7).

mod common;

use approx::assert_relative_eq;
use std::f64::consts::PI;
use stickslip::motor::Motor;
use stickslip::{
    MotorParams, SignalSpec, signal::Drive, signal::FourierSignal, signal::IdealShape,
    signal::Signal,
};
use stickslip::{power::ActuatorParams, power::input_power};

/// (29) and (30) exactly as printed, for velocity amplitude `v_hat` at
/// angular frequency `w`.
fn paper_29_30(p: &ActuatorParams, w: f64, v_hat: f64) -> (f64, f64) {
    let (m, d, c, alpha, cap) = (
        p.mass,
        p.damping,
        p.stiffness,
        p.transfer_factor,
        p.capacitance,
    );
    let x = w * m - c / w;
    let u = v_hat * (d * d + x * x).sqrt() / alpha;
    let i = (alpha.powi(4) - 2.0 * cap * x * alpha * alpha * w
        + cap * cap * (d * d + x * x) * w * w)
        .sqrt()
        / alpha
        * v_hat;
    (u, i)
}

/// (31) and (32) exactly as printed, for harmonic `k` of amplitude `d_k`.
fn paper_31_32(p: &ActuatorParams, w0: f64, k: f64, d_k: f64) -> (f64, f64) {
    let (m, d, c, alpha, cap) = (
        p.mass,
        p.damping,
        p.stiffness,
        p.transfer_factor,
        p.capacitance,
    );
    let a_k = d * d + (k * w0 * m - c / (k * w0)).powi(2);
    let u = w0 * d_k * k / alpha * a_k.sqrt();
    let i = w0 * d_k * k / alpha
        * (alpha.powi(4)
            + 2.0 * cap * alpha * alpha * (c - m * k * k * w0 * w0)
            + cap * cap * k * k * w0 * w0 * a_k)
            .sqrt();
    (u, i)
}

/// Phasor solution of (23) and (21) for `x_R = Re(x_hat e^{jwt})`:
/// `alpha u = (c - w^2 M + j w d) x`, `i = j w (alpha x + C u)`.
fn phasor(p: &ActuatorParams, w: f64, x_hat: f64) -> (f64, f64) {
    let (re, im) = (p.stiffness - w * w * p.mass, w * p.damping);
    let (u_re, u_im) = (
        re * x_hat / p.transfer_factor,
        im * x_hat / p.transfer_factor,
    );
    let (q_re, q_im) = (
        p.transfer_factor * x_hat + p.capacitance * u_re,
        p.capacitance * u_im,
    );
    // i = j w q
    let (i_re, i_im) = (-w * q_im, w * q_re);
    (u_re.hypot(u_im), i_re.hypot(i_im))
}

fn single_harmonic(f0: f64, cos: f64, sin: f64) -> FourierSignal {
    FourierSignal::from_coefficients(1.0 / f0, 0.0, vec![cos], vec![sin])
}

// Frequencies around the Table 1 resonance (13.95 kHz), kept away from the
// anti-resonance sqrt((c + alpha^2/C)/M)/(2 pi) = 15.29 kHz, where the
// expanded (30) loses digits to cancellation.
const FREQUENCIES: [f64; 6] = [10.0, 1574.8, 9448.8, 13_954.4, 30_000.0, 1e6];

#[test]
fn single_harmonic_matches_29_and_30() {
    let actuator = ActuatorParams::default();
    for f0 in FREQUENCIES {
        let signal = single_harmonic(f0, 3e-6, -12e-6);
        let d_1 = 3e-6f64.hypot(12e-6);
        let w = 2.0 * PI * f0;
        let (u, i) = paper_29_30(&actuator, w, w * d_1);
        let report = input_power(&signal, &actuator);
        assert_eq!(report.harmonics.len(), 1);
        let h = report.harmonics[0];
        assert_eq!(h.k, 1);
        assert_relative_eq!(h.amplitude, d_1, max_relative = 1e-15);
        assert_relative_eq!(h.u_hat, u, max_relative = 1e-12);
        assert_relative_eq!(h.i_hat, i, max_relative = 1e-12);
        // (33)-(35) for one harmonic: RMS = amplitude / sqrt(2).
        assert_relative_eq!(report.u_rms, u / 2f64.sqrt(), max_relative = 1e-12);
        assert_relative_eq!(report.i_rms, i / 2f64.sqrt(), max_relative = 1e-12);
        assert_relative_eq!(report.apparent_power, u * i / 2.0, max_relative = 1e-12);
    }
}

#[test]
fn equation_30_and_32_are_the_same_expression() {
    // (32) rewrites (30) at w = k w_0 with v_hat = k w_0 d_k.
    let actuator = ActuatorParams::default();
    for f0 in FREQUENCIES {
        let w0 = 2.0 * PI * f0;
        for k in [1.0, 2.0, 3.0] {
            let d_k = 7e-6 / k;
            let (u30, i30) = paper_29_30(&actuator, k * w0, k * w0 * d_k);
            let (u32, i32) = paper_31_32(&actuator, w0, k, d_k);
            assert_relative_eq!(u30, u32, max_relative = 1e-12);
            assert_relative_eq!(i30, i32, max_relative = 1e-12);
        }
    }
}

#[test]
fn single_harmonic_matches_the_phasor_solution_of_23_and_21() {
    // Independent of the paper's algebra: solve the actuator model directly.
    let actuator = ActuatorParams::default();
    for f0 in FREQUENCIES.into_iter().chain([15_290.0, 15_295.0]) {
        let d_1 = 5e-6;
        let report = input_power(&single_harmonic(f0, 0.0, d_1), &actuator);
        let (u, i) = phasor(&actuator, 2.0 * PI * f0, d_1);
        assert_relative_eq!(report.harmonics[0].u_hat, u, max_relative = 1e-12);
        assert_relative_eq!(report.harmonics[0].i_hat, i, max_relative = 1e-12);
    }
}

#[test]
fn several_harmonics_sum_as_33_to_35() {
    let actuator = ActuatorParams::default();
    let f0 = 4000.0;
    let w0 = 2.0 * PI * f0;
    let cos = vec![1e-6, -2e-6, 0.5e-6];
    let sin = vec![-8e-6, 1e-6, 0.0];
    let signal = FourierSignal::from_coefficients(1.0 / f0, 3e-6, cos.clone(), sin.clone());
    let report = input_power(&signal, &actuator);
    let (mut su, mut si) = (0.0, 0.0);
    for (j, h) in report.harmonics.iter().enumerate() {
        let k = (j + 1) as f64;
        assert_eq!(h.k, j + 1);
        let d_k = cos[j].hypot(sin[j]);
        assert_relative_eq!(h.amplitude, d_k, max_relative = 1e-15);
        let (u, i) = paper_31_32(&actuator, w0, k, d_k);
        assert_relative_eq!(h.u_hat, u, max_relative = 1e-12);
        assert_relative_eq!(h.i_hat, i, max_relative = 1e-12);
        su += u * u;
        si += i * i;
    }
    let (u_rms, i_rms) = ((su / 2.0).sqrt(), (si / 2.0).sqrt());
    assert_relative_eq!(report.u_rms, u_rms, max_relative = 1e-12);
    assert_relative_eq!(report.i_rms, i_rms, max_relative = 1e-12);
    assert_relative_eq!(report.apparent_power, u_rms * i_rms, max_relative = 1e-12);
}

/// A two-harmonic signal of fixed shape scaled to `stroke` at `f0`.
fn shaped(f0: f64, stroke: f64) -> FourierSignal {
    let spec = SignalSpec::Harmonics {
        frequency: f0,
        amplitudes: vec![8.4e-6, 2.0e-6],
        phases: vec![2.83, 2.98],
        scale_to_stroke: Some(stroke),
        shift_to_minimum: true,
    };
    let motor = Motor::new(MotorParams::default()).unwrap();
    match Signal::build(&spec, &motor).unwrap() {
        Signal::Fourier(f) => f,
        Signal::Ideal(_) => unreachable!("a harmonic series is a Fourier signal"),
    }
}

#[test]
fn power_is_quadratic_in_the_stroke_at_fixed_frequency() {
    // (31), (32) are linear in d_k, so U, I ∝ x_Rmax and S = U I ∝ x_Rmax^2
    // (not ∝ x_Rmax as the text after (36) states).
    let actuator = ActuatorParams::default();
    for f0 in [1574.8, 9448.8, 20_000.0] {
        let small = input_power(&shaped(f0, 25e-6), &actuator);
        for lambda in [2.0, 3.0, 0.1] {
            let big = input_power(&shaped(f0, lambda * 25e-6), &actuator);
            assert_relative_eq!(big.u_rms, lambda * small.u_rms, max_relative = 1e-12);
            assert_relative_eq!(big.i_rms, lambda * small.i_rms, max_relative = 1e-12);
            assert_relative_eq!(
                big.apparent_power,
                lambda * lambda * small.apparent_power,
                max_relative = 1e-12
            );
        }
    }
}

#[test]
fn equation_36_holds_with_the_stroke_squared() {
    // (36) as printed has the prefactor w_0^2 x_Rmax / (2 alpha^2), which has
    // units of W/m: the value of (35) is x_Rmax times it, i.e. (36) with
    // x_Rmax^2.
    let p = ActuatorParams::default();
    for (f0, stroke) in [(1574.8, 25e-6), (9448.8, 25e-6), (9448.8, 100e-6)] {
        let signal = shaped(f0, stroke);
        let w0 = signal.omega();
        let (mut sum_u, mut sum_i) = (0.0, 0.0);
        for (j, d_k) in signal.amplitudes().into_iter().enumerate() {
            let k = (j + 1) as f64;
            let d_star = d_k / stroke;
            let a_k = p.damping.powi(2) + (k * w0 * p.mass - p.stiffness / (k * w0)).powi(2);
            sum_u += (d_star * k).powi(2) * a_k;
            sum_i += (d_star * k).powi(2)
                * (p.transfer_factor.powi(4)
                    + 2.0
                        * p.capacitance
                        * p.transfer_factor.powi(2)
                        * (p.stiffness - p.mass * k * k * w0 * w0)
                    + p.capacitance.powi(2) * k * k * w0 * w0 * a_k);
        }
        let paper_36 =
            w0 * w0 * stroke / (2.0 * p.transfer_factor.powi(2)) * sum_u.sqrt() * sum_i.sqrt();
        let s = input_power(&signal, &p).apparent_power;
        assert_relative_eq!(s, stroke * paper_36, max_relative = 1e-11);
    }
}

#[test]
fn paper_scaling_keeps_the_shape_and_gives_no_single_power_law() {
    // Section 8: fixed kappa, n and sigma give T ∝ sqrt(x_Rmax) (40) and the
    // same normalised amplitudes d / x_hat. With S = x^2 w_0^2 G(w_0), S
    // follows x^(3/2) far below the actuator resonance (quasi-static: U does
    // not depend on w_0, I ∝ w_0 x) and x^(-1/2) far above it (mass-
    // dominated: U ∝ w_0^2 x, I ∝ w_0^3 x); the paper's "∝ x_Rmax" holds in
    // neither limit.
    let motor = Motor::default();
    let shape = |stroke| IdealShape {
        stroke,
        drive: Drive::Kappa(36.0),
        duty: 1.0,
    };
    let lambda = 4.0;
    let a = FourierSignal::approximate_ideal(shape(25e-6), 2, true, &motor).unwrap();
    let b = FourierSignal::approximate_ideal(shape(lambda * 25e-6), 2, true, &motor).unwrap();
    assert_relative_eq!(b.period(), lambda.sqrt() * a.period(), max_relative = 1e-12);
    for (da, db) in a.amplitudes().iter().zip(b.amplitudes()) {
        assert_relative_eq!(db, lambda * da, max_relative = 1e-9);
    }

    // The limits, with the same signal shape at f_0 and f_0 / sqrt(lambda).
    let table1 = ActuatorParams::default();
    let exponent = |f0: f64| {
        let s_small = input_power(&shaped(f0, 25e-6), &table1).apparent_power;
        let s_big =
            input_power(&shaped(f0 / lambda.sqrt(), lambda * 25e-6), &table1).apparent_power;
        (s_big / s_small).ln() / lambda.ln()
    };
    // f_max = 20 Hz << 13.95 kHz: corrections ~ (f/f_r)^2 ~ 1e-6.
    assert_relative_eq!(exponent(10.0), 1.5, max_relative = 1e-4);
    // f_0 = 10 MHz >> 13.95 kHz: corrections ~ (f_r/f)^2 ~ 1e-6.
    assert_relative_eq!(exponent(1e7), -0.5, max_relative = 1e-4);

    // In between, the resonance (13.95 kHz) and the anti-resonance
    // (15.29 kHz) bend the curve beyond both limits. For the paper's default
    // signal (f_max = 18.9 kHz at 25 um), quadrupling the stroke gives
    // S ∝ x^2.07 and quartering it S ∝ x^-0.25: far from ∝ x either way.
    let c = FourierSignal::approximate_ideal(shape(25e-6 / lambda), 2, true, &motor).unwrap();
    let [s_c, s_a, s_b] = [&c, &a, &b].map(|s| input_power(s, &table1).apparent_power);
    let up = (s_b / s_a).ln() / lambda.ln();
    let down = (s_a / s_c).ln() / lambda.ln();
    assert!((up - 2.07).abs() < 0.01, "exponent {up}");
    assert!((down + 0.25).abs() < 0.01, "exponent {down}");
}

#[test]
fn table_1_resonance() {
    // docs/model.md section 4: sqrt(c/M)/(2 pi) = 13.95 kHz.
    let f = ActuatorParams::default().resonance_frequency();
    assert!((f / 1e3 - 13.95).abs() < 0.01, "{f} Hz");
}

#[test]
fn table_1_defaults() {
    let p = ActuatorParams::default();
    assert_eq!(
        (
            p.mass,
            p.damping,
            p.stiffness,
            p.transfer_factor,
            p.capacitance
        ),
        (3.2e-3, 9.50, 24.6e6, 1.985, 800e-9)
    );
    p.validate().unwrap();
}

#[test]
fn invalid_actuator_names_the_field() {
    let fields = [
        "actuator.mass",
        "actuator.damping",
        "actuator.stiffness",
        "actuator.transfer_factor",
        "actuator.capacitance",
    ];
    for (j, field) in fields.iter().enumerate() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let mut p = ActuatorParams::default();
            let slot = match j {
                0 => &mut p.mass,
                1 => &mut p.damping,
                2 => &mut p.stiffness,
                3 => &mut p.transfer_factor,
                _ => &mut p.capacitance,
            };
            *slot = bad;
            let err = p.validate().unwrap_err().to_string();
            assert!(err.starts_with(field), "{err}");
        }
    }
}

#[test]
fn apparent_power_matches_the_reference_grid() {
    // tests/data/section7_grid.csv: S = v_inf / velocity_per_power, from an
    // independent implementation; its velocity_per_power is printed to 6
    // digits (rounding up to 5e-6) and v_inf is accurate to 1e-6. The input
    // power itself needs no simulation, so only rounding separates the two.
    let text = common::reference_grid_text();
    let motor = Motor::default();
    let actuator = ActuatorParams::default();
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let cols: Vec<&str> = line.split(',').collect();
        let n: usize = cols[1].parse().unwrap();
        let sqrt_kappa: f64 = cols[2].parse().unwrap();
        let sigma: bool = cols[3].parse().unwrap();
        let v_inf: f64 = cols[4].parse().unwrap();
        let vpp: f64 = cols[9].parse().unwrap();
        let shape = IdealShape {
            stroke: 25e-6,
            drive: Drive::Kappa(sqrt_kappa * sqrt_kappa),
            duty: 1.0,
        };
        let signal = FourierSignal::approximate_ideal(shape, n, sigma, &motor).unwrap();
        let s = input_power(&signal, &actuator).apparent_power;
        assert_relative_eq!(s, v_inf / vpp, max_relative = 2e-5);
        rows += 1;
    }
    assert_eq!(rows, 50);
}
