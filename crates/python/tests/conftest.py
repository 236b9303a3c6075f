import json
import os

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
