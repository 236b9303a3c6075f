from typing import Any, Optional, Sequence

import numpy as np
import numpy.typing as npt

def material_index(name: str, wavelengths_nm: npt.ArrayLike) -> Any: ...
def materials() -> list[tuple[list[str], str]]: ...
def colors_of_stacks(
    indices: npt.ArrayLike,
    thicknesses_nm: npt.ArrayLike,
    angle_rad: float = ...,
    illuminant: str = ...,
    observer: str = ...,
    polarization: str = ...,
    grid_nm: Optional[npt.ArrayLike] = ...,
) -> dict[str, npt.NDArray[np.float64]]: ...

class Stack:
    def __init__(self, spec: str) -> None: ...
    @classmethod
    def from_lists(
        cls,
        indices: Any,
        thicknesses_nm: npt.ArrayLike,
        incoherent: Optional[Sequence[bool]] = ...,
        wavelengths_nm: Optional[npt.ArrayLike] = ...,
    ) -> "Stack": ...
    @property
    def layers(self) -> int: ...
    def indices(self, wavelengths_nm: npt.ArrayLike) -> npt.NDArray[np.complex128]: ...
    def rta(
        self, wavelengths_nm: npt.ArrayLike, angles_rad: npt.ArrayLike = ..., offsets_nm: npt.ArrayLike = ...,
        polarization: str = ...,
    ) -> dict[str, npt.NDArray[np.float64]]: ...
    def reflectance(
        self, wavelengths_nm: npt.ArrayLike, angles_rad: npt.ArrayLike = ..., offsets_nm: npt.ArrayLike = ...,
        polarization: str = ...,
    ) -> npt.NDArray[np.float64]: ...
    def transmittance(
        self, wavelengths_nm: npt.ArrayLike, angles_rad: npt.ArrayLike = ..., offsets_nm: npt.ArrayLike = ...,
        polarization: str = ...,
    ) -> npt.NDArray[np.float64]: ...
    def rough(
        self,
        roughness_nm: float,
        correlation_nm: float,
        d_iterations: Optional[int] = ...,
        diffuse_transport: str = ...,
    ) -> "RoughFilm": ...
    def profile(
        self, wavelength_nm: float, angle_rad: float = ..., polarization: str = ..., points: int = ...,
        depth_nm: Optional[tuple[float, float]] = ...,
    ) -> dict[str, Any]: ...
    def color(
        self,
        angles_rad: npt.ArrayLike = ...,
        offsets_nm: npt.ArrayLike = ...,
        illuminant: str = ...,
        observer: str = ...,
        polarization: str = ...,
        grid_nm: Optional[npt.ArrayLike] = ...,
    ) -> dict[str, Any]: ...

class RoughFilm:
    stack: Stack
    roughness_nm: float
    correlation_nm: float
    d_iterations: Optional[int]
    diffuse_transport: str
    def __init__(
        self,
        stack: Stack,
        roughness_nm: float,
        correlation_nm: float,
        d_iterations: Optional[int] = ...,
        diffuse_transport: str = ...,
    ) -> None: ...
    def spectrum(
        self,
        wavelengths_nm: npt.ArrayLike,
        view_rad: float = ...,
        light_rad: Optional[float] = ...,
        azimuth_rad: float = ...,
    ) -> dict[str, Any]: ...
    def color(
        self,
        view_rad: float = ...,
        light_rad: Optional[float] = ...,
        azimuth_rad: float = ...,
        illuminant: str = ...,
        observer: str = ...,
        grid_nm: Optional[npt.ArrayLike] = ...,
    ) -> dict[str, Any]: ...

def profile(
    stack: Any, wavelength_nm: float, angle_rad: float = ..., polarization: str = ..., points: int = ...,
    depth_nm: Optional[tuple[float, float]] = ...,
) -> dict[str, Any]: ...
def fit(
    measured: Any, stack: str, angle_rad: float = ..., quantity: str = ..., sigma: Any = ..., weights: Any = ...,
    grid: int = ..., columns: Optional[str] = ..., percent: Optional[bool] = ..., from_nm: Optional[float] = ...,
    to_nm: Optional[float] = ...,
) -> dict[str, Any]: ...
