//! The compile-fail cases of `chaplygin::model!` (`tests/compile_fail/`,
//! checked by trybuild): a package of its own so that trybuild's project
//! builds the macro and nothing more. The cases call the macro by its own
//! crate's path, `chaplygin_macros::model!`, which `chaplygin::model!`
//! re-exports: the same macro, the same errors on the same tokens.
