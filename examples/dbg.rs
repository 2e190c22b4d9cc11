use std::time::Instant;
use stickslip::engine::event::*;
use stickslip::*;
fn main() {
    let scene = Scene::default();
    for _ in 0..3 {
        let t = Instant::now();
        let (sig, motor) = simulation::build(&scene).unwrap();
        let t_build = t.elapsed();
        let t = Instant::now();
        let eng = EventEngine::new(&sig, &motor, EventOptions::default());
        let t_engine = t.elapsed();
        let t = Instant::now();
        let r = simulation::run_with(eng, &scene, &motor).unwrap();
        let t_run = t.elapsed();
        println!(
            "build {:?} engine {:?} run {:?} periods {}",
            t_build, t_engine, t_run, r.work.periods
        );
    }
    let r = stickslip::check::check(&scene, &[5000]).unwrap();
    println!("{}", r.to_text());
    let _ = r;
}
