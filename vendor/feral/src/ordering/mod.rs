pub mod amd;
pub mod elimination_tree;
pub mod postorder;
pub mod schur;
