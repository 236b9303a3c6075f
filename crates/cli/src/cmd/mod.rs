//! One module per command group.
pub mod bench;
pub mod color;
pub mod demo;
pub mod surface;
pub mod thinfilm;
