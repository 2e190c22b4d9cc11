//! Step 4 of the root finder (module docs of the parent): the candidates
//! that are one root are merged, and each root is reported once.

use std::f64::consts::TAU;

use super::isolate::{Candidate, Models};
use super::{EPS, MAX_ACCEPT, TrigPoly, WithTwoDerivatives, wrap};

impl TrigPoly {
    /// Groups the candidates that are one root — `p` at rounding level
    /// between neighbours, cyclically — and returns one value per group,
    /// sorted, in `[0, 2π)`.
    ///
    /// With the finder's `models`, a midpoint where a model proves
    /// `|p| > 2η + 2 ε max(|θ|, 1) Σ k (|a_k| + |b_k|)` is not evaluated:
    /// the computed `|p|` there (within `η` of the true one) exceeds the
    /// rounding level `η + |p'| ulp`, so the evaluation would separate the
    /// neighbours too. A single candidate whose solve left `p'` and whose
    /// `|p'| > 4 sqrt(2 η Σ k² (|a_k| + |b_k|))` is no tangency (see
    /// [`TrigPoly::representative`]) and is its own value without another
    /// evaluation. Both give the same values, to the bit, as evaluating.
    pub(super) fn merge(
        &self,
        mut found: Vec<Candidate>,
        eta: f64,
        models: Option<&Models>,
    ) -> Vec<f64> {
        for c in &mut found {
            let theta = wrap(c.theta);
            if theta.to_bits() != c.theta.to_bits() {
                c.slope = None;
            }
            c.theta = theta;
        }
        if found.is_empty() {
            return Vec::new();
        }
        found.sort_by(|x, y| x.theta.total_cmp(&y.theta));
        let d1 = self.derivative_bound(1);
        let steep = 4.0 * (2.0 * eta * self.derivative_bound(2)).sqrt();
        let same = |x: f64, y: f64| {
            let mid = 0.5 * (x + y);
            let apart = models
                .is_some_and(|m| m.exceeds(mid, 2.0 * eta + 2.0 * d1 * EPS * mid.abs().max(1.0)));
            y - x <= 4.0 * EPS * y.abs().max(1.0) || (!apart && self.is_zero_at(mid, eta))
        };
        let mut groups: Vec<Vec<Candidate>> = vec![vec![found[0]]];
        for w in found.windows(2) {
            match groups.last_mut() {
                Some(g) if same(w[0].theta, w[1].theta) => g.push(w[1]),
                _ => groups.push(vec![w[1]]),
            }
        }
        let last = found[found.len() - 1].theta;
        // across the seam: the last group continues the first one
        if groups.len() > 1
            && same(last - TAU, found[0].theta)
            && let Some(last) = groups.pop()
        {
            let mut joined: Vec<Candidate> = last
                .into_iter()
                .map(|c| Candidate {
                    theta: c.theta - TAU,
                    slope: None,
                })
                .collect();
            joined.append(&mut groups[0]);
            groups[0] = joined;
        }
        let mut out: Vec<f64> = groups
            .iter()
            .map(|g| match g.as_slice() {
                [c] if c.slope.is_some_and(|d| d.abs() > steep) => c.theta,
                _ => {
                    let thetas: Vec<f64> = g.iter().map(|c| c.theta).collect();
                    wrap(self.representative(&thetas, eta))
                }
            })
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }

    /// One value for a group (sorted, nonempty) of accepted values that are
    /// one root: the member of smallest `|p|`, replaced by the critical point of
    /// `p` when the group looks like a tangency (several members, or
    /// `|p'| <= 4 sqrt(η |p''|)`) and that point is within the group and at
    /// rounding level.
    fn representative(&self, group: &[f64], eta: f64) -> f64 {
        let abs_p = |x: f64| self.eval(x).abs();
        let best = group
            .iter()
            .copied()
            .min_by(|&x, &y| abs_p(x).total_cmp(&abs_p(y)))
            .unwrap_or(0.0);
        let WithTwoDerivatives {
            value: p,
            first: dp,
            second: d2p,
        } = self.eval_with_two_derivatives(best);
        let tangent = group.len() > 1 || dp.abs() <= 4.0 * (eta * d2p.abs()).sqrt();
        if !tangent {
            return best;
        }
        let width = (2.0 * eta / d2p.abs()).sqrt();
        let span = group[group.len() - 1] - group[0];
        let radius = (span + 4.0 * width).min(MAX_ACCEPT);
        match self.critical_point(best, radius) {
            Some(tc) if abs_p(tc) <= eta.max(p.abs()) => tc,
            _ => best,
        }
    }

    /// `Σ_k k^l (|a_k| + |b_k|)`, a bound on `|p^{(l)}|` over the circle.
    fn derivative_bound(&self, l: i32) -> f64 {
        self.a
            .iter()
            .zip(&self.b)
            .enumerate()
            .map(|(i, (a, b))| ((i + 1) as f64).powi(l) * (a.abs() + b.abs()))
            .sum()
    }
}
