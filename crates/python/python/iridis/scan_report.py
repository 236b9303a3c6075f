"""The report of a scan (``iridis report FILE -o DIR``): from a new scan to its colours in one call. The same
library function as the command (``iridis_api::scan_report::write_report``): it writes ``DIR/index.html``,
``DIR/report.json`` and the figures, and returns ``report.json``'s content as a dict. Each step's JSON is the
library's answer (the command line adds the command's ``"inputs"`` to each; the rest is the same).
"""
from __future__ import annotations

import json
import os

from . import _native

__all__ = ["report"]


def report(surface, output, *, channel=None, pixel_size=None, max_height=None, height_unit=None, level=None,
           override_units=False, as_height=False, size=128, coherence=None, visual="bluetit", testbench=True):
    """Writes the report of ``surface`` (a SURFACE argument: a file or ``builtin:NAME``) into the folder
    ``output`` and returns ``report.json``'s dict (``verdict``, ``info``, ``unit_cell``, ``testbench``,
    ``warnings``, ``commands``, ``figures``, …). Lengths are given as the CLI takes them (``pixel_size="5nm"``,
    ``coherence="20um"``; ``max_height="250nm"`` is the height of white in a PNG or TIFF image of heights);
    ``size`` is the BRDF maps' size in pixels, ``visual`` the animal whose view is shown, ``testbench=False``
    leaves out the test bench (the slowest step). The report's warnings are Python warnings;
    ``result["text"]`` is what ``iridis report`` prints.
    """
    opts = dict(channel=None if channel is None else str(channel), pixel_size=pixel_size, max_height=max_height,
                height_unit=height_unit, level=level, override_units=bool(override_units),
                as_height=bool(as_height), size=int(size), coherence=coherence, visual=str(visual),
                testbench=bool(testbench))
    out, text = _native._report(os.fspath(surface), os.fspath(output), opts)
    result = json.loads(out)
    result["text"] = text
    return result
