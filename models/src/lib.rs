//! The built-in Chaplygin models.
