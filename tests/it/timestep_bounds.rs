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

/// [B00] §5 on a finite body (`stiffness --body`): with a support just over one spacing the
/// MLS shapes of a linear basis are the linear finite element's hat functions (two nodes per
/// Gauss point), so the free–free bar is the linear-element chain, whose modes are
/// cos(kπj/(N − 1)) with λ_k = 4 sin²(kπ/(2(N − 1))) (row-sum mass) and
/// 6(1 − cos θ_k)/(2 + cos θ_k), θ_k = kπ/(N − 1) (consistent mass): λ_max = 4 and 12 (k = N − 1).
#[test]
fn finite_bar_with_hat_shapes_is_the_linear_element_chain() {
    use sphstab::studies::finite_body::finite_body;
    let k = kernel::by_name("efg-cubic").unwrap();
    for n in [5, 41] {
        let r = finite_body(
            1,
            n,
            k,
            1.0001,
            ShapeFamily::Mls,
            &sphstab::budget::Budget::default(),
        )
        .unwrap();
        assert!(
            (r.lambda_max_lumped - 4.0).abs() < 1e-10,
            "{n} nodes: lumped {}",
            r.lambda_max_lumped
        );
        let c = r.lambda_max_consistent.unwrap();
        assert!((c - 12.0).abs() < 1e-9, "{n} nodes: consistent {c}");
    }
}

/// The Lanczos route (beyond 1600 unknowns) against the dense one: the largest mode of a free
/// bar sits at its ends and decays into the interior within a few spacings, so the bars of
/// 1600 (dense) and 1601 nodes (Lanczos) share it to rounding; and the finite bar's λ_max is
/// never below the infinite lattice's (the boundary only adds), here by the 1/N² of a
/// windowed plane wave at most.
#[test]
fn finite_bar_lanczos_matches_dense_and_lies_above_the_lattice() {
    use sphstab::studies::finite_body::finite_body;
    let k = kernel::by_name("efg-cubic").unwrap();
    for d in [1.5, 2.5] {
        let dense = finite_body(
            1,
            1600,
            k,
            d,
            ShapeFamily::Mls,
            &sphstab::budget::Budget::default(),
        )
        .unwrap();
        let lanczos = finite_body(
            1,
            1601,
            k,
            d,
            ShapeFamily::Mls,
            &sphstab::budget::Budget::default(),
        )
        .unwrap();
        assert!(dense.dense && !lanczos.dense);
        let rel =
            (dense.lambda_max_lumped - lanczos.lambda_max_lumped).abs() / dense.lambda_max_lumped;
        assert!(
            rel < 1e-9,
            "D_max = {d}: dense {} Lanczos {}",
            dense.lambda_max_lumped,
            lanczos.lambda_max_lumped
        );
        let lattice = bounds_1d(
            ShapeFamily::Mls,
            KernelParams { kernel: k, h: d },
            true,
            2048,
        )
        .unwrap()
        .exact;
        let small = finite_body(
            1,
            101,
            k,
            d,
            ShapeFamily::Mls,
            &sphstab::budget::Budget::default(),
        )
        .unwrap();
        assert!(
            small.lambda_max_lumped >= lattice - 1e-3,
            "D_max = {d}: finite {} below the lattice {lattice}",
            small.lambda_max_lumped
        );
    }
}
