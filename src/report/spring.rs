//! The spring's reading in the run report (docs/model.md section 17): the
//! keys of `run --json` and the lines of the text summary.

use crate::simulation::SpringReading;

/// The reading's JSON keys, values and units, in the order the text
/// prints them.
pub(super) fn spring_figures(r: &SpringReading) -> [(&'static str, f64, &'static str); 5] {
    let p = &r.profile;
    [
        ("spring_force_mean", p.force_mean, "N"),
        ("spring_force_max", p.force_max, "N"),
        ("spring_force_min", p.force_min, "N"),
        ("spring_position_mean", p.position_mean, "m"),
        ("contact_fraction", p.contact_fraction, ""),
    ]
}
