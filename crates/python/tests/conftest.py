import json
import os
import struct
import zlib

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def load(*parts):
    with open(os.path.join(ROOT, *parts)) as f:
        return json.load(f)


def fixture_file(*parts):
    """A session fixture holding the JSON file at ROOT/PARTS (read once)."""

    @pytest.fixture(scope="session")
    def read():
        return load(*parts)

    return read


tmm_reference = fixture_file("crates", "thinfilm", "tests", "fixtures", "tmm_reference.json")
tmm_incoherent = fixture_file("crates", "thinfilm", "tests", "fixtures", "tmm_incoherent.json")
colour_science = fixture_file("crates", "color", "tests", "fixtures", "colour_science.json")
sharma = fixture_file("crates", "color", "tests", "fixtures", "sharma2005.json")


@pytest.fixture
def grey_sine_png(tmp_path):
    """A 64² 8-bit grey PNG of a sine along x, 16 pixels a period, constant along y (a scan saved as an image of
    relative heights), and its grey levels per column."""
    grey = (127.5 + 127.5 * np.sin(2 * np.pi * np.arange(64) / 16)).astype(np.uint8)
    rows = b"".join(b"\x00" + grey.tobytes() for _ in range(64))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = tmp_path / "grey.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 64, 64, 8, 0, 0, 0, 0))
                    + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
    return png, grey
