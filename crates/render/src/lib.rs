//! # iridis-render
//!
//! Put diffraction and thin-film materials on real geometry and get a picture, headless and reproducible: the
//! reference that the GPU renderer must match (issue 7; user documentation in `docs/render.md`).
//!
//! * [`scene`]: the scene a renderer draws; [`scene_toml`] the TOML scene format (camera, lights, environment,
//!   textures, materials, objects, output), [`gltf_scene`] glTF 2.0 files as scenes, [`load`] either by name;
//! * [`geometry`]: meshes with normals, UVs and MikkTSpace tangent frames ([`obj_io`], [`gltf_io`]), analytic
//!   spheres and planes; [`snake`] the procedural snake with curved, overlapping scale plates; [`bvh`] the
//!   acceleration structure;
//! * [`material`]: diffraction (lookup tables of `iridis precompute`, orientation fields, the thesis' texture
//!   blending, Algorithm 4), thin films (Sussenbach's smooth illumination model, eq. 3.14, with spatially
//!   varying thickness, eq. 4.3–4.4), Lambert and GGX microfacet;
//! * [`light`]: directional and point lights with a spectrum, uniform / sky / equirectangular environments
//!   and their importance sampler; [`area`] sphere, disk and rectangle lights;
//! * [`integrate`]: extended light by Monte Carlo (light and BRDF sampling, multiple importance sampling), with
//!   [`sampling`] the samplers and [`lobe`] the diffraction lobe's sampler and prefiltered table;
//! * [`camera`]: perspective, orthographic and the hemisphere camera that reproduces a BRDF map;
//! * [`mod@render`]: ray casting on all cores, anti-aliasing, linear float images, PNG and EXR encoding.
//!
//! Conventions (`docs/PHYSICS.md`): the nanostructure's x axis is the surface tangent `t`, `y` is `n × t`;
//! colours are linear sRGB with D65 white = 1; light levels are in RU, so a directional light of 1 RU on the
//! plane of a diffraction material gives exactly the colours of `iridis brdf-map` at exposure 1.

pub mod area;
pub mod bvh;
pub mod camera;
pub mod energy;
pub mod error;
pub mod geometry;
pub mod gltf_export;
pub mod gltf_io;
pub mod gltf_scene;
pub mod integrate;
pub mod light;
pub mod load;
pub mod lobe;
pub mod lobe_albedo;
pub mod material;
pub mod math;
pub mod obj_io;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod scene_toml;
pub mod snake;
pub mod tables;
pub mod texture;

pub use error::RenderError;
pub use load::{load_scene, load_scene_with};
pub use render::{render, Image};
pub use scene::Scene;
pub use scene_toml::parse_scene;
