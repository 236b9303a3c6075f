"""The examples in the package's docstrings run and give what they show."""
import doctest

import iridis
import iridis.bench
import iridis.color
import iridis.diffraction
import iridis.film
import iridis.lab
import iridis.render
import iridis.scan_report
import iridis.surface
import iridis.thinfilm
import iridis.tmm
import iridis.vision
from iridis import _native


def test_docstring_examples():
    finder, runner = doctest.DocTestFinder(), doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    tests = []
    # Every module: an example that no test runs goes stale (film's asked a spectrum of one wavelength).
    modules = (iridis, iridis.tmm, iridis.thinfilm, iridis.color, iridis.vision, iridis.film, iridis.surface,
               iridis.diffraction, iridis.lab, iridis.render, iridis.scan_report, iridis.bench)
    for mod in modules:
        tests += finder.find(mod)
    for name in ("coh_tmm",):
        tests += finder.find(getattr(_native, name), name=f"iridis.tmm.{name}", globs={})
    examples = sum(len(t.examples) for t in tests)
    for t in tests:
        runner.run(t)
    result = runner.summarize(verbose=False)
    assert examples >= 15 and result.failed == 0, result
