//! The 2D argument types of the shape families: [`KernelParams2`] and [`eval2`], a thin wrapper
//! of [`crate::shape::eval_d`] with D = 2 (one definition of every family for every dimension;
//! see [`crate::shape`] for the table).

use crate::error::Result;
use crate::kernel::{self, Kernel};
use crate::scalar::Scalar;
use crate::shape::ShapeFamily;

/// A 2D vector of scalars.
pub type V2<S> = [S; 2];

/// Kernel parameters in 2D.
#[derive(Clone, Copy, Debug)]
pub struct KernelParams2 {
    /// The kernel.
    pub kernel: &'static dyn Kernel,
    /// Smoothing length.
    pub h: f64,
}

impl KernelParams2 {
    /// Support radius ζh.
    pub fn support(&self) -> f64 {
        self.kernel.zeta() * self.h
    }

    /// W(|d|) and ∇_x W(|x − x_J|) = −W'(r) d/r for d = x_J − x, differentiable through
    /// d = 0 ([`kernel::w_and_grad`]).
    #[inline]
    pub fn w_and_grad<S: Scalar>(&self, d: V2<S>) -> (S, V2<S>) {
        kernel::w_and_grad(self.kernel, self.h, d)
    }
}

/// Evaluates `(φ_J, ∇φ_J)` at x for all nodes `(d_J, V_J)`: [`crate::shape::eval_d`] with
/// D = 2. `out` is cleared and filled in node order; `x_abs` is used in error messages only.
pub fn eval2<S: Scalar>(
    family: ShapeFamily,
    kp: KernelParams2,
    nodes: &[(V2<S>, S)],
    x_abs: [f64; 2],
    out: &mut Vec<(S, V2<S>)>,
) -> Result<()> {
    crate::shape::eval_d(
        family,
        crate::shape::KernelParams {
            kernel: kp.kernel,
            h: kp.h,
        },
        nodes,
        x_abs[0],
        out,
    )
}
