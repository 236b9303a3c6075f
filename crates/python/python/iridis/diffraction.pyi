from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

from .surface import Surface

class Table:
    @classmethod
    def load(cls, path: Any) -> "Table": ...
    def save(self, path: Any) -> None: ...
    @property
    def meta(self) -> dict[str, Any]: ...

def precompute(
    surface: Surface,
    coherence_nm: Optional[float] = ...,
    terms: Optional[int] = ...,
    uv_resolution: int = ...,
    uv_power: float = ...,
    illuminant: str = ...,
    observer: str = ...,
    step_nm: float = ...,
) -> Table: ...
def brdf_map(
    source: Union[Surface, Table],
    incidence: Union[float, tuple[float, float]] = ...,
    size: int = ...,
    method: Optional[str] = ...,
    coherence_nm: Optional[float] = ...,
    terms: Optional[int] = ...,
    illuminant: str = ...,
    observer: str = ...,
    step_nm: float = ...,
) -> npt.NDArray[np.float64]: ...
def brdf_map_of(
    spec: str,
    incidence: Union[float, tuple[float, float]] = ...,
    size: int = ...,
    method: str = ...,
    level: Optional[str] = ...,
    **options: Any,
) -> npt.NDArray[np.float64]: ...
