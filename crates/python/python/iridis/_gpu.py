"""What a GPU call needs from the process before the driver starts, set from Python, where the environment is
Python's own to change (shared by iridis.render, iridis.lab, iridis.diffraction and iridis.bench)."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile


def ensure_gpu_environment():
    """A private ``XDG_RUNTIME_DIR`` (mode 0700, removed at exit) when it is unset or names no folder, as the
    CLI makes one (crates/cli/src/runtime_dir.rs): the Vulkan loader's Wayland client prints "XDG_RUNTIME_DIR is
    invalid or not set" on every GPU start without it, although nothing is wrong. Set before the first GPU call,
    from Python, where the environment is Python's own to change."""
    d = os.environ.get("XDG_RUNTIME_DIR")
    if d and os.path.isabs(d) and os.path.isdir(d):
        return
    d = tempfile.mkdtemp(prefix="iridis-runtime-")  # mkdtemp makes it 0700
    atexit.register(shutil.rmtree, d, ignore_errors=True)
    os.environ["XDG_RUNTIME_DIR"] = d
