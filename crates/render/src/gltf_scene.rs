//! A glTF 2.0 file as a whole scene ([`scene_from_gltf`]): its meshes and materials ([`crate::gltf_io`]), its
//! cameras and KHR_lights_punctual lights, and — in a file iridis exported — its materials, environment and
//! output from its `extras`, read by the TOML parser.

use std::path::Path;

use crate::error::RenderError;
use crate::light::{Environment, Light};
use crate::math::*;

use crate::gltf_io::{bad, extras_of, identity4, load_gltf, mat4_mul, GltfOptions};
use crate::scene::{Output, Scene, SceneSource};
use crate::scene_toml::parse_scene;

/// A camera or light of the default scene, with its node's world matrix.
struct Placed<T> {
    node: Option<String>,
    item: T,
    world: [[f64; 4]; 4],
}

/// The default scene's cameras and punctual lights, in node order.
fn placed(doc: &gltf::Document) -> (Vec<Placed<gltf::Camera<'_>>>, Vec<Placed<gltf::khr_lights_punctual::Light<'_>>>) {
    let (mut cameras, mut lights) = (Vec::new(), Vec::new());
    let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) else { return (cameras, lights) };
    let mut stack: Vec<(gltf::Node, [[f64; 4]; 4])> = scene.nodes().map(|n| (n, identity4())).collect();
    stack.reverse();
    while let Some((node, parent)) = stack.pop() {
        let world = mat4_mul(&parent, &node.transform().matrix().map(|c| c.map(|x| x as f64)));
        let name = node.name().map(str::to_string);
        if let Some(c) = node.camera() {
            cameras.push(Placed { node: name.clone(), item: c, world });
        }
        if let Some(l) = node.light() {
            lights.push(Placed { node: name, item: l, world });
        }
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, world));
        }
    }
    (cameras, lights)
}

/// Column `j` of a column-major 4×4 matrix as a 3-vector.
fn column(w: &[[f64; 4]; 4], j: usize) -> V3 {
    [w[j][0], w[j][1], w[j][2]]
}

fn camera_label(c: &Placed<gltf::Camera<'_>>, index: usize) -> String {
    match (c.node.as_deref(), c.item.name()) {
        (Some(n), Some(m)) if n != m => format!("'{n}' (camera '{m}')"),
        (Some(n), _) | (None, Some(n)) => format!("'{n}'"),
        (None, None) => format!("#{index}"),
    }
}

/// A glTF file as a whole scene: its meshes and materials; its first camera (or the one `opts` names), else
/// one framing the meshes from the front (+z) and a little above; its KHR_lights_punctual lights, else a
/// directional D65 light from the upper left; a sky environment. A file exported by iridis (`render
/// --export-mesh`) brings back its materials, environment and output settings from its `extras`. The notes
/// say which camera and lights were used and how to choose others.
pub fn scene_from_gltf(path: &Path) -> Result<Scene, RenderError> {
    scene_from_gltf_with(path, &GltfOptions::default())
}

/// [`scene_from_gltf`] with the camera and lights chosen by `opts`.
pub fn scene_from_gltf_with(path: &Path, opts: &GltfOptions) -> Result<Scene, RenderError> {
    let bytes = std::fs::read(path).map_err(|e| bad(path, format!("cannot read the file: {e}")))?;
    let g = gltf::Gltf::from_slice(&bytes).map_err(|e| bad(path, format!("not a valid glTF 2.0 file: {e}")))?;
    let mut notes = Vec::new();
    let mut warnings = Vec::new();
    // iridis' own extras: the materials, textures, environment and output of the scene it was exported from.
    let own = extras_of(&g.document.as_json().extras).and_then(|x| x.get("iridis").cloned());
    let from = match &own {
        Some(x) => {
            let source = SceneSource {
                sections: x.get("sections").cloned().unwrap_or_default(),
                base: x.get("base").and_then(|b| b.as_str()).map(std::path::PathBuf::from).unwrap_or_default(),
            };
            let base = if source.base.is_dir() {
                source.base.clone()
            } else {
                path.parent().map(Path::to_path_buf).unwrap_or_default()
            };
            let name = format!("{} (iridis extras)", path.display());
            let s = parse_scene(&source.to_toml(), &name, &base)?;
            notes.push(format!(
                "materials, environment and output from the file's iridis extras (exported by iridis, resolved in {})",
                base.display()
            ));
            notes.extend(s.notes.into_iter().filter(|n| !n.contains("has no objects")));
            Some((s.materials, s.material_names, s.textures, s.environment, s.environment_visible, s.output))
        }
        None => None,
    };
    let (mut materials, mut names, mut textures) = match &from {
        Some((m, n, t, ..)) => (m.clone(), n.clone(), t.clone()),
        None => (Vec::new(), Vec::new(), Vec::new()),
    };
    let meshes = load_gltf(path, &mut materials, &mut names, &mut textures, None, &mut notes, &mut warnings)?;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for m in &meshes {
        let (a, b) = m.bounds();
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
        }
    }
    let mut output = Output {
        width: 512,
        height: 512,
        spp: 4,
        exposure: 1.0,
        encoding: iridis_color::Encoding::Srgb,
        background: [0.0; 3],
        max_depth: 6,
        seed: 0,
    };
    let (cameras, gl_lights) = placed(&g.document);
    // The camera.
    let listing = || cameras.iter().enumerate().map(|(i, c)| camera_label(c, i)).collect::<Vec<_>>().join(", ");
    let chosen = match opts.camera.as_deref() {
        Some("default") => None,
        Some(want) => Some(
            cameras
                .iter()
                .enumerate()
                .position(|(i, c)| {
                    c.node.as_deref() == Some(want) || c.item.name() == Some(want) || want.parse() == Ok(i)
                })
                .ok_or_else(|| {
                    bad(
                        path,
                        if cameras.is_empty() {
                            format!("--camera {want}: the file has no camera (leave --camera out for the default framing)")
                        } else {
                            format!("--camera {want}: no camera of that name; the file's cameras are {} (or --camera default)", listing())
                        },
                    )
                })?,
        ),
        None => (!cameras.is_empty()).then_some(0),
    };
    let camera = match chosen {
        Some(i) => {
            let c = &cameras[i];
            let w = &c.world;
            let position = column(w, 3);
            let forward = normalize(mul(column(w, 2), -1.0));
            let up0 = column(w, 1);
            let (forward, right, up) = crate::camera::frame(forward, up0).ok_or_else(|| {
                bad(path, format!("camera {}: its node's transform is degenerate", camera_label(c, i)))
            })?;
            let others = if cameras.len() > 1 {
                format!(" (of {}: {}; --camera NAME picks another", cameras.len(), listing())
            } else {
                " (--camera default frames the scene instead".to_string()
            };
            match c.item.projection() {
                gltf::camera::Projection::Perspective(p) => {
                    if let Some(a) = p.aspect_ratio().filter(|a| *a > 0.0) {
                        output.width = ((output.height as f32 * a).round() as u32).clamp(1, 16384);
                    }
                    notes.push(format!(
                        "glTF camera {} from the file, perspective, vertical field of view {:.1}°{others})",
                        camera_label(c, i),
                        f64::from(p.yfov()).to_degrees()
                    ));
                    crate::camera::Camera::Perspective {
                        position,
                        forward,
                        right,
                        up,
                        tan_half: (f64::from(p.yfov()) / 2.0).tan(),
                    }
                }
                gltf::camera::Projection::Orthographic(o) => {
                    if o.xmag() > 0.0 && o.ymag() > 0.0 {
                        output.width = ((output.height as f32 * o.xmag() / o.ymag()).round() as u32).clamp(1, 16384);
                    }
                    notes.push(format!(
                        "glTF camera {} from the file, orthographic, {} high{others})",
                        camera_label(c, i),
                        2.0 * o.ymag()
                    ));
                    crate::camera::Camera::Orthographic {
                        position,
                        forward,
                        right,
                        up,
                        half_height: f64::from(o.ymag()),
                    }
                }
            }
        }
        None => {
            let center = mul(add(lo, hi), 0.5);
            let radius = (0.5 * length(sub(hi, lo))).max(1e-6);
            let fov = 35f64.to_radians();
            let dist = radius / (fov / 2.0).sin() * 1.1;
            let position = add(center, mul(normalize([0.0, 0.35, 1.0]), dist));
            let (forward, right, up) =
                crate::camera::frame(sub(center, position), [0.0, 1.0, 0.0]).expect("camera frame");
            notes.push(if cameras.is_empty() {
                "glTF scene: the file has no camera; a default one frames it (front, slightly above)".to_string()
            } else {
                format!(
                    "glTF scene: the default camera (front, slightly above), as asked, instead of the file's ({})",
                    listing()
                )
            });
            crate::camera::Camera::Perspective { position, forward, right, up, tan_half: (fov / 2.0).tan() }
        }
    };
    // The lights: KHR_lights_punctual's intensities (lux for directional lights, candela for point and spot
    // lights) are taken as RU, 1 lux = 1 RU.
    let default_light = || Light::Directional { direction: normalize([-0.5, 1.0, 0.7]), rgb: [1.0; 3] };
    let lights = if gl_lights.is_empty() {
        notes.push("glTF scene: the file has no KHR_lights_punctual light; a D65 light from the upper left".into());
        vec![default_light()]
    } else if opts.ignore_lights {
        notes.push(format!(
            "glTF scene: the file's {} KHR_lights_punctual light(s) ignored (--ignore-gltf-lights); a D65 light from \
             the upper left instead",
            gl_lights.len()
        ));
        vec![default_light()]
    } else {
        let mut out = Vec::new();
        let mut spots = 0;
        for l in &gl_lights {
            let rgb = l.item.color().map(|c| f64::from(c) * f64::from(l.item.intensity()));
            match l.item.kind() {
                gltf::khr_lights_punctual::Kind::Directional => {
                    // It shines along the node's −z: the direction towards it is +z.
                    let direction = try_normalize(column(&l.world, 2))
                        .ok_or_else(|| bad(path, "a directional light's node has a degenerate transform"))?;
                    out.push(Light::Directional { direction, rgb });
                }
                gltf::khr_lights_punctual::Kind::Point => {
                    out.push(Light::Point { position: column(&l.world, 3), rgb });
                }
                gltf::khr_lights_punctual::Kind::Spot { .. } => {
                    spots += 1;
                    out.push(Light::Point { position: column(&l.world, 3), rgb });
                }
            }
        }
        notes.push(format!(
            "glTF scene: the file's {} KHR_lights_punctual light(s), intensities taken as RU (1 lux, or 1 cd at unit \
             distance, = 1 RU){}; --ignore-gltf-lights uses a D65 light from the upper left instead",
            out.len(),
            if spots > 0 {
                format!(", {spots} spot light(s) as point lights (their cones are not modelled)")
            } else {
                String::new()
            }
        ));
        out
    };
    let (environment, environment_visible) = match from {
        Some((.., env, visible, out)) => {
            output = out;
            (env, visible)
        }
        None => {
            notes.push("glTF scene: a sky environment (glTF has none)".into());
            (
                Environment::Sky { zenith: [0.25, 0.45, 0.9], horizon: [0.9, 0.92, 0.95], ground: [0.2, 0.18, 0.15] },
                true,
            )
        }
    };
    let bvh = crate::bvh::Bvh::build(&meshes);
    Ok(Scene {
        camera,
        lights,
        irradiance: environment.irradiance_map(),
        environment_lights: environment.as_lights(),
        area_lights: Vec::new(),
        integration: Default::default(),
        env_sampler: None,
        environment,
        environment_visible,
        meshes,
        spheres: Vec::new(),
        planes: Vec::new(),
        materials,
        material_names: names,
        textures,
        bvh,
        output,
        notes,
        warnings,
        source: None,
    })
}
