//! The integration tests of iridis-surface: one module a file, one test binary (README, "Tests").

mod afm_instruments;
mod common;
mod robustness;
mod surface;
mod unit_analysis;
mod unit_builtin;
mod unit_fft;
mod unit_formats;
mod unit_formats_channel;
mod unit_formats_gsf;
mod unit_formats_gwy;
mod unit_formats_ibw;
mod unit_formats_nanoscope;
mod unit_formats_npy;
mod unit_formats_npz;
mod unit_formats_raster;
mod unit_formats_sidecar;
mod unit_formats_text;
mod unit_generate;
mod unit_prep;
mod unit_render;
mod unit_rng;
mod unit_stats;
