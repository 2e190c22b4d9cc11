//! The design space of a signal of `n` harmonics at a fixed stroke and a
//! fixed fundamental frequency (docs/model.md sections 2 and 14).
//!
//! A scene's harmonic series `x_R = sum_k d_k sin(k w_0 t + phi_k)` has
//! `2n` numbers, but two of them are not free: the stroke scaling fixes
//! the overall scale of the amplitudes and the shift to the minimum fixes
//! the time origin (a delay `s` adds `k w_0 s` to `phi_k`). What is left
//! are `2n - 2` numbers, which a [`Shape`] holds:
//!
//! * the direction of the amplitude vector, a unit vector `u` in `R^n`
//!   given by `n - 1` hyperspherical angles,
//!   `u_1 = cos t_1`, `u_2 = sin t_1 cos t_2`, ...,
//!   `u_n = sin t_1 ... sin t_(n-1)`;
//! * the relative phases `psi_k = phi_k - k phi_1`, `k = 2..n`, which a
//!   delay leaves unchanged (`phi_1 = 0`).
//!
//! `u_k` is signed: a negative `u_k` is the amplitude `|u_k|` with the
//! phase `psi_k + pi` (`-sin a = sin(a + pi)`), so the series is a smooth
//! function of the angles and phases everywhere, amplitudes of zero
//! included, and every shape has real numbers without bounds as its
//! coordinates. [`Shape::series`] writes a shape as the amplitudes
//! (`|u_k| x_hat / 2`, in metres, `x_hat` the stroke) and phases (in
//! `[0, 2 pi)`) a `kind = "harmonics"` scene gives, before its stroke
//! scaling and shift; the scene scales them to the stroke exactly.
//!
//! Two shapes are the same signal when their coefficients
//! `c_k = u_k e^(i psi_k)` agree up to a delay, `c_k -> c_k e^(i k s)`
//! ([`Shape::distance`]); a shape whose `u_1` is negative is the same
//! signal as the one with every `c_k` multiplied by `(-1)^k` (a delay by
//! half a period).

use std::f64::consts::{PI, TAU};

/// A point of the design space: `n - 1` amplitude angles and `n - 1`
/// relative phases (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    /// Hyperspherical angles `t_1 .. t_(n-1)` of the unit amplitude vector
    /// (rad).
    pub angles: Vec<f64>,
    /// Relative phases `psi_2 .. psi_n` (rad).
    pub phases: Vec<f64>,
}

/// A harmonic series as a `kind = "harmonics"` scene gives it: amplitudes
/// `d_k` (m, `>= 0`) and phases `phi_k` (rad), `k = 1..n`, before stroke
/// scaling and shift.
#[derive(Debug, Clone, PartialEq)]
pub struct HarmonicSeries {
    /// `d_1 .. d_n` (m).
    pub amplitudes: Vec<f64>,
    /// `phi_1 .. phi_n` (rad).
    pub phases: Vec<f64>,
}

impl Shape {
    /// The shape of a series of `n >= 1` harmonics with any amplitudes and
    /// phases (a series with all amplitudes zero gives `u = e_1`).
    pub fn of_series(amplitudes: &[f64], phases: &[f64]) -> Shape {
        let n = amplitudes.len();
        let norm = amplitudes.iter().map(|d| d * d).sum::<f64>().sqrt();
        let u: Vec<f64> = if norm > 0.0 {
            amplitudes.iter().map(|d| d / norm).collect()
        } else {
            (0..n).map(|k| if k == 0 { 1.0 } else { 0.0 }).collect()
        };
        // Angles from the tail norms: t_j = atan2(|u_(j+1..n)|, u_j); the
        // last one keeps the sign of u_n.
        let mut angles = Vec::with_capacity(n.saturating_sub(1));
        for j in 0..n.saturating_sub(1) {
            if j + 2 == n {
                angles.push(u[n - 1].atan2(u[n - 2]));
            } else {
                let tail = u[j + 1..].iter().map(|x| x * x).sum::<f64>().sqrt();
                angles.push(tail.atan2(u[j]));
            }
        }
        let phi1 = phases.first().copied().unwrap_or(0.0);
        let rel = phases
            .iter()
            .enumerate()
            .skip(1)
            .map(|(i, phi)| wrap(phi - (i + 1) as f64 * phi1))
            .collect();
        Shape {
            angles,
            phases: rel,
        }
    }

    /// A shape from its coordinates: the `n - 1` angles, then the `n - 1`
    /// phases.
    pub fn from_coordinates(z: &[f64]) -> Shape {
        let m = z.len() / 2;
        Shape {
            angles: z[..m].to_vec(),
            phases: z[m..].to_vec(),
        }
    }

    /// The coordinates: the angles, then the phases.
    pub fn coordinates(&self) -> Vec<f64> {
        self.angles.iter().chain(&self.phases).copied().collect()
    }

    /// Number of harmonics `n`.
    pub fn harmonics(&self) -> usize {
        self.angles.len() + 1
    }

    /// The signed unit amplitude vector `u` (module docs).
    pub fn unit_amplitudes(&self) -> Vec<f64> {
        let n = self.harmonics();
        let mut u = Vec::with_capacity(n);
        let mut sines = 1.0;
        for t in &self.angles {
            u.push(sines * t.cos());
            sines *= t.sin();
        }
        u.push(sines);
        u
    }

    /// `d u_k / d t_j` for every `k` (rows) and `j` (columns).
    pub fn unit_jacobian(&self) -> Vec<Vec<f64>> {
        let n = self.harmonics();
        let t = &self.angles;
        (0..n)
            .map(|k| {
                (0..n - 1)
                    .map(|j| {
                        if j > k {
                            return 0.0;
                        }
                        // u_k = prod_{i<k} sin t_i * (cos t_k, or 1 for k = n-1).
                        let mut p = 1.0;
                        for (i, ti) in t.iter().enumerate().take(k) {
                            p *= if i == j { ti.cos() } else { ti.sin() };
                        }
                        if j == k {
                            -p * t[k].sin()
                        } else if k + 1 < n {
                            p * t[k].cos()
                        } else {
                            p
                        }
                    })
                    .collect()
            })
            .collect()
    }

    /// The series a scene gives for this shape at stroke `stroke` (module
    /// docs): `d_k = |u_k| stroke / 2`, `phi_1 = 0` and `phi_k = psi_k`,
    /// each plus `pi` where `u_k < 0`, in `[0, 2 pi)`.
    pub fn series(&self, stroke: f64) -> HarmonicSeries {
        let u = self.unit_amplitudes();
        let half = 0.5 * stroke;
        let mut amplitudes = Vec::with_capacity(u.len());
        let mut phases = Vec::with_capacity(u.len());
        for (k, uk) in u.iter().enumerate() {
            let psi = if k == 0 { 0.0 } else { self.phases[k - 1] };
            amplitudes.push(uk.abs() * half);
            phases.push(wrap(if *uk < 0.0 { psi + PI } else { psi }));
        }
        HarmonicSeries { amplitudes, phases }
    }

    /// The canonical coefficients `c_k = u_k e^(i psi_k)` as `(re, im)`,
    /// with `u_1 >= 0` (module docs).
    pub fn coefficients(&self) -> Vec<(f64, f64)> {
        let u = self.unit_amplitudes();
        let flip = u[0] < 0.0;
        u.iter()
            .enumerate()
            .map(|(k, uk)| {
                let psi = if k == 0 { 0.0 } else { self.phases[k - 1] };
                // A delay by T/2 multiplies c_k by (-1)^k (k from 1).
                let sign = if flip && k % 2 == 0 { -1.0 } else { 1.0 };
                let (s, c) = psi.sin_cos();
                (sign * uk * c, sign * uk * s)
            })
            .collect()
    }

    /// How far apart two shapes are as signals: the largest difference of
    /// their coefficients, `max_k |c_k - c'_k e^(i k s)|`, minimised over
    /// the delay `s` (`0` for the same signal, at most 2). Fixing
    /// `phi_1 = 0` fixes the time origin only while `d_1` is not small; the
    /// minimum over `s` makes the distance independent of it. The minimum
    /// is bracketed on 512 delays and refined by golden-section search.
    pub fn distance(&self, other: &Shape) -> f64 {
        let (a, b) = (self.coefficients(), other.coefficients());
        let at = |s: f64| {
            a.iter()
                .zip(&b)
                .enumerate()
                .map(|(k, (x, y))| {
                    let (sin, cos) = ((k + 1) as f64 * s).sin_cos();
                    let (yr, yi) = (y.0 * cos - y.1 * sin, y.0 * sin + y.1 * cos);
                    (x.0 - yr).hypot(x.1 - yi)
                })
                .fold(0.0, f64::max)
        };
        min_over_circle(at, 512, 60)
    }

    /// For `n = 2`: the amplitude ratio `d_2 / d_1` and the relative phase
    /// `psi_2 = phi_2 - 2 phi_1` in `[0, 2 pi)` of the series.
    pub(crate) fn ratio_and_phase(&self) -> (f64, f64) {
        let c = self.coefficients();
        let d1 = c[0].0.hypot(c[0].1);
        let d2 = c[1].0.hypot(c[1].1);
        let phase = if d2 > 0.0 {
            wrap(c[1].1.atan2(c[1].0))
        } else {
            0.0
        };
        (d2 / d1, phase)
    }

    /// For `n = 2`: the shape with amplitude ratio `d_2 / d_1 = ratio`
    /// (`>= 0`) and relative phase `phase`.
    pub fn from_ratio_and_phase(ratio: f64, phase: f64) -> Shape {
        Shape {
            angles: vec![ratio.atan()],
            phases: vec![wrap(phase)],
        }
    }
}

/// An angle in `[0, 2 pi)`.
pub(super) fn wrap(angle: f64) -> f64 {
    let w = angle.rem_euclid(TAU);
    // rem_euclid can round up to 2 pi itself.
    if w >= TAU { 0.0 } else { w }
}

/// The smallest value of `at` over a period `[0, 2 pi)` of its argument:
/// the best of `grid` equally spaced points, then `iterations` steps of a
/// golden-section search in the two grid steps around it (the minimum
/// of a function that is unimodal there, to the grid's resolution
/// otherwise).
pub(super) fn min_over_circle(at: impl Fn(f64) -> f64, grid: usize, iterations: usize) -> f64 {
    let step = TAU / grid as f64;
    let (mut best, mut s_best) = (at(0.0), 0.0);
    for i in 1..grid {
        let s = step * i as f64;
        let d = at(s);
        if d < best {
            best = d;
            s_best = s;
        }
    }
    let (mut lo, mut hi) = (s_best - step, s_best + step);
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..iterations {
        let (c, d) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        if at(c) < at(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    best.min(at(0.5 * (lo + hi)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_and_shape_round_trip() {
        let amplitudes = [3.0, 1.0, 0.5, 0.25];
        let phases = [0.3, 2.0, -1.0, 4.0];
        let shape = Shape::of_series(&amplitudes, &phases);
        assert_eq!(shape.harmonics(), 4);
        let u = shape.unit_amplitudes();
        let norm = amplitudes.iter().map(|d| d * d).sum::<f64>().sqrt();
        for (k, d) in amplitudes.iter().enumerate() {
            assert!((u[k] - d / norm).abs() < 1e-15, "u_{k}");
        }
        // psi_k = phi_k - k phi_1.
        for k in 2..=4 {
            let expected = wrap(phases[k - 1] - k as f64 * phases[0]);
            assert!((shape.phases[k - 2] - expected).abs() < 1e-14);
        }
        let series = shape.series(2.0);
        assert!(series.phases[0] == 0.0);
        for (d, uk) in series.amplitudes.iter().zip(&u) {
            assert!((d - uk.abs()).abs() < 1e-15);
        }
    }

    #[test]
    fn negative_amplitudes_are_phases_plus_pi() {
        // u_2 < 0: the series flips its phase; the coefficients stay.
        let shape = Shape {
            angles: vec![-0.4],
            phases: vec![1.0],
        };
        let s = shape.series(2.0);
        assert!((s.amplitudes[1] - 0.4f64.sin()).abs() < 1e-15);
        assert!((s.phases[1] - (1.0 + PI)).abs() < 1e-15);
        let back = Shape::of_series(&s.amplitudes, &s.phases);
        assert!(back.distance(&shape) < 1e-15);
        // u = (-cos 0.4, sin 0.4) is u = (cos 0.4, sin 0.4) delayed by T/2
        // (sin(t + pi) = -sin t, sin(2t + 2 pi + psi) = sin(2t + psi)).
        let flipped = Shape {
            angles: vec![PI - 0.4],
            phases: vec![1.0],
        };
        let canonical = Shape {
            angles: vec![0.4],
            phases: vec![1.0],
        };
        assert!(flipped.distance(&canonical) < 1e-15);
        // u -> -u is the mirrored signal, another one (model 7).
        let mirrored = Shape {
            angles: vec![0.4 - PI],
            phases: vec![1.0],
        };
        assert!(mirrored.distance(&canonical) > 0.1);
    }

    #[test]
    fn jacobian_matches_central_differences() {
        let shape = Shape {
            angles: vec![0.3, 1.1, -0.7],
            phases: vec![0.0; 3],
        };
        let jac = shape.unit_jacobian();
        let h = 1e-6;
        for j in 0..3 {
            let mut plus = shape.clone();
            plus.angles[j] += h;
            let mut minus = shape.clone();
            minus.angles[j] -= h;
            let (up, um) = (plus.unit_amplitudes(), minus.unit_amplitudes());
            for (k, row) in jac.iter().enumerate() {
                let fd = (up[k] - um[k]) / (2.0 * h);
                assert!((row[j] - fd).abs() < 1e-9, "d u_{k} / d t_{j}");
            }
        }
    }

    #[test]
    fn a_delay_is_no_distance() {
        // Harmonics 2 and 4 only: phi_1 fixes no time origin, and a delay
        // s turns psi_k into psi_k + k s.
        let a = Shape::of_series(&[0.0, 1.0, 0.0, 0.25], &[0.0, 0.3, 0.0, 2.0]);
        let s = 0.7;
        let b = Shape::of_series(
            &[0.0, 1.0, 0.0, 0.25],
            &[0.0, 0.3 + 2.0 * s, 0.0, 2.0 + 4.0 * s],
        );
        assert!(a.distance(&b) < 1e-12, "{}", a.distance(&b));
        let c = Shape::of_series(&[0.0, 1.0, 0.0, 0.25], &[0.0, 0.3, 0.0, 2.5]);
        // Harmonic 4 moved by 0.5 rad and harmonic 2 not: no delay moves
        // both, so this is another signal.
        assert!(a.distance(&c) > 1e-3);
    }

    #[test]
    fn ratio_and_phase_round_trip() {
        let shape = Shape::from_ratio_and_phase(0.25, 3.0);
        let (r, p) = shape.ratio_and_phase();
        assert!((r - 0.25).abs() < 1e-15 && (p - 3.0).abs() < 1e-15);
    }
}
