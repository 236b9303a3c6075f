from typing import Any, Optional

import numpy as np
import numpy.typing as npt

def render(
    scene: Any,
    size: Optional[tuple[int, int]] = ...,
    spp: Optional[int] = ...,
    space: str = ...,
    gpu: bool = ...,
    exposure: Optional[float] = ...,
    spectral_samples: Optional[int] = ...,
    camera: Optional[str] = ...,
    ignore_gltf_lights: bool = ...,
) -> npt.NDArray[np.float64]: ...
def export_mesh(
    scene: Any, path: Any, camera: Optional[str] = ..., ignore_gltf_lights: bool = ...
) -> str: ...
