//! Axes: range, linear or logarithmic scale, round tick values and their
//! labels.
//!
//! Contract: linear ticks are multiples of 1, 2 or 5 times a power of ten,
//! about [`Axis::ticks`] of them inside the range; logarithmic ticks are
//! powers of ten (and 2 and 5 times them on axes of at most three
//! decades), with unlabelled minor ticks at the other integer multiples;
//! an axis too short to hold two of those labels labels every integer
//! multiple.
//! Labels are compact (`0.25`, `−3`, `10⁻⁶`, `2.5×10⁶`); a logarithmic
//! axis within `[0.001, 10000]` is labelled in plain decimals.

/// One axis of a panel.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Description with unit, e.g. `t (ms)`.
    pub label: String,
    /// Range shown, in drawn units.
    pub range: (f64, f64),
    /// Logarithmic.
    pub log: bool,
    /// Multiply data by this before drawing (1e3 for s -> ms); the range
    /// is in drawn units.
    pub scale: f64,
    /// Number of tick labels wanted.
    pub ticks: usize,
    /// Whole numbers only (periods, harmonic numbers): no tick between
    /// two integers.
    pub integer: bool,
    /// A phase in radians: ticks at multiples of π/2, labelled `π/2`,
    /// `π`, `3π/2`, `2π`.
    pub pi: bool,
}

/// A tick: its value and label (empty for a minor tick).
#[derive(Debug, Clone, PartialEq)]
pub struct Tick {
    /// Value in drawn units.
    pub value: f64,
    /// Label; empty for a minor tick.
    pub label: String,
}

impl Axis {
    /// A linear axis with data drawn unscaled.
    pub fn linear(label: &str, range: (f64, f64)) -> Self {
        Axis {
            label: label.to_owned(),
            range: widen(range, false),
            log: false,
            scale: 1.0,
            ticks: 5,
            integer: false,
            pi: false,
        }
    }

    /// A logarithmic axis (the range must be positive).
    pub fn log(label: &str, range: (f64, f64)) -> Self {
        Axis {
            log: true,
            range: widen(range, true),
            ..Self::linear(label, (0.0, 1.0))
        }
    }

    /// The same axis drawing data times `scale`.
    pub fn scaled(mut self, scale: f64) -> Self {
        self.scale = scale;
        self
    }

    /// The same axis with ticks at whole numbers only.
    pub fn integers(mut self) -> Self {
        self.integer = true;
        self
    }

    /// The same axis with ticks at multiples of π/2 (a phase in radians).
    pub fn in_pi(mut self) -> Self {
        self.pi = true;
        self
    }

    /// The same axis with about `n` tick labels.
    pub fn with_ticks(mut self, n: usize) -> Self {
        self.ticks = n;
        self
    }

    /// Where drawn value `v` lies along the axis, 0 at the start of the
    /// range and 1 at its end.
    pub fn fraction(&self, v: f64) -> f64 {
        let (lo, hi) = self.range;
        if self.log {
            (v.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (v - lo) / (hi - lo)
        }
    }

    /// True if drawn value `v` is inside the range.
    pub fn contains(&self, v: f64) -> bool {
        let (lo, hi) = self.range;
        v >= lo.min(hi) && v <= hi.max(lo) && (!self.log || v > 0.0)
    }

    /// The ticks inside the range.
    pub fn tick_marks(&self) -> Vec<Tick> {
        if self.log {
            log_ticks(self.range)
        } else if self.pi {
            pi_ticks(self.range)
        } else {
            linear_ticks(self.range, self.ticks, self.integer)
        }
    }
}

/// A range of zero width (a constant series) or reversed, made usable.
fn widen((lo, hi): (f64, f64), log: bool) -> (f64, f64) {
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    if !(lo.is_finite() && hi.is_finite()) {
        return if log { (1.0, 10.0) } else { (0.0, 1.0) };
    }
    if hi > lo {
        return (lo, hi);
    }
    if log {
        (lo / 2.0, hi * 2.0)
    } else if lo == 0.0 {
        (-1.0, 1.0)
    } else {
        let d = lo.abs() * 0.1;
        (lo - d, hi + d)
    }
}

fn linear_ticks((lo, hi): (f64, f64), wanted: usize, integer: bool) -> Vec<Tick> {
    let span = hi - lo;
    let raw = span / wanted.max(2) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= wanted.max(2) as f64 + 1.0)
        .unwrap_or(10.0 * mag);
    let step = if integer { step.max(1.0) } else { step };
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            // k * step in floating point can be 1e-17 for k = 0 of a shifted
            // range; label exact multiples.
            let v = if k == 0 { 0.0 } else { v };
            Tick {
                value: v,
                label: tick_label(v, step),
            }
        })
        .collect()
}

/// Ticks at multiples of π/2, labelled in π (minor ticks at π/4).
fn pi_ticks((lo, hi): (f64, f64)) -> Vec<Tick> {
    let quarter = std::f64::consts::FRAC_PI_4;
    let first = (lo / quarter - 1e-9).ceil() as i64;
    let last = (hi / quarter + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let label = if k % 2 != 0 {
                String::new()
            } else {
                // k / 2 halves of π, in lowest terms.
                let h = k / 2;
                let sign = if h < 0 { "−" } else { "" };
                match h.abs() {
                    0 => "0".to_owned(),
                    1 => format!("{sign}π/2"),
                    2 => format!("{sign}π"),
                    m if m % 2 == 0 => format!("{sign}{}π", m / 2),
                    m => format!("{sign}{m}π/2"),
                }
            };
            Tick {
                value: k as f64 * quarter,
                label,
            }
        })
        .collect()
}

fn log_ticks((lo, hi): (f64, f64)) -> Vec<Tick> {
    let first = lo.log10().floor() as i32;
    let last = hi.log10().ceil() as i32;
    let decades = (hi / lo).log10();
    let labelled: &[f64] = if decades <= 3.01 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    // On axes of many decades, label every k-th power so labels do not
    // crowd.
    let every = ((decades / 6.0).ceil() as i32).max(1);
    let mut out = Vec::new();
    for e in first..=last {
        for m in 1..10 {
            let v = f64::from(m) * 10f64.powi(e);
            if v < lo * (1.0 - 1e-9) || v > hi * (1.0 + 1e-9) {
                continue;
            }
            let major = labelled.contains(&f64::from(m)) && (m != 1 || e.rem_euclid(every) == 0);
            if decades > 8.0 && m != 1 {
                continue;
            }
            let label = if major {
                log_label(m, e, (lo, hi))
            } else {
                String::new()
            };
            out.push(Tick { value: v, label });
        }
    }
    // An axis of less than a decade may hold one labelled tick or none:
    // then every integer multiple is labelled, so the scale can be read.
    if out.iter().filter(|t| !t.label.is_empty()).count() < 2 {
        for t in &mut out {
            let e = t.value.log10().floor() as i32;
            let m = (t.value / 10f64.powi(e)).round() as i32;
            t.label = log_label(m, e, (lo, hi));
        }
    }
    out
}

/// A tick label of `m × 10^e`: plain when the whole axis lies in
/// `[0.001, 10000]` (`0.002`, `0.05`, `200`), with a power of ten
/// otherwise.
fn log_label(m: i32, e: i32, (lo, hi): (f64, f64)) -> String {
    let v = f64::from(m) * 10f64.powi(e);
    if lo >= 0.999e-3 && hi <= 1.001e4 {
        let s = format!("{v:.4}");
        return s.trim_end_matches('0').trim_end_matches('.').to_owned();
    }
    if m == 1 {
        format!("10{}", superscript(e))
    } else {
        format!("{m}×10{}", superscript(e))
    }
}

/// A linear tick value `v` on a grid of step `step`: as many decimals as
/// the step needs, scientific outside `[1e-3, 1e5)`.
pub(super) fn tick_label(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) && step >= 1e-4 {
        let decimals = (-step.log10().floor()).max(0.0) as usize;
        let s = format!("{v:.decimals$}");
        return s.replace('-', "−");
    }
    let exp = a.log10().floor() as i32;
    let mantissa = v / 10f64.powi(exp);
    let sup = superscript(exp);
    if (mantissa.abs() - 1.0).abs() < 1e-9 {
        format!("{}10{sup}", if mantissa < 0.0 { "−" } else { "" })
    } else {
        let m = format!("{mantissa:.2}");
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{}×10{sup}", m.replace('-', "−"))
    }
}

/// An integer in superscript digits, for exponents in labels.
pub fn superscript(e: i32) -> String {
    e.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(ticks: &[Tick]) -> Vec<&str> {
        ticks
            .iter()
            .filter(|t| !t.label.is_empty())
            .map(|t| t.label.as_str())
            .collect()
    }

    #[test]
    fn linear_ticks_are_round() {
        let a = Axis::linear("t", (0.0, 1.0));
        assert_eq!(
            labels(&a.tick_marks()),
            ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]
        );
        let a = Axis::linear("v", (-3.2, 7.9));
        assert_eq!(labels(&a.tick_marks()), ["−2", "0", "2", "4", "6"]);
    }

    #[test]
    fn integer_axes_have_whole_ticks() {
        let a = Axis::linear("p", (0.0, 2.5)).integers();
        assert_eq!(labels(&a.tick_marks()), ["0", "1", "2"]);
    }

    #[test]
    fn log_ticks_are_powers_of_ten() {
        let a = Axis::log("x", (1e-9, 1e-3));
        assert_eq!(
            labels(&a.tick_marks()),
            ["10⁻⁹", "10⁻⁸", "10⁻⁷", "10⁻⁶", "10⁻⁵", "10⁻⁴", "10⁻³"]
        );
        let a = Axis::log("x", (1.0, 100.0));
        assert_eq!(
            labels(&a.tick_marks()),
            ["1", "2", "5", "10", "20", "50", "100"]
        );
        // Seconds of a start-up time read as decimals, not 5×10⁻².
        let a = Axis::log("t", (1.5e-3, 0.06));
        assert_eq!(
            labels(&a.tick_marks()),
            ["0.002", "0.005", "0.01", "0.02", "0.05"]
        );
    }

    #[test]
    fn a_log_axis_shorter_than_its_labels_labels_every_multiple() {
        // 3e-4 to 1.5e-3 holds only 5e-4 and 1e-3 of 1, 2, 5: with the
        // limit of two labels met it keeps them; 3.2e-4 to 9e-4 holds only
        // 5e-4, so every multiple is labelled.
        let a = Axis::log("e", (3.0e-4, 1.5e-3));
        assert_eq!(labels(&a.tick_marks()), ["5×10⁻⁴", "10⁻³"]);
        let a = Axis::log("e", (3.2e-4, 9.0e-4));
        assert_eq!(
            labels(&a.tick_marks()),
            ["4×10⁻⁴", "5×10⁻⁴", "6×10⁻⁴", "7×10⁻⁴", "8×10⁻⁴", "9×10⁻⁴"]
        );
    }

    #[test]
    fn phase_ticks_are_multiples_of_pi() {
        let a = Axis::linear("ψ", (0.0, std::f64::consts::TAU)).in_pi();
        assert_eq!(labels(&a.tick_marks()), ["0", "π/2", "π", "3π/2", "2π"]);
        assert_eq!(a.tick_marks().len(), 9);
    }

    #[test]
    fn labels_are_compact() {
        assert_eq!(tick_label(1e-6, 1e-6), "10⁻⁶");
        assert_eq!(tick_label(2.5e6, 5e5), "2.5×10⁶");
        assert_eq!(tick_label(-3.0, 1.0), "−3");
    }
}
