//! Not a correctness test: solver throughput (particle-steps per second) on a 200×200 block,
//! printed with `cargo test --release --test throughput_probe -- --nocapture --ignored`.

use sphstab::forms::{FormKind, Material2D, Model2D, ModelParams2D, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice2D;
use sphstab::shape::ShapeFamily;
use sphstab::shape2d::KernelParams2;
use sphstab::solver::{BoundaryDensity, Run2D};

#[test]
#[ignore = "timing probe, run on demand"]
fn throughput_200x200() {
    for (name, mat) in [
        ("hydro", Material2D::Hydro { bulk: 1.0 }),
        (
            "elastic",
            Material2D::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap(),
        ),
    ] {
        let p = ModelParams2D {
            form: FormKind::Classical,
            shape: ShapeFamily::Sph,
            kp: KernelParams2 {
                kernel: kernel::by_name("m4").unwrap(),
                h: 1.3,
            },
            material: mat,
            rho0: 1.0,
            c_partition: 0.5,
            av: None,
            art_stress: None,
        };
        let model = Model2D::periodic_patch(
            p,
            &Lattice2D::square(1.0).unwrap(),
            1.0,
            [200, 200],
            1.0,
            0.0,
        )
        .unwrap();
        let z = model.rest_state(1.0);
        let n = z.x.len();
        let mut run = Run2D::new(model, z, vec![false; n], BoundaryDensity::Evolve).unwrap();
        run.z.v[n / 2 + 100][0] = 1e-6;
        run.step(0.1).unwrap();
        let steps = 10;
        let t = std::time::Instant::now();
        for _ in 0..steps {
            run.step(0.1).unwrap();
        }
        let s = t.elapsed().as_secs_f64();
        eprintln!(
            "200×200 classical m4 h=1.3 {name}: {steps} steps in {s:.2} s = {:.3e} particle-steps/s ({:.0} ns per particle-step)",
            (n * steps) as f64 / s,
            s / (n * steps) as f64 * 1e9
        );
    }
}
