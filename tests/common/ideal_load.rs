//! Closed forms of the continuous ideal signal (`kind = "ideal"`,
//! `duty = 1`) under a load `g_t` (docs/model.md section 14.5): `v_inf` in
//! the stick-slip and the slip-slip regime, its derivatives with respect
//! to `g_t`, `a_d` and `a_0` (the signal's `a_R = kappa a_0` and
//! `T = sqrt(2 x_Rmax / a_R)` follow `a_0`), and the stall load.
//!
//! `a_r` is the rod acceleration `kappa a_0`, `period` = `T` = `t_1`.

/// The steady-state regime of the continuous ideal signal under `g_t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IdealRegime {
    /// `a_R - a_0 <= g_t < a_d`: the rod's acceleration lies in the stick
    /// band; after each jump the slider slides back, then sticks.
    StickSlip,
    /// `-a_d < g_t < a_R - a_0`: the slider slides back, reverses, slides
    /// forward to the jump.
    SlipSlip,
}

/// `v_inf`, `dv_inf/dg_t`, `dv_inf/da_d` and `dv_inf/da_0` (at fixed
/// `kappa` and stroke) of the continuous ideal signal, with its regime;
/// `None` outside both regimes (a run-away).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdealLoad {
    /// Which regime.
    pub regime: IdealRegime,
    /// `v_inf` (m/s).
    pub v_inf: f64,
    /// `dv_inf / dg_t` (s).
    pub d_g_t: f64,
    /// `dv_inf / da_d` (s).
    pub d_a_d: f64,
    /// `dv_inf / da_0` at fixed `kappa` and stroke (s).
    pub d_a_0: f64,
}

/// The closed forms at rod acceleration `a_r = kappa a_0`, period
/// `period = sqrt(2 x_Rmax / a_r)`, accelerations `a_0`, `a_d`, `g_t`.
///
/// Stick-slip: after the jump the slider (at `a_R T`) slides back with
/// `-a_d + g_t` until the rod catches up at `t_s = a_R T / (a_R + a_d - g_t)`
/// and sticks to the period end:
/// `v_inf = (a_R T / 2)(1 + a_R / (a_R + a_d - g_t))`.
///
/// Slip-slip: it slides back with `-a_d + g_t` until
/// `t* = T (a_d + g_t) / (2 a_d)`, reverses (`a_R > a_0 + g_t`) and slides
/// forward with `a_d + g_t`:
/// `v_inf = T (a_R (a_d + g_t) / (2 a_d) + (a_d^2 - g_t^2) / (4 a_d))`.
pub fn ideal_load(a_r: f64, period: f64, a_0: f64, a_d: f64, g_t: f64) -> Option<IdealLoad> {
    let (a, t) = (a_r, period);
    // dT/da_R = -T / (2 a_R), and a_R = kappa a_0.
    let kappa = a_r / a_0;
    let dt_da = -t / (2.0 * a);
    if a - a_0 <= g_t && g_t < a_d {
        let q = a + a_d - g_t;
        let v = 0.5 * a * t * (1.0 + a / q);
        // d(a_R T)/da_R = T / 2 (a_R T = sqrt(2 x_Rmax a_R)).
        let dv_da = 0.25 * t * (1.0 + a / q) + 0.5 * a * t * (a_d - g_t) / (q * q);
        Some(IdealLoad {
            regime: IdealRegime::StickSlip,
            v_inf: v,
            d_g_t: 0.5 * a * t * a / (q * q),
            d_a_d: -0.5 * a * t * a / (q * q),
            d_a_0: kappa * dv_da,
        })
    } else if -a_d < g_t && g_t < a - a_0 && g_t < a_d {
        let u = (a_d + g_t) / (2.0 * a_d);
        let w = (a_d * a_d - g_t * g_t) / (4.0 * a_d);
        let v = t * (a * u + w);
        Some(IdealLoad {
            regime: IdealRegime::SlipSlip,
            v_inf: v,
            d_g_t: t * (a - g_t) / (2.0 * a_d),
            d_a_d: t * (-a * g_t / (2.0 * a_d * a_d) + (a_d * a_d + g_t * g_t) / (4.0 * a_d * a_d)),
            d_a_0: kappa * (t * u + dt_da * (a * u + w)),
        })
    } else {
        None
    }
}

/// The stall load of the continuous ideal signal as an extra acceleration:
/// `g_t = -a_d` (a load `F = m_s a_d = mu_d F_c`), where the slip-slip
/// `v_inf = T (a_d + g_t)(2 a_R + a_d - g_t) / (4 a_d)` reaches 0; it is
/// in the slip-slip regime when `a_R - a_0 > -a_d`. `None` otherwise (the
/// slider then sticks up to `g_t = a_R - a_0` and runs away beyond).
pub fn stall_extra_acceleration(a_r: f64, a_0: f64, a_d: f64) -> Option<f64> {
    (a_r - a_0 > -a_d).then_some(-a_d)
}
