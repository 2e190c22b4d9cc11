use stickslip::signal::*;
use stickslip::*;
fn main() {
    for (n, sigma) in [(2, true), (2, false), (5, false), (1, false)] {
        let motor = Motor::default();
        let Signal::Fourier(sig) = Signal::build(
            &SignalSpec::Fourier {
                shape: IdealShape {
                    stroke: 25e-6,
                    kappa: 1e6,
                    duty: 1.0,
                },
                harmonics: n,
                sigma,
            },
            &motor,
        )
        .unwrap() else {
            panic!()
        };
        println!("n={n} sigma={sigma} median={}", sig.velocity_median());
    }
}
