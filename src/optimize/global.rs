//! The global stage: a seeded Latin hypercube over the design space and
//! the choice of starting points for the local refinement (docs/model.md
//! section 15).
//!
//! The box is every amplitude direction in the positive orthant (angles
//! `t_j` in `[0, pi/2]`; negative amplitudes are phases shifted by `pi`,
//! so nothing is left out) times every relative phase (`psi_k` in
//! `[0, 2 pi)`). A Latin hypercube of `m` points cuts each coordinate into
//! `m` equal strata and puts one point in each, the strata of the
//! coordinates paired at random: every coordinate is covered evenly
//! whatever `m`. The random numbers come from ChaCha8 seeded with the
//! user's seed, whose stream is fixed by its specification, so the same
//! seed gives the same points on every machine and thread count.
//!
//! The starts of the local refinement are the best candidates by merit
//! that lie at least a given [`Shape::distance`] apart, so that several
//! refinements do not climb the same hill from neighbouring points.

use super::params::Shape;
use rand::rngs::ChaCha8Rng;
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use std::f64::consts::{FRAC_PI_2, TAU};

/// `count` Latin hypercube samples of the design space of `n` harmonics
/// (module docs), from `seed`.
pub(super) fn samples(n: usize, count: usize, seed: u64) -> Vec<Shape> {
    let dims = 2 * (n - 1);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // One column of stratum indices per coordinate, each shuffled.
    let columns: Vec<Vec<usize>> = (0..dims)
        .map(|_| {
            let mut strata: Vec<usize> = (0..count).collect();
            strata.shuffle(&mut rng);
            strata
        })
        .collect();
    (0..count)
        .map(|i| {
            let unit: Vec<f64> = columns
                .iter()
                .map(|col| (col[i] as f64 + rng.random::<f64>()) / count as f64)
                .collect();
            Shape {
                angles: unit[..n - 1].iter().map(|u| u * FRAC_PI_2).collect(),
                phases: unit[n - 1..].iter().map(|u| u * TAU).collect(),
            }
        })
        .collect()
}

/// Indices of at most `k` starting points: candidates in decreasing order
/// of merit (ties by index), each at least `separation` away from every
/// one taken before; candidates with merit `-inf` are never taken.
pub(super) fn starts(shapes: &[Shape], merits: &[f64], k: usize, separation: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..shapes.len()).collect();
    order.sort_by(|&a, &b| merits[b].total_cmp(&merits[a]).then(a.cmp(&b)));
    let mut taken: Vec<usize> = Vec::with_capacity(k);
    for i in order {
        if taken.len() == k || merits[i] == f64::NEG_INFINITY || merits[i].is_nan() {
            break;
        }
        if taken
            .iter()
            .all(|&j| shapes[i].distance(&shapes[j]) >= separation)
        {
            taken.push(i);
        }
    }
    taken
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_stratum_holds_one_sample() {
        let count = 16;
        let s = samples(3, count, 7);
        assert_eq!(s.len(), count);
        for j in 0..2 {
            let mut strata: Vec<usize> = s
                .iter()
                .map(|x| (x.angles[j] / FRAC_PI_2 * count as f64) as usize)
                .collect();
            strata.sort();
            assert_eq!(strata, (0..count).collect::<Vec<_>>(), "angle {j}");
            let mut strata: Vec<usize> = s
                .iter()
                .map(|x| (x.phases[j] / TAU * count as f64) as usize)
                .collect();
            strata.sort();
            assert_eq!(strata, (0..count).collect::<Vec<_>>(), "phase {j}");
        }
        assert_eq!(s, samples(3, count, 7), "same seed, same points");
        assert_ne!(s, samples(3, count, 8), "another seed, other points");
    }

    #[test]
    fn starts_are_apart_and_best_first() {
        let shapes: Vec<Shape> = [0.1, 0.1001, 0.5, 0.9]
            .iter()
            .map(|a| Shape {
                angles: vec![*a],
                phases: vec![0.0],
            })
            .collect();
        let merits = [3.0, 2.9, 1.0, f64::NEG_INFINITY];
        assert_eq!(starts(&shapes, &merits, 4, 0.01), vec![0, 2]);
    }
}
