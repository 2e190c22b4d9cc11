//! The one table of symbols: for each quantity the project names (an
//! indicator, a sweep axis, a motor or signal parameter), its name in files
//! and columns, its symbol as typeset in figures, its SI unit and a short
//! description. The indicator table (`src/indicator.rs`) takes its units
//! from here, and every figure's labels take their symbols from here, so a
//! column, its axis label and its legend entry cannot disagree.
//!
//! Contract: [`Symbol::quantity`] is in the figures' quantity markup
//! (`src/plot/text.rs`): between `$` signs, letters italic, `_x` or `_{…}`
//! a subscript, `^x` or `^{…}` a superscript, never a space inside; units
//! are upright and plain. [`Symbol::label`] is the axis label
//! "description quantity (unit)" (no unit for a ratio, unit `1`); no
//! label shows an underscore once typeset. Every key is unique.

/// A quantity's name, symbol, unit and description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Symbol {
    /// Name in scene files, JSON keys and sweep columns (`v_inf`).
    pub key: &'static str,
    /// The symbol in the quantity markup (`$v_∞$`).
    pub quantity: &'static str,
    /// SI unit, upright (`m/s`); `1` for a ratio.
    pub unit: &'static str,
    /// A short description (`steady-state velocity`), empty when the
    /// symbol says it all.
    pub description: &'static str,
}

impl Symbol {
    /// The unit in parentheses, or nothing for a ratio.
    pub fn unit_suffix(&self) -> String {
        if self.unit == "1" {
            String::new()
        } else {
            format!(" ({})", self.unit)
        }
    }

    /// Axis label: description, symbol and unit (`steady-state velocity
    /// $v_∞$ (m/s)`).
    pub fn label(&self) -> String {
        let lead = if self.description.is_empty() {
            String::new()
        } else {
            format!("{} ", self.description)
        };
        format!("{lead}{}{}", self.quantity, self.unit_suffix())
    }

    /// Short axis label: symbol and unit (`$v_∞$ (m/s)`).
    pub fn short_label(&self) -> String {
        format!("{}{}", self.quantity, self.unit_suffix())
    }
}

const fn s(
    key: &'static str,
    quantity: &'static str,
    unit: &'static str,
    description: &'static str,
) -> Symbol {
    Symbol {
        key,
        quantity,
        unit,
        description,
    }
}

/// Every symbol, indicators first (in `Indicator::ALL` order).
pub const SYMBOLS: &[Symbol] = &[
    s("v_inf", "$v_∞$", "m/s", "steady-state velocity"),
    s("startup_time", "$Tp_{0.99}$", "s", "start-up time"),
    s("smoothness", "$ζ$", "1", "smoothness"),
    s("durability", "$δ$", "1/N", "durability"),
    s(
        "friction_energy",
        "$W_f$",
        "J",
        "friction energy per period",
    ),
    s("stiction_fraction", "$s$", "1", "stiction fraction"),
    s(
        "velocity_per_power",
        "$v_∞/S$",
        "m/(s VA)",
        "velocity per power",
    ),
    s("startup_periods", "$p_{0.99}$", "1", "start-up periods"),
    s("v_p", "$v_p$", "m/s", "mean velocity"),
    s("p", "$p$", "1", "period"),
    s("harmonics", "$n$", "1", "number of harmonics"),
    s("level", "$n$√$κ$", "1", "level"),
    s("sqrt_kappa", "√$κ$", "1", ""),
    s("kappa", "$κ$", "1", ""),
    s("sigma", "$σ$", "1", "sigma factors"),
    s("stroke", "$x̂_R$", "m", "stroke"),
    s("f_max", "$f_{max}$", "Hz", "highest frequency"),
    s("f_allowed", "$f_{allowed}$", "Hz", "allowed frequency"),
    s("f_0", "$f_0$", "Hz", "fundamental frequency"),
    s("d_k", "$d_k$", "1", "amplitude"),
    s("contact_force", "$F_c$", "N", "contact force"),
    s("mu_static", "$µ_0$", "1", "static friction coefficient"),
    s("mu_dynamic", "$µ_d$", "1", "dynamic friction coefficient"),
    s("slider_mass", "$m_s$", "kg", "slider mass"),
    s("extra_acceleration", "$g_t$", "m/s²", "load acceleration"),
    s("spring.stiffness", "$k$", "N/m", "spring stiffness"),
    s("spring.damping", "$b$", "N s/m", "spring damping"),
    s("spring.gap", "$x_{gap}$", "m", "gap of the free end"),
    s("spring.preload", "$F_p$", "N", "spring preload"),
    s("spring_force_mean", "$F_{mean}$", "N", "mean spring force"),
    s("spring_force_max", "$F_{max}$", "N", "largest spring force"),
    s("spring_force_min", "$F_{min}$", "N", "least spring force"),
    s(
        "spring_position_mean",
        "$x_{mean}$",
        "m",
        "mean slider position",
    ),
    s("contact_fraction", "$t_c/T$", "1", "contact fraction"),
    s("load", "$F$", "N", "load force"),
    s("stall_force", "$F_{stall}$", "N", "stall force"),
    s("holding_force", "$µ_0F_c$", "N", "holding force"),
    s("a_0", "$a_0$", "m/s²", "stick band"),
    s("output_power", "$P_{out}$", "W", "output power"),
    s("t", "$t$", "s", "time"),
    s("x_R", "$x_R$", "m", "rod position"),
    s("v_R", "$v_R$", "m/s", "rod velocity"),
    s("a_R", "$a_R$", "m/s²", "rod acceleration"),
    s("x_S", "$x_S$", "m", "slider position"),
    s("v_S", "$v_S$", "m/s", "slider velocity"),
    s("a_S", "$a_S$", "m/s²", "slider acceleration"),
    s("period", "$T$", "s", "period"),
    s("stiffness", "$c$", "N/m", "actuator stiffness"),
    s("stiffness_error", "Δ$c$/$c$", "1", "stiffness error"),
    s("rod_deviation", "$x_R$−$x_{sig}$", "m", "rod deviation"),
];

/// The symbol named `key`, if the table has it.
pub fn symbol(key: &str) -> Option<&'static Symbol> {
    SYMBOLS.iter().find(|s| s.key == key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_unique_and_quantities_are_closed_markup_without_spaces() {
        for (i, a) in SYMBOLS.iter().enumerate() {
            assert!(SYMBOLS[..i].iter().all(|b| b.key != a.key), "{}", a.key);
            assert_eq!(a.quantity.matches('$').count() % 2, 0, "{}", a.key);
            assert!(!a.quantity.contains(' '), "{}", a.key);
            assert!(!a.unit.contains('_') && !a.description.contains('_'));
        }
    }

    #[test]
    fn a_label_has_symbol_and_unit_and_a_ratio_no_unit() {
        assert_eq!(
            symbol("v_inf").unwrap().label(),
            "steady-state velocity $v_∞$ (m/s)"
        );
        assert_eq!(symbol("smoothness").unwrap().label(), "smoothness $ζ$");
        assert_eq!(symbol("kappa").unwrap().short_label(), "$κ$");
    }
}
