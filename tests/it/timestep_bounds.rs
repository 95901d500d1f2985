//! [B00 §5] time-step bounds: the bound is never below the exact maximum eigenvalue
//! (D_mx ∈ {1.5, 2, 2.5, 3}), ratios printed.

use sphstab::kernel;
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::vonneumann::antiplane::Quadrature;
use sphstab::vonneumann::timestep_bounds::{bounds_1d, bounds_2d};

#[test]
fn bounds_hold_in_1d_eq136() {
    let k = kernel::by_name("efg-cubic").unwrap();
    for gauss2 in [false, true] {
        for d in [1.5, 2.0, 2.5, 3.0] {
            let b = bounds_1d(
                ShapeFamily::Mls,
                KernelParams { kernel: k, h: d },
                gauss2,
                2048,
            )
            .unwrap();
            let r = b.ratios();
            eprintln!(
                "1D {} D_mx={d}: exact λ_max = {:.5} (consistent mass {:.5}), ratios {:?}, eq 136/consistent {:.3}",
                if gauss2 { "2-point Gauss" } else { "nodal" },
                b.exact,
                b.exact_consistent,
                r,
                b.closed[0].1 / b.exact_consistent
            );
            for (name, ratio) in r {
                assert!(ratio >= 1.0, "{name} D_mx={d}: bound/exact = {ratio}");
            }
        }
    }
}

#[test]
fn bounds_hold_in_2d_eq146_eq148() {
    let k = kernel::by_name("efg-cubic").unwrap();
    for d in [1.5, 2.0, 2.5, 3.0] {
        let b = bounds_2d(
            ShapeFamily::Mls,
            KernelParams { kernel: k, h: d },
            Quadrature::Cell2x2,
            48,
        )
        .unwrap();
        let r = b.ratios();
        eprintln!(
            "2D cell 2×2 D_mx={d}: exact λ_max = {:.5} (consistent mass {:.5}), ratios {:?}, eq146/consistent {:.3}, eq148/consistent {:.3}",
            b.exact,
            b.exact_consistent,
            r,
            b.closed[0].1 / b.exact_consistent,
            b.closed[1].1 / b.exact_consistent
        );
        for (name, ratio) in r {
            assert!(ratio >= 1.0, "{name} D_mx={d}: bound/exact = {ratio}");
        }
    }
}
