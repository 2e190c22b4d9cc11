//! The gradient `stickslip optimize` refines with (docs/model.md
//! section 15, `optimize::gradient`): exact derivatives of `v_inf` (the
//! period map's sensitivities, model 14) and of the apparent power and
//! RMS voltage (the actuator model, model 4) agree with central differences
//! of exact runs on random signals wherever the event structure is the
//! same within the difference step; at a change of the event structure
//! the gradient is the derivative of the side the point's own orbit lies
//! on.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::{FRAC_PI_2, TAU};
use stickslip::Scene;
use stickslip::optimize::{
    HarmonicSeries, Measured, Objective, OptimizeTable, Overrides, Param, Problem, Settings, Shape,
    Values, gradient, gradient_by_differences,
};
use stickslip::sensitivity::{self, Derivative, Parameter};

mod common;
use common::event_token as token;

/// The problem of `n` harmonics at the paper's default `f_max` (model 6),
/// with `objective` (its run computes what that objective needs).
fn problem(n: i64, objective: Objective) -> Problem {
    let scene = Scene::default();
    let overrides = Overrides {
        harmonics: Some(n),
        ..Overrides::default()
    };
    let settings = Settings::resolve(&OptimizeTable::default(), &overrides, &scene).unwrap();
    let mut p = settings.problem(&scene, objective).unwrap();
    p.scale = 0.3;
    p.v_ref = 0.3;
    p
}

/// The event structure of the steady period of `series` as a cyclic
/// sequence (named by its smallest rotation), with what the run reported;
/// `None` without a steady state.
fn structure(p: &Problem, series: &HarmonicSeries) -> Option<(Vec<String>, Measured)> {
    let m = p.measure(p.spec(series)).ok()?;
    let s = sensitivity::of_steady_state(&p.spec(series), &p.base.motor, m.boundary_velocity, &[])
        .ok()?;
    let tokens: Vec<String> = s.events.iter().map(|e| token(&e.kind)).collect();
    let cycle = (0..tokens.len().max(1))
        .map(|k| {
            let mut t = tokens.clone();
            t.rotate_left(k);
            t
        })
        .min()
        .unwrap_or_default();
    Some((cycle, m))
}

/// The series with one parameter moved by `delta` (amplitudes stay
/// positive here: every amplitude is far above the step).
fn moved(series: &HarmonicSeries, param: Param, delta: f64) -> HarmonicSeries {
    let mut s = series.clone();
    match param {
        Param::Amplitude(k) => s.amplitudes[k - 1] += delta,
        Param::Phase(k) => s.phases[k - 1] += delta,
    }
    s
}

/// 200 random signals of 2 to 5 harmonics (seeded), every amplitude and
/// phase: the exact `v_inf`, `S` and `U` derivatives against
/// [`gradient_by_differences`] (relative step `h = 1e-5`, module docs of
/// `optimize::gradient`), to 1e-6 of the difference beyond the difference
/// quotient's own error, wherever the event structure at `p +- h` and
/// `p +- 2h` is that of the signal. That error is its rounding, from the
/// runs' error estimates of `v_inf`, `(e_+ + e_-) / 2h` (`S` and `U` are
/// closed forms, exact to rounding), and its truncation, estimated by
/// Richardson's rule from the quotient with step `2h`: `|D(2h) - D(h)| / 3`
/// (it is `O(h^2)`; where the stroke scaling's extrema nearly tie, `S` and
/// `U` curve strongly and it reaches `1e-6` relative).
#[test]
fn exact_gradient_matches_central_differences_on_random_signals() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let problems: Vec<Problem> = (2..=5)
        .map(|n| problem(n, Objective::VelocityPerPower))
        .collect();
    let (mut signals, mut checked, mut skipped) = (0, 0, 0);
    let mut worst: f64 = 0.0;
    while signals < 200 {
        let n = rng.random_range(2..=5usize);
        let p = &problems[n - 2];
        // Angles away from 0 and pi/2: no amplitude below 5 % of the
        // largest, far above the step.
        let shape = Shape {
            angles: (0..n - 1)
                .map(|_| (0.1 + 0.8 * rng.random::<f64>()) * FRAC_PI_2)
                .collect(),
            phases: (0..n - 1).map(|_| rng.random::<f64>() * TAU).collect(),
        };
        let series = shape.series(p.stroke);
        let Some((here, _)) = structure(p, &series) else {
            continue;
        };
        let wrt: Vec<Param> = (1..=n)
            .map(Param::Amplitude)
            .chain((1..=n).map(Param::Phase))
            .collect();
        let (Ok(exact), Ok(fd)) = (
            gradient(p, &series, &wrt),
            gradient_by_differences(p, &series, &wrt),
        ) else {
            continue;
        };
        signals += 1;
        let largest = series.amplitudes.iter().copied().fold(0.0, f64::max);
        for ((param, e), d) in wrt.iter().zip(&exact).zip(&fd) {
            let h = match param {
                Param::Amplitude(_) => 1e-5 * largest,
                Param::Phase(_) => 1e-5,
            };
            let runs: Option<Vec<(Vec<String>, Measured)>> = [h, -h, 2.0 * h, -2.0 * h]
                .iter()
                .map(|delta| structure(p, &moved(&series, *param, *delta)))
                .collect();
            let Some(runs) = runs else {
                skipped += 1;
                continue;
            };
            if runs.iter().any(|(s, _)| *s != here) {
                skipped += 1;
                continue;
            }
            let error = |r: &Measured| r.v_inf_error.unwrap_or(f64::INFINITY);
            let rounding = (error(&runs[0].1) + error(&runs[1].1)) / (2.0 * h);
            let (up2, down2) = (&runs[2].1.values, &runs[3].1.values);
            let wide = |q: fn(&Values) -> f64| (q(up2) - q(down2)) / (4.0 * h);
            for (name, exact, fd, wide, own) in [
                ("v_inf", e.v_inf, d.v_inf, wide(|v| v.v_inf), rounding),
                (
                    "S",
                    e.apparent_power,
                    d.apparent_power,
                    wide(|v| v.apparent_power),
                    0.0,
                ),
                (
                    "U",
                    e.voltage_rms,
                    d.voltage_rms,
                    wide(|v| v.voltage_rms),
                    0.0,
                ),
            ] {
                let truncation = (wide - fd).abs() / 3.0;
                let tol = 1e-6 * fd.abs() + own + truncation;
                assert!(
                    (exact - fd).abs() <= tol,
                    "n = {n}, {param:?}, d{name}: exact {exact:e} against {fd:e} \
                     (tolerance {tol:e}), shape {shape:?}"
                );
                if fd != 0.0 {
                    worst = worst.max((exact - fd).abs() / fd.abs());
                }
            }
            checked += 1;
        }
    }
    println!(
        "{signals} signals, {checked} parameters checked, {skipped} skipped, worst {worst:.1e}"
    );
    assert!(checked >= 1000, "only {checked} parameters checked");
}

/// At a change of the event structure the exact derivatives are one-sided
/// (model 14.4). Along `d_2` through the `n = 2` optimum at the paper's
/// default (`psi = 3.15`; model 15: the slider touches the rod in the dip
/// of `v_R`), bisection on the event structure finds the change (a
/// grazing: beyond it the slider's velocity crosses the rod's twice more).
/// The two ends of the bisection, within `1e-13` of `d_1` of the change,
/// each have their own orbit's structure; the sensitivities report both
/// sides there, and the gradient the search uses is the side of the
/// point's own orbit: it equals the one-sided difference on that side
/// (three points, step `1e-7` of `d_1`; to `1e-4`, the error of a
/// difference next to a grazing, model 14.4) and not the other side's.
#[test]
fn at_a_kink_the_gradient_is_the_side_of_the_points_own_orbit() {
    let p = problem(2, Objective::VInf);
    let at = |ratio: f64| {
        let shape = Shape::from_ratio_and_phase(ratio, 3.15);
        shape.series(p.stroke)
    };
    let d1 = at(0.25).amplitudes[0];
    // d_2 / d_1 from 0.15 to 0.35 holds the change (the optimum's ratio is
    // 0.2500, model 15); move d_2 alone, at fixed d_1 and phases.
    let with_d2 = |d2: f64| {
        let mut s = at(0.25);
        s.amplitudes[1] = d2;
        s
    };
    let (mut lo, mut hi) = (0.15 * d1, 0.35 * d1);
    let s_lo = structure(&p, &with_d2(lo)).unwrap().0;
    let s_hi = structure(&p, &with_d2(hi)).unwrap().0;
    assert_ne!(s_lo, s_hi, "a change of the event structure in between");
    while hi - lo > 1e-13 * d1 {
        let mid = 0.5 * (lo + hi);
        if structure(&p, &with_d2(mid)).unwrap().0 == s_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    println!(
        "change at d_2 / d_1 = {:.12}: {s_lo:?} -> {s_hi:?}",
        lo / d1
    );
    let h = 1e-7 * d1;
    let v = |d2: f64| structure(&p, &with_d2(d2)).unwrap().1.values.v_inf;
    // Three-point one-sided differences from x towards `dir`.
    let one_sided = |x: f64, dir: f64| {
        let (f0, f1, f2) = (v(x), v(x + dir * h), v(x + 2.0 * dir * h));
        (-1.5 * f0 + 2.0 * f1 - 0.5 * f2) / (dir * h)
    };
    let left = one_sided(lo, -1.0);
    let right = one_sided(hi, 1.0);
    assert!(
        (left - right).abs() > 1e-2 * left.abs().max(right.abs()),
        "a kink: {left:e} against {right:e}"
    );
    for (x, own, other) in [(lo, left, right), (hi, right, left)] {
        let series = with_d2(x);
        let g = gradient(&p, &series, &[Param::Amplitude(2)]).unwrap()[0].v_inf;
        let m = p.measure(p.spec(&series)).unwrap();
        let reported = sensitivity::of_steady_state(
            &p.spec(&series),
            &p.base.motor,
            m.boundary_velocity,
            &[Parameter::Amplitude(1)],
        )
        .unwrap();
        let d = reported.entries[0].derivative;
        assert!(
            matches!(d, Derivative::OneSided { .. }),
            "one-sided within 1e-9 of the change: {d:?}"
        );
        println!(
            "d_2 / d_1 = {:.12}: gradient {g:e}, own side {own:e}, other {other:e}, {d:?}",
            x / d1
        );
        assert!(
            (g - own).abs() <= 1e-4 * own.abs(),
            "gradient {g:e} against its own side {own:e}"
        );
        assert!((g - other).abs() > 1e2 * (g - own).abs());
        let side = if x == lo { d.left() } else { d.right() };
        assert_eq!(side, Some(g), "the reported side of the point's own orbit");
    }
}
