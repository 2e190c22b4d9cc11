//! The datasheet block: the five numbers vendors state for an inertia
//! drive (docs/model.md section 9), each with its unit.
//!
//! | key | unit | value |
//! | --- | --- | --- |
//! | `max_speed` | m/s | the no-load speed `abs(v_inf(0))` |
//! | `stall_force` | N | `abs(F_stall)` ([`super::stall`]) |
//! | `holding_force` | N | `mu_0 F_c`: the load a slider at rest (rod not moving) holds |
//! | `max_output_power` | W | the largest `F v_inf` ([`super::output_power`]); 0 without drive |
//! | `recommended_load` | N | `stall_force / 2`, the usual vendor rule |
//!
//! Magnitudes, whatever the drive direction; the characteristic says
//! which way the drive moves.

/// One datasheet entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DatasheetEntry {
    /// The key in JSON.
    pub key: &'static str,
    /// The value (`None`: not available).
    pub value: Option<f64>,
    /// Its SI unit.
    pub unit: &'static str,
}

/// The datasheet block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Datasheet {
    /// No-load speed (m/s).
    pub max_speed: f64,
    /// Stall force (N).
    pub stall_force: Option<f64>,
    /// Holding force at rest, `mu_0 F_c` (N).
    pub holding_force: f64,
    /// Largest mechanical output power (W).
    pub max_output_power: Option<f64>,
    /// Half the stall force (N).
    pub recommended_load: Option<f64>,
}

impl Datasheet {
    /// The block from the no-load speed, the stall force, the holding
    /// force and the largest output power (signed values are taken by
    /// magnitude).
    pub fn new(
        no_load_speed: f64,
        stall_force: Option<f64>,
        holding_force: f64,
        max_output_power: Option<f64>,
    ) -> Self {
        let stall = stall_force.map(f64::abs);
        Datasheet {
            max_speed: no_load_speed.abs(),
            stall_force: stall,
            holding_force,
            max_output_power: max_output_power.map(f64::abs),
            recommended_load: stall.map(|f| f / 2.0),
        }
    }

    /// The entries in the order of the table above.
    pub fn entries(&self) -> [DatasheetEntry; 5] {
        [
            DatasheetEntry {
                key: "max_speed",
                value: Some(self.max_speed),
                unit: "m/s",
            },
            DatasheetEntry {
                key: "stall_force",
                value: self.stall_force,
                unit: "N",
            },
            DatasheetEntry {
                key: "holding_force",
                value: Some(self.holding_force),
                unit: "N",
            },
            DatasheetEntry {
                key: "max_output_power",
                value: self.max_output_power,
                unit: "W",
            },
            DatasheetEntry {
                key: "recommended_load",
                value: self.recommended_load,
                unit: "N",
            },
        ]
    }
}
