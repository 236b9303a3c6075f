//! The viewer's frames without a readback: a compute pass stores the displayed pixels of a frame shader's
//! packed output buffer into a texture that egui's renderer draws directly (registered with
//! `egui_wgpu::Renderer::register_native_texture`). The frame never leaves the GPU; only the scripted check reads
//! it back, to verify that the texture holds exactly the frame.

use crate::{Gpu, GpuError};

/// The present pipeline (compiled once per window).
#[derive(Debug)]
pub(crate) struct Presenter {
    pipeline: wgpu::ComputePipeline,
}

/// A texture of one frame size that egui samples.
#[derive(Debug)]
pub(crate) struct PresentTarget {
    texture: wgpu::Texture,
    /// The view the present pass writes (rgba8unorm: storage textures cannot be sRGB).
    store_view: wgpu::TextureView,
    /// The view egui samples: the same bytes as rgba8unorm-srgb, decoded to linear on sampling as egui's own
    /// textures are.
    pub(crate) sample_view: wgpu::TextureView,
    pub(crate) width: u32,
    pub(crate) height: u32,
}

impl Presenter {
    pub(crate) fn new(gpu: &Gpu) -> Result<Self, GpuError> {
        gpu.checked("compiling the present shader", || {
            let module = gpu.shader("present", include_str!("shaders/present.wgsl"));
            let pipeline = gpu.compute_pipeline(&module, "present", "main");
            Self { pipeline }
        })
    }

    /// A texture for frames of `width × height`.
    pub(crate) fn target(&self, gpu: &Gpu, width: u32, height: u32) -> Result<PresentTarget, GpuError> {
        gpu.checked("allocating the frame texture", || {
            let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("iridis frame"),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[wgpu::TextureFormat::Rgba8UnormSrgb],
            });
            let store_view = texture.create_view(&wgpu::TextureViewDescriptor {
                usage: Some(wgpu::TextureUsages::STORAGE_BINDING),
                ..Default::default()
            });
            // sRGB formats cannot be storage views: this one is for sampling only.
            let sample_view = texture.create_view(&wgpu::TextureViewDescriptor {
                format: Some(wgpu::TextureFormat::Rgba8UnormSrgb),
                usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
                ..Default::default()
            });
            PresentTarget { texture, store_view, sample_view, width, height }
        })
    }

    /// Stores `packed` (`width × height` words of `pack4x8unorm`) into `target`. Submitted without waiting:
    /// egui's draw, later on the same queue, sees the result.
    pub(crate) fn present(&self, gpu: &Gpu, packed: &wgpu::Buffer, target: &PresentTarget) -> Result<(), GpuError> {
        let needed = u64::from(target.width) * u64::from(target.height) * 4;
        if packed.size() < needed {
            return Err(GpuError::Invalid(format!(
                "the frame buffer holds {} bytes but a {}×{} texture needs {needed}",
                packed.size(),
                target.width,
                target.height
            )));
        }
        gpu.checked("presenting the frame", || {
            let bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("present"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: packed.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&target.store_view),
                    },
                ],
            });
            let mut enc = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("present") });
            {
                let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("present"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.dispatch_workgroups(target.width.div_ceil(8), target.height.div_ceil(8), 1);
            }
            gpu.queue.submit([enc.finish()]);
        })
    }
}

impl PresentTarget {
    /// The texture's RGB bytes, read back (the scripted check's proof that the window shows the frame).
    pub(crate) fn read_rgb8(&self, gpu: &Gpu) -> Result<Vec<u8>, GpuError> {
        // Rows of a texture-to-buffer copy are padded to 256 bytes.
        let row = (self.width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let bytes = u64::from(row) * u64::from(self.height);
        // Straight from the texture into the mappable buffer.
        let data = gpu.read_back("frame texture readback", bytes, |enc, staging| {
            enc.copy_texture_to_buffer(
                self.texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: staging,
                    layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
                },
                wgpu::Extent3d { width: self.width, height: self.height, depth_or_array_layers: 1 },
            )
        })?;
        let mut out = Vec::with_capacity((self.width * self.height * 3) as usize);
        for r in 0..self.height as usize {
            let line = &data[r * row as usize..][..self.width as usize * 4];
            out.extend(line.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]));
        }
        Ok(out)
    }
}
