import os
from typing import Any, Optional, Sequence, Union

from .surface import Surface

METHODS: tuple[str, ...]

def testbench(
    surface: Union[Surface, str, os.PathLike[str]],
    method: str = ...,
    incidence: float = ...,
    azimuth: Optional[float] = ...,
    order: int = ...,
    wavelengths: tuple[float, float, float] = ...,
    angles_deg: tuple[float, float, float] = ...,
    period_nm: Optional[float] = ...,
    max_period_nm: Optional[float] = ...,
    **options: Any,
) -> dict[str, Any]: ...
def compare(
    surface: Union[Surface, str, os.PathLike[str]],
    methods: Union[str, Sequence[str]] = ...,
    against: str = ...,
    exposures: Sequence[float] = ...,
    incidence: Union[float, tuple[float, float]] = ...,
    size: int = ...,
    step_nm: float = ...,
    illuminant: str = ...,
    uv_resolution: Optional[int] = ...,
    uv_power: Optional[float] = ...,
    table: Optional[Union[str, os.PathLike[str]]] = ...,
    gpu: bool = ...,
    **options: Any,
) -> dict[str, Any]: ...
def sweep(
    surface: Union[Surface, str, os.PathLike[str]],
    param: str,
    values: Sequence[float],
    output: Union[str, os.PathLike[str]],
    method: str = ...,
    against: str = ...,
    exposures: Sequence[float] = ...,
    incidence: Union[float, tuple[float, float]] = ...,
    size: int = ...,
    step_nm: Optional[float] = ...,
    uv_resolution: Optional[int] = ...,
    uv_power: Optional[float] = ...,
    plot: Optional[Union[str, os.PathLike[str]]] = ...,
    gpu: bool = ...,
    **options: Any,
) -> dict[str, Any]: ...
def laser(
    surface: Union[Surface, str, os.PathLike[str]],
    output: Union[str, os.PathLike[str]],
    method: str = ...,
    incidence: float = ...,
    azimuth: float = ...,
    aperture_nm: float = ...,
    distance_nm: float = ...,
    screen_nm: float = ...,
    size: int = ...,
    subsamples: int = ...,
    spectrum: Optional[Union[str, os.PathLike[str]]] = ...,
    coating: str = ...,
    exposures: Sequence[float] = ...,
    step_nm: float = ...,
    uv_resolution: Optional[int] = ...,
    uv_power: Optional[float] = ...,
    table: Optional[Union[str, os.PathLike[str]]] = ...,
    save_table: Optional[Union[str, os.PathLike[str]]] = ...,
    **options: Any,
) -> dict[str, Any]: ...
