"""The report of a scan (``iridis report FILE -o DIR``): from a new scan to its colours in one call. The same
library function as the command (``iridis_api::scan_report::write_report``): it writes ``DIR/index.html``,
``DIR/report.json`` and the figures, and returns ``report.json``'s content as a dict. Each step's JSON is the
library's answer (the command line adds the command's ``"inputs"`` to each; the rest is the same).

The demo gallery (``iridis demo``): the main job on built-in data, the same library function
(``iridis_api::demo::demo``).
"""
from __future__ import annotations

import json
import os

from . import _native
from ._answer import count, flag

__all__ = ["report", "demo", "DEMO_SECTIONS"]

#: The demo gallery's sections, in its order (``iridis demo --only``).
DEMO_SECTIONS = tuple(_native.DEMO_SECTIONS)


def _length(name, nm, text):
    """A length given as ``NAME_nm`` (a number of nm) or ``NAME`` (text with a unit, as the CLI's), as text."""
    if nm is not None and text is not None:
        raise ValueError(f"{name}_nm and {name} give the same length: give one")
    if nm is None:
        return text
    if isinstance(nm, bool) or not isinstance(nm, (int, float)):
        raise TypeError(f"{name}_nm must be a number of nm, got {type(nm).__name__}")
    return f"{float(nm)!r}nm"


def report(surface, output, *, channel=None, pixel_size_nm=None, max_height_nm=None, height_unit=None, level=None,
           override_units=False, as_height=False, size=128, coherence_nm=None, visual="bluetit", testbench=True,
           pixel_size=None, max_height=None, coherence=None):
    """Writes the report of ``surface`` (a SURFACE argument: a file or ``builtin:NAME``) into the folder
    ``output`` and returns ``report.json``'s dict (``verdict``, ``info``, ``unit_cell``, ``testbench``,
    ``too_deep_for_scalar_model``, ``warnings``, ``commands``, ``figures``, …). Lengths in nm as the package's
    other functions take them (``pixel_size_nm=5``, ``coherence_nm=20000``; ``max_height_nm=250`` is the height
    of white in a PNG or TIFF image of heights), or as text with a unit as the CLI takes them (``pixel_size="5nm"``,
    ``coherence="20um"``, ``max_height="250nm"``; one of the two forms per length);
    ``size`` is the BRDF maps' size in pixels, ``visual`` the animal whose view is shown, ``testbench=False``
    leaves out the test bench (the slowest step). The report's warnings are Python warnings;
    ``result["text"]`` is what ``iridis report`` prints.
    """
    pixel_size = _length("pixel_size", pixel_size_nm, pixel_size)
    max_height = _length("max_height", max_height_nm, max_height)
    coherence = _length("coherence", coherence_nm, coherence)
    opts = dict(channel=None if channel is None else str(channel), pixel_size=pixel_size, max_height=max_height,
                height_unit=height_unit, level=level, override_units=flag(override_units, "override_units"),
                as_height=flag(as_height, "as_height"), size=count(size, "size"), coherence=coherence,
                visual=str(visual),
                testbench=flag(testbench, "testbench"))
    out, text = _native._report(os.fspath(surface), os.fspath(output), opts)
    result = json.loads(out)
    result["text"] = text
    return result


def demo(out="iridis-demo", only=None):
    """Writes the demo gallery (``iridis demo``) into the folder ``out``: every section, or those named in
    ``only`` (a list or a comma-separated string of ``DEMO_SECTIONS``), in the gallery's order. Returns
    ``{"index": path of index.html, "written": [path of every figure]}``; each figure is also logged (the
    ``iridis`` logger, INFO) as the command prints it. The whole gallery takes a few minutes on two cores;
    ``only="color,thinfilm"`` seconds.
    """
    if only is None:
        only = []
    elif isinstance(only, str):
        only = [s.strip() for s in only.split(",") if s.strip()]
    index, written = _native._demo(os.fspath(out), [str(s) for s in only])
    return {"index": index, "written": written}
