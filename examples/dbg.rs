use std::time::Instant;
use stickslip::signal::*;
use stickslip::*;
fn f(kappa: f64, n: usize, sigma: bool) -> SignalSpec {
    SignalSpec::Fourier {
        shape: IdealShape {
            stroke: 25e-6,
            kappa,
            duty: 1.0,
        },
        harmonics: n,
        sigma,
    }
}
fn main() {
    let mut cases: Vec<(String, Scene)> = vec![];
    for kappa in [1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6] {
        for sigma in [false, true] {
            for n in [1, 2, 5] {
                cases.push((
                    format!("kappa {kappa} n {n} sigma {sigma}"),
                    Scene {
                        signal: f(kappa, n, sigma),
                        ..Scene::default()
                    },
                ));
            }
        }
    }
    for n in [16, 32, 64] {
        for sigma in [false, true] {
            cases.push((
                format!("n {n} sigma {sigma}"),
                Scene {
                    signal: f(1.0, n, sigma),
                    ..Scene::default()
                },
            ));
        }
    }
    for (mu0, mud) in [(0.1736, 0.1736), (0.1736, 0.0)] {
        for kappa in [0.36, 36.0] {
            let mut s = Scene {
                signal: f(kappa, 5, true),
                ..Scene::default()
            };
            s.motor.mu_static = mu0;
            s.motor.mu_dynamic = mud;
            cases.push((format!("mu {mu0} {mud} kappa {kappa}"), s));
        }
    }
    for g in [-100.0, -130.0, -200.0, 100.0, 200.0] {
        let mut s = Scene::default();
        s.motor.extra_acceleration = g;
        cases.push((format!("g_t {g}"), s));
    }
    for g in [-100.0, -130.0, -200.0] {
        let mut s = Scene {
            signal: f(0.36, 5, true),
            ..Scene::default()
        };
        s.motor.extra_acceleration = g;
        cases.push((format!("stickheavy g_t {g}"), s));
    }
    for (m, fc) in [(1e-6, 1.0), (1.0, 1.0), (1e-3, 1e-3), (1e-3, 1e3)] {
        let mut s = Scene::default();
        s.motor.slider_mass = m;
        s.motor.contact_force = fc;
        cases.push((format!("m {m} F {fc}"), s));
    }
    for (name, s) in cases {
        let t = Instant::now();
        let r = simulation::run(&s);
        let el = t.elapsed();
        match r {
            Ok(r) => println!(
                "{name:40} v={:.6e} ±{:.1e} periods={} ev/per={} P'={:.4} t={:?}",
                r.indicators.v_inf,
                r.error.v_inf.unwrap(),
                r.transient.as_ref().unwrap().periods(),
                r.steady.stats.events.total(),
                r.steady.map_derivative,
                el
            ),
            Err(e) => println!("{name:40} ERR {e} t={el:?}"),
        }
    }
}
