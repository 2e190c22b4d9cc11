//! The driven rod's parts of the reports (docs/model.md section 16): its
//! figures by their output keys and the actuator's sensitivities, as JSON
//! and as lines of the text summary.

use super::{Map, Value, json, number};
use crate::engine::DriveProfile;
use crate::sensitivity::ActuatorSensitivities;
use std::fmt::Write as _;

/// A driven rod's figures by their output keys (docs/interface.md).
pub(super) fn drive_figures(d: &DriveProfile) -> [(&'static str, f64); 6] {
    [
        ("rod_deviation_max", d.rod_deviation_max),
        ("rod_deviation_rms", d.rod_deviation_rms),
        ("voltage_peak", d.voltage_peak),
        ("voltage_rms", d.voltage_rms),
        ("current_peak", d.current_peak),
        ("current_rms", d.current_rms),
    ]
}

/// The `sensitivities` of a driven rod (`run --json --sensitivities`):
/// `held_fixed` is `"voltage"`, one object per real-actuator field with
/// `value` (`dv_inf/dtheta`), `unit` and `relative`
/// (`theta / v_inf dv_inf/dtheta`); `null` and `sensitivities_unavailable`
/// with the reason when there are none.
pub(crate) fn add_actuator_sensitivities_json(
    object: &mut Value,
    sensitivities: &Result<ActuatorSensitivities, String>,
) {
    let Value::Object(m) = object else {
        return;
    };
    m.insert("held_fixed".into(), json!("voltage"));
    match sensitivities {
        Ok(s) => {
            let mut entries = Map::new();
            for e in &s.entries {
                entries.insert(
                    e.field.into(),
                    json!({
                        "value": number(e.value),
                        "unit": e.unit,
                        "relative": number(e.value * e.at / s.v_inf),
                    }),
                );
            }
            m.insert("sensitivities".into(), Value::Object(entries));
        }
        Err(reason) => {
            m.insert("sensitivities".into(), Value::Null);
            m.insert("sensitivities_unavailable".into(), json!(reason));
        }
    }
}

/// A driven rod's sensitivities as lines of the text summary.
pub(crate) fn actuator_sensitivities_text(
    sensitivities: &Result<ActuatorSensitivities, String>,
) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "sensitivities held fixed: the voltage (designed for [actuator], or given in [voltage])"
    );
    match sensitivities {
        Ok(s) => {
            let _ = writeln!(out, "sensitivities of v_inf to the real actuator:");
            for e in &s.entries {
                let _ = writeln!(
                    out,
                    "  d/d {:<30} {:.6e} {}  (relative {:.4})",
                    e.field,
                    e.value,
                    e.unit,
                    e.value * e.at / s.v_inf
                );
            }
        }
        Err(reason) => {
            let _ = writeln!(out, "sensitivities: none ({reason})");
        }
    }
    out
}
