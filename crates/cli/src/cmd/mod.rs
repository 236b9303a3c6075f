//! One module per command group.
pub mod color;
pub mod demo;
