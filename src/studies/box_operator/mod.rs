//! The exact linear operator of a finite particle set (a solver run linearised about its rest
//! state), dense, and its fastest growth rate: the Swegle study's box prediction.

mod dense;

pub use dense::{MAX_DENSE_DOFS, box_growth};
