pub(crate) mod block_ldlt32;
pub mod equilibrate;
pub mod factor;
pub mod matrix;
pub(crate) mod rook;
#[doc(hidden)]
pub mod schur_kernel;
pub mod solve;
