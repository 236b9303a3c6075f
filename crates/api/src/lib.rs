//! # iridis-api
//!
//! The library API the front ends share: the command line (`crates/cli`), the viewer's inputs and the Python
//! package (`crates/python`) call these functions, so that a SURFACE is read, a table checked, an evaluator
//! made, a coherence length fitted or a rough film coloured the same way — with the same messages — whichever
//! front end asked. The front ends keep what is theirs: parsing arguments, printing, writing files.
//!
//! * [`surface`]: a SURFACE argument with its options, levelled for the model ([`surface::load_patch`]);
//! * [`model`]: the spectral setup, coherence (given or fitted), Taylor terms, lookup tables built, loaded and
//!   checked against the options;
//! * [`fresnel`]: the Fresnel factor from its text form (`schlick:1.5`, `index:0.2+3.4i`, `gold`, `stack:…`);
//! * [`brdf`]: evaluators for a method on a SURFACE or TABLE, BRDF maps, point queries (`brdf eval`);
//! * [`rigorous_brdf`]: the rigorous BRDF of a periodic surface (the scalar lobes carrying Maxwell's
//!   efficiencies), its unit cell and assumptions;
//! * [`lab`]: the workbench, the test bench with its warnings, comparisons, the laser experiment's inputs;
//! * [`film`], [`film_chart`], [`film_fit`], [`film_bench`]: thin films (spectra, tables, colours, materials, the
//!   soap-film chart, depth profiles, fits, the benchmark against tmm) as `iridis thinfilm` and `iridis.film` give them;
//! * [`rough`]: films on rough substrates (LSRS): options, spectra, colours, tables, the chart's bands, the bench;
//! * [`gpu`]: scenes and lookup maps on the GPU;
//! * [`grating_bench`]: the rigorous solver timed against grcwa (`iridis bench grating`);
//! * [`mod@bench`]: every benchmark (`iridis bench …`, `python -m iridis.bench NAME`);
//! * [`brdf_map`], [`brdf_eval`], [`brdf_vision`]: the `brdf-map`, `brdf eval` and `brdf vision` commands'
//!   work, text and JSON; [`scene`]: `iridis render` and the example scenes; `view` (feature `viewer`);
//! * [`unit_cell`]: one period of a scan averaged along its ridges (a 1-D grating profile);
//! * [`surface_info`], [`grating_run`], [`lab_run`], [`scan_report`]: the runs of `iridis surface`, `grating`,
//!   the lab commands and `report` (requests in, results with their text and JSON out, figures written).
//!
//! With the feature `cli` the option structs derive `clap::Args` (their doc comments are the `--help` text)
//! and `args` holds the value parsers for lengths and angles.
//!
//! Errors are messages for people (`anyhow`, with the library's typed error as the source and the context a
//! person needs: "cannot load surface X: …"); notes, warnings and progress go to a [`report::Report`] the front
//! end supplies — the facade never prints.
//!
//! Arrows: `cli, python → api → lab, gpu → render → diffraction → thinfilm, surface → color`.

#[cfg(feature = "cli")]
pub mod args;
pub mod bench;
pub mod brdf;
pub mod brdf_eval;
pub mod brdf_map;
pub mod brdf_vision;
pub mod color;
pub mod demo;
pub mod film;
pub mod film_bench;
pub mod film_chart;
pub mod film_fit;
pub mod film_run;
pub mod fresnel;
pub mod gallery;
pub mod gpu;
pub mod grating;
pub mod grating_bench;
pub mod grating_run;
pub mod lab;
pub mod lab_run;
pub mod lit;
pub mod model;
pub mod output;
pub mod precompute;
pub mod report;
pub mod rigorous_brdf;
pub mod rough;
pub mod scan_report;
pub mod scene;
pub mod surface;
pub mod surface_info;
pub mod unit_cell;
#[cfg(feature = "viewer")]
pub mod view;
pub mod vision;

pub use model::ModelOptions;
pub use report::{Kind, Quiet, Report};
pub use surface::SurfaceOptions;
