//! What an output was made by and from: the program version and a
//! fingerprint of the resolved scene, so that a result can be traced to
//! its inputs and a stored result can be recognised as stale.
//!
//! The fingerprint is the SHA-256 of [`Scene::to_toml`], the resolved scene
//! with every field written out (defaults included; floats in shortest
//! round-trip form), so two scenes have the same fingerprint exactly when
//! every parameter is bit-identical. It is printed as its first 16
//! hexadecimal digits (64 bits).

use crate::scene::Scene;
use sha2::{Digest, Sha256};

/// The program version, `CARGO_PKG_VERSION`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The fingerprint of a resolved scene: 16 hexadecimal digits.
pub fn scene_hash(scene: &Scene) -> String {
    let digest = Sha256::digest(scene.to_toml().as_bytes());
    digest[..8].iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_changes_with_any_parameter_and_only_then() {
        let a = Scene::default();
        let mut b = Scene::default();
        assert_eq!(scene_hash(&a), scene_hash(&b));
        assert_eq!(scene_hash(&a).len(), 16);
        b.motor.slider_mass = f64::from_bits(a.motor.slider_mass.to_bits() + 1);
        assert_ne!(scene_hash(&a), scene_hash(&b));
        let mut c = Scene::default();
        c.run.max_periods += 1;
        assert_ne!(scene_hash(&a), scene_hash(&c));
    }
}
