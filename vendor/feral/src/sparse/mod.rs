pub mod csc;
