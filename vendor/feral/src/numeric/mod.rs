pub mod condition;
pub mod factorize;
pub mod solve;
pub mod solver;
