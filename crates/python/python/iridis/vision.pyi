from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

VISUAL_SYSTEMS: dict[str, str]
ILLUMINANTS: dict[str, str]

def analyse(
    wavelengths_nm: npt.ArrayLike,
    values: npt.ArrayLike,
    visual: Optional[str] = ...,
    names: Optional[Sequence[str]] = ...,
    *,
    lambda_max: Optional[Union[str, npt.ArrayLike]] = ...,
    chromophore: Optional[str] = ...,
    oil_droplets: Optional[str] = ...,
    ocular_media: Optional[str] = ...,
    illuminant: Optional[str] = ...,
    illuminant_units: Optional[str] = ...,
    illuminant_scale: Optional[float] = ...,
    background: Optional[str] = ...,
    weber: Optional[float] = ...,
    weber_ref: Optional[Union[str, int]] = ...,
    densities: Optional[Union[str, npt.ArrayLike]] = ...,
    receptor_noise: Optional[Union[str, npt.ArrayLike]] = ...,
    noise: Optional[str] = ...,
    achromatic: Optional[str] = ...,
    weber_achromatic: Optional[float] = ...,
    space: Optional[str] = ...,
    achromatic_weber: Optional[float] = ...,
) -> dict[str, Any]: ...
def sensitivities(
    wavelengths_nm: npt.ArrayLike,
    visual: Optional[str] = ...,
    *,
    lambda_max: Optional[Union[str, npt.ArrayLike]] = ...,
    chromophore: Optional[str] = ...,
    oil_droplets: Optional[str] = ...,
) -> tuple[list[str], npt.NDArray[np.float64]]: ...
def vision(
    spectra: str, visual: Optional[str] = ..., *, percent: bool = ..., lambda_max: Any = ...,
    chromophore: Optional[str] = ..., oil_droplets: Optional[str] = ..., ocular_media: Optional[str] = ...,
    illuminant: str = ..., illuminant_units: Optional[str] = ..., illuminant_scale: float = ..., background: str = ...,
    weber: Optional[float] = ..., weber_ref: Optional[str] = ..., densities: Any = ..., receptor_noise: Any = ...,
    noise: str = ..., achromatic: Optional[str] = ..., weber_achromatic: Optional[float] = ..., space: str = ...,
    achromatic_weber: Optional[float] = ...
) -> dict[str, Any]: ...
