pub mod mtx;
pub mod sidecar;
