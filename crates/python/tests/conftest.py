import json
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def load(*parts):
    with open(os.path.join(ROOT, *parts)) as f:
        return json.load(f)


@pytest.fixture(scope="session")
def tmm_reference():
    return load("crates", "thinfilm", "tests", "fixtures", "tmm_reference.json")


@pytest.fixture(scope="session")
def tmm_incoherent():
    return load("crates", "thinfilm", "tests", "fixtures", "tmm_incoherent.json")


@pytest.fixture(scope="session")
def colour_science():
    return load("crates", "color", "tests", "fixtures", "colour_science.json")


@pytest.fixture(scope="session")
def sharma():
    return load("crates", "color", "tests", "fixtures", "sharma2005.json")
