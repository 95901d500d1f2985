use sphstab::forms::{FormKind, ModelParams};
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::vonneumann::linearise::{Lattice1D, Linearisation};
fn main() {
    let k = sphstab::kernel::by_name("efg-quartic").unwrap();
    for form in [FormKind::TotalLagrangian, FormKind::LagrangianStressPoints, FormKind::EulerianStressPoints, FormKind::Classical, FormKind::Nonlocal, FormKind::Local, FormKind::LeastSquares] {
      for sig in [0.0, 0.2] {
        let p = ModelParams { form, shape: ShapeFamily::Mls, kp: KernelParams{kernel:k, h:1.5}, modulus:1.0, rho0:1.0, sigma0:sig, c_partition:0.5, alpha_s:0.0, av:None, dx:1.0};
        let p = if form==FormKind::Local { ModelParams{shape: ShapeFamily::Corrected, ..p} } else {p};
        match Linearisation::new(p, Lattice1D::default()) {
            Ok(lin) => {
                let mut mx = f64::MIN; let mut kmax=0.0; let mut mn = f64::MAX;
                for i in 1..=1024 { let kap = std::f64::consts::PI*i as f64/1024.0; let (w2,_) = lin.omega2(kap); if w2>mx {mx=w2;kmax=kap;} mn = mn.min(w2);}
                println!("{:?} σ̄={sig}: max ω² = {mx:.12} at κ={:.4}π, min {mn:.3e}, ω²(π)={:.3e}", form, kmax/std::f64::consts::PI, lin.omega2(std::f64::consts::PI).0);
            }
            Err(e) => println!("{:?}: {e}", form),
        }
      }
    }
}
