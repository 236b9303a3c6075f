import os
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from .surface import Surface

class Table:
    @classmethod
    def load(cls, path: Union[str, os.PathLike[str]]) -> "Table": ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None: ...
    @property
    def meta(self) -> dict[str, Any]: ...

Source = Union[Surface, Table, str, os.PathLike[str]]
Direction = Union[float, tuple[float, float]]

def precompute(
    surface: Union[Surface, str, os.PathLike[str]],
    coherence_nm: Optional[float] = ...,
    terms: Optional[int] = ...,
    uv_resolution: Optional[int] = ...,
    uv_power: Optional[float] = ...,
    illuminant: Optional[str] = ...,
    observer: Optional[str] = ...,
    step_nm: Optional[float] = ...,
    name: Optional[str] = ...,
    units: Optional[str] = ...,
    gpu: bool = ...,
    **options: Any,
) -> Table: ...
def brdf_map(
    source: Source,
    incidence: Direction = ...,
    size: int = ...,
    method: Optional[str] = ...,
    per_sr: bool = ...,
    gpu: bool = ...,
    subsamples: int = ...,
    **options: Any,
) -> npt.NDArray[np.float64]: ...
def brdf_map_run(
    source: Union[str, os.PathLike[str]],
    incidence: Direction = ...,
    size: int = ...,
    method: str = ...,
    **options: Any,
) -> dict[str, Any]: ...
def brdf_eval(
    source: Union[str, os.PathLike[str]],
    light: Direction,
    view: Direction,
    method: Optional[str] = ...,
    **options: Any,
) -> dict[str, Any]: ...
def evaluate(
    source: Source, light: Direction, view: Direction, method: Optional[str] = ..., **options: Any
) -> dict[str, Any]: ...
def brdf_map_of(
    spec: Union[str, os.PathLike[str]],
    incidence: Direction = ...,
    size: int = ...,
    method: str = ...,
    level: Optional[str] = ...,
    **options: Any,
) -> npt.NDArray[np.float64]: ...
def grating(
    source: Source,
    light: Direction = ...,
    wavelengths_nm: Union[float, Sequence[float]] = ...,
    method: Optional[str] = ...,
    material: Optional[str] = ...,
    fresnel: Optional[str] = ...,
    normalisation: str | None = ...,
    detector: Optional[Direction] = ...,
    acceptance: Optional[float] = ...,
    compare: bool = ...,
    orders_above: Optional[float] = ...,
    **options: Any,
) -> dict[str, Any]: ...
def vision(
    source: Source,
    visual: str,
    light: float = ...,
    views_deg: Sequence[float] = ...,
    azimuth: Optional[float] = ...,
    illuminant: Optional[str] = ...,
    **options: Any,
) -> dict[str, Any]: ...
