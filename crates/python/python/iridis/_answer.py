"""What a command of the CLI gives, from Python: its ``--json`` answer as a dict, with the text it prints, its
CSV and its plot where it has them (shared by ``iridis.film``, ``iridis.color.xyz`` and ``iridis.vision.vision``)."""
from __future__ import annotations

import csv
import difflib
import functools
import inspect
import io
import json
import os
import sys
import warnings

import numpy as np

from . import _native


class Answer(dict):
    """The command's ``--json`` answer (a dict; without the CLI's ``inputs``), with attributes:

    ``text``: what the command prints without ``--json``; ``csv``: its CSV (``None`` when it has none);
    ``image``: its plot as an ``(height, width, 3)`` ``uint8`` RGB array (``None`` unless asked for)."""

    text: str | None = None
    csv: str | None = None
    image: np.ndarray | None = None


def with_text(answer, text):
    """A command's ``--json`` dict as an :class:`Answer` with ``.text``, what the command prints without
    ``--json``."""
    out = Answer(answer)
    out.text = text
    return out


def file_path(x, who, arrays):
    """``x`` as a path for a function that reads a file as the CLI does (``who``); anything else is refused with
    the function ``arrays`` that takes arrays (str() of a tuple of arrays was read as a file name: "cannot read
    (array([380., …")."""
    if isinstance(x, (str, bytes)) or hasattr(x, "__fspath__"):
        return os.fsdecode(os.fspath(x))
    raise TypeError(f"{who} reads a file, as the CLI does, and was given a {type(x).__name__}; for arrays use {arrays}")


def keywords(f):
    """For a function that passes ``**options`` on to the library: the library's "unexpected keyword argument"
    error names only the options; this adds the function's own keyword parameters and the nearest name to the
    one given (``aperture`` → ``aperture_nm``, as the CLI's ``--aperture`` is named here)."""
    kinds = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    parameters = inspect.signature(f).parameters
    own = [n for n, p in parameters.items() if p.kind in kinds]
    # A function without **options: Python's own "unexpected keyword argument" gets the same hint (film.spectrum's
    # `angle=0.5`, the CLI's --angle, is angle_rad here).
    closed = not any(p.kind == inspect.Parameter.VAR_KEYWORD for p in parameters.values())

    def unexpected(name, known):
        near = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        hint = f"did you mean {near[0]}? " if near else ""
        return TypeError(f"{f.__name__}() got an unexpected keyword argument '{name}' ({hint}it takes: "
                         f"{', '.join(known)})")

    @functools.wraps(f)
    def call(*args, **kwargs):
        if closed:
            for name in kwargs:
                if name not in own:
                    raise unexpected(name, sorted(own))
        try:
            return f(*args, **kwargs)
        except _native.UnexpectedKeyword as e:
            raise unexpected(e.keyword, sorted(set(own) | set(e.known))) from None
    return call


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn_caller(text, category=UserWarning):
    """``warnings.warn(text, category)`` attributed to the first caller outside this package (however many of
    its wrappers and decorators stand between): a warning of the user's line."""
    level, frame = 1, sys._getframe(0)
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    warnings.warn(text, category, stacklevel=level)


def flag(value, name):
    """``value`` as a yes/no option: a bool (Python's or numpy's) only; ``bool("no")`` is True, so a str or a
    number given by mistake is a TypeError naming ``name``, not silently yes."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name} must be True or False, got {type(value).__name__} {value!r}")


def whole(value, name):
    """``value`` as a whole number (an int, a numpy integer, or a float such as 5.0 that is one): anything else is
    a TypeError or ValueError naming ``name``."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be a whole number, got {value!r}")
    try:
        n = int(value)
    except (TypeError, ValueError, OverflowError):
        raise TypeError(f"{name} must be a whole number, got {value!r}") from None
    if n != value:
        raise ValueError(f"{name} = {value!r} must be a whole number")
    return n


def count(value, name):
    """``value`` as a whole number ≥ 0 (a size, a number of points or samples): a negative one is a ValueError
    naming ``name`` (the binding's conversion said only "can't convert negative int to unsigned")."""
    n = whole(value, name)
    if n < 0:
        raise ValueError(f"{name} = {n} must be ≥ 0")
    return n


def renamed(function, old, old_value, new, new_value):
    """The value of a keyword whose former name was ``old`` (its name now, ``new``, is the CLI's flag's; both
    default to None): the former name's value with a DeprecationWarning where only it is given; both given is a
    TypeError."""
    if old_value is None:
        return new_value
    if new_value is not None:
        raise TypeError(f"{function}() got both {new}= and its former name {old}=; give {new}= alone")
    warn_caller(f"{old}= is now {new}=", DeprecationWarning)
    return old_value


def columns(text):
    """A CSV's columns by header name: numbers as float arrays (an empty cell is NaN), other columns as lists."""
    rows = list(csv.reader(io.StringIO(text)))
    out = {}
    for k, name in enumerate(rows[0]):
        cells = [r[k] for r in rows[1:]]
        try:
            out[name] = np.array([float(c) if c != "" else np.nan for c in cells])
        except ValueError:
            out[name] = cells
    return out


def answer(raw, table=False):
    """The native answer (``json``, ``text``, ``csv``, ``image`` and extras) as an :class:`Answer`; ``table``:
    the dict holds the CSV's columns (commands whose answer is a table, without ``--json``)."""
    a = Answer(json.loads(raw["json"]) if raw.get("json") else (columns(raw["csv"]) if table else {}))
    a.text, a.csv = raw.get("text"), raw.get("csv")
    img = raw.get("image")
    a.image = None if img is None else np.frombuffer(img[2], dtype=np.uint8).reshape(img[0], img[1], 3)
    for k in ("summary", "spectra_csv"):
        if k in raw:
            setattr(a, k, raw[k])
    if "exposure" in raw:
        a.exposure = float(raw["exposure"])
    return a
