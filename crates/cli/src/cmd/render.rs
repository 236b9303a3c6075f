//! `iridis render`: offline rendering of a scene (TOML or glTF) on the CPU (`iridis-render`, issue 7) or the
//! GPU, through `iridis_api::scene::render_file`.

use anyhow::Result;
use clap::Args as ClapArgs;

use crate::progress::Cli;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Renders a scene: a TOML file (camera, lights, environment, textures, materials, objects; see docs/render.md)
or a glTF 2.0 file (.gltf/.glb, KHR_materials_iridescence as a thin film): its first camera (--camera NAME
picks another, --camera default frames the scene) and its KHR_lights_punctual lights (--ignore-gltf-lights
uses a default light), or a default camera and light where it has none; the notes say which. The output
format follows the extension: .png is tone-mapped (exposure in RU, sRGB), .exr is linear sRGB float.
Nothing is written unless the whole render succeeds. --export-mesh writes the scene's triangle meshes (the
procedural snake's scale plates, OBJ and glTF meshes) as binary glTF with normals, UVs and the orientation
field as TANGENT, so orientation \"tangent\" on that file gives what \"along\" gives on the procedural snake;
with the scene's materials (glTF PBR for other tools, iridis' own in the extras), camera and lights, so that
rendering the .glb looks like the scene.

Examples:
  iridis render examples/soap_bubble.toml -o bubble.png
  iridis render examples/snake_elaphe.toml -o snake.png --size 1024x768 --spp 4
  iridis render examples/gold_sphere.toml -o gold.exr
  iridis render examples/rough_film.toml -o rough.png --size 480x320   # films on rough substrates (LSRS)
  iridis render examples/iridescent_spheres.gltf -o gltf.png --size 512x512
  iridis render examples/snake_elaphe.toml -o snake_gpu.png --gpu      on the GPU (lavapipe without one)
  iridis render examples/soap_bubble.toml -o bubble_81.png --size 96x96 --gpu --spectral-samples 81
  iridis render examples/fig1_elaphe_section.toml --export-mesh snake.glb   the scaled snake as glTF
  iridis render snake.glb -o snake_again.png --size 96x64                   rendered back, materials and all
  iridis render examples/iridescent_spheres.gltf -o g.png --camera default --ignore-gltf-lights

--gpu renders the same scene with the WGSL port of the renderer (iridis-gpu) through Vulkan; its colours
match the CPU's (mean CIEDE2000 < 1 on every example scene, tested). Thin films shade there from colour
tables (XYZ over angle and thickness, filled by the 81-sample evaluation; rough films' LSRS tables are made
on the CPU); --spectral-samples N evaluates smooth films directly at N wavelengths (380-780 nm) per hit
instead, 81 being the reference. Without a GPU, Mesa's software driver works:
apt-get install mesa-vulkan-drivers.")]
pub struct RenderArgs {
    #[command(flatten)]
    pub request: iridis_api::scene::RenderRequest,
    /// glTF scenes: the camera to render through, by node or camera name (or index); `default` frames the
    /// scene with iridis' own camera. Without it, the file's first camera.
    #[arg(long, value_name = "NAME")]
    pub camera: Option<String>,
    /// glTF scenes: leave out the file's KHR_lights_punctual lights and use a default D65 light.
    #[arg(long)]
    pub ignore_gltf_lights: bool,
}

pub fn run(a: RenderArgs) -> Result<()> {
    let gltf = iridis_render::gltf_io::GltfOptions { camera: a.camera, ignore_lights: a.ignore_gltf_lights };
    let r = iridis_api::scene::RenderRequest { gltf, ..a.request };
    for line in iridis_api::scene::render_file(&r, &Cli)?.lines {
        crate::outln!("{line}")?;
    }
    Ok(())
}
