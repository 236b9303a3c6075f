import os
from typing import Any, Optional, Union

def report(
    surface: Union[str, os.PathLike[str]],
    output: Union[str, os.PathLike[str]],
    *,
    channel: Union[int, str, None] = ...,
    pixel_size_nm: Optional[float] = ...,
    max_height_nm: Optional[float] = ...,
    height_unit: Optional[str] = ...,
    level: Optional[str] = ...,
    override_units: bool = ...,
    as_height: bool = ...,
    size: int = ...,
    coherence_nm: Optional[float] = ...,
    visual: str = ...,
    testbench: bool = ...,
    pixel_size: Optional[str] = ...,
    max_height: Optional[str] = ...,
    coherence: Optional[str] = ...,
) -> dict[str, Any]: ...

DEMO_SECTIONS: tuple[str, ...]

def demo(
    out: Union[str, os.PathLike[str]] = ...,
    only: Union[str, list[str], None] = ...,
) -> dict[str, Any]: ...
