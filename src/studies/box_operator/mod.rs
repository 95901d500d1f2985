//! The exact linear operator of a finite particle set (a solver run linearised about its rest
//! state) and its fastest growth rate: the Swegle study's box prediction. Applied matrix-free
//! ([`BoxOperator`]) to find the fastest mode of a box of any size by thick-restart Arnoldi
//! ([`box_growth_iterative`]); dense ([`box_growth`]), every eigenvalue, as the reference for
//! small boxes.

mod arnoldi;
mod dense;
mod iterative;
mod product;

pub use arnoldi::{ArnoldiParams, FastestMode, fastest_mode};
pub use dense::{MAX_DENSE_DOFS, box_growth, box_spectrum, growth_of};
pub use iterative::{
    ATOL, BASIS, IterativeGrowth, KEEP, MAX_PRODUCTS, RTOL, STABLE_PROBE, Start,
    box_growth_iterative,
};
pub use product::BoxOperator;
