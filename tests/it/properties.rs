//! Property test (issue 5, item 4): over random kernels, forms, smoothing lengths, stresses and
//! wave numbers, no output is NaN or infinite, and the closed forms agree with the numeric route
//! (1e−8 relative to the curve's scale).

use crate::common;

use common::*;
use proptest::prelude::*;
use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::closed_form as cf;

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn closed_forms_agree_and_nothing_is_nan(
        ki in 0usize..11,
        ht in 0.0f64..1.0,
        sig in -0.9f64..0.9,
        kt in 1e-6f64..1.0,
        which in 0usize..6,
    ) {
        let k = kernel::all()[ki];
        let (lo, hi) = k.customary_h();
        let h = lo + ht * (hi - lo);
        let kap = kt * std::f64::consts::PI;
        let r = k.zeta() * h;
        let (form, shape) = [
            (FormKind::Classical, ShapeFamily::Sph),
            (FormKind::Nonlocal, ShapeFamily::Sph),
            (FormKind::Local, ShapeFamily::Corrected),
            (FormKind::TotalLagrangian, ShapeFamily::Sph),
            (FormKind::LagrangianStressPoints, ShapeFamily::Mls),
            (FormKind::EulerianNodal, ShapeFamily::Sph),
        ][which];
        let l = lin(form, k.name(), shape, h, sig);
        let num = l.omega2(kap).0;
        prop_assert!(num.is_finite());
        prop_assert!(l.growth(kap).unwrap().is_finite());
        let phi = shape_fn(shape, k.name(), h);
        let closed = |q: f64| -> f64 {
            match form {
                FormKind::Classical | FormKind::Nonlocal | FormKind::Local => {
                    derived_omega2(form, k.name(), h, sig, q)
                }
                FormKind::TotalLagrangian => cf::b00_eq82_lagrangian_nodal(&phi, r, sig, q),
                FormKind::LagrangianStressPoints => cf::b00_eq103_lagrangian_stress_points(&phi, r, sig, q),
                _ => cf::b00_eq74_eulerian_nodal(&phi, r, sig, q),
            }
        };
        let scale = grid(32).iter().map(|&q| closed(q).abs()).fold(0.0, f64::max);
        let c = closed(kap);
        prop_assert!(c.is_finite());
        prop_assert!((num - c).abs() <= 1e-8 * scale.max(1e-12), "{:?} {} h={} σ̄={} κ={}: {} vs {}", form, k.name(), h, sig, kap, num, c);
    }
}
