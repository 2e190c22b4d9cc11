//! The spectral radius of a small square matrix, `max |lambda_i|` over
//! its eigenvalues, from its real Schur form (nalgebra's `try_schur`).
//!
//! Contract: `None` where an entry is not finite or the Schur iteration
//! does not converge within its iteration limit (it would otherwise run
//! without end on such input); the caller then has no contraction to
//! rely on.

use nalgebra::DMatrix;

/// Iterations the Schur decomposition may take (it takes some tens on the
/// period maps' 2x2 to 4x4 Jacobians).
const MAX_ITERATIONS: usize = 10_000;

/// `max |lambda_i|` of `m`, or `None` (module docs).
pub(crate) fn spectral_radius(m: &DMatrix<f64>) -> Option<f64> {
    if !m.iter().all(|x| x.is_finite()) {
        return None;
    }
    let schur = m.clone().try_schur(f64::EPSILON, MAX_ITERATIONS)?;
    let radius = schur
        .complex_eigenvalues()
        .iter()
        .map(|l| l.norm())
        .fold(0.0, f64::max);
    radius.is_finite().then_some(radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation by 90 degrees scaled by 1/2 has the eigenvalues `±i/2`
    /// (closed form): radius 1/2. A triangular matrix's eigenvalues are its
    /// diagonal. A matrix with a NaN or an infinity has none.
    #[test]
    fn radius_of_known_matrices_and_none_for_non_finite_entries() {
        let rotation = DMatrix::from_row_slice(2, 2, &[0.0, -0.5, 0.5, 0.0]);
        let r = spectral_radius(&rotation).expect("a radius");
        assert!((r - 0.5).abs() <= 1e-15, "{r}");
        let triangular =
            DMatrix::from_row_slice(3, 3, &[0.2, 5.0, 1.0, 0.0, -0.9, 3.0, 0.0, 0.0, 0.4]);
        let r = spectral_radius(&triangular).expect("a radius");
        assert!((r - 0.9).abs() <= 1e-14, "{r}");
        for bad in [f64::NAN, f64::INFINITY] {
            let m = DMatrix::from_row_slice(2, 2, &[1.0, bad, 0.0, 1.0]);
            assert_eq!(spectral_radius(&m), None);
        }
    }
}
