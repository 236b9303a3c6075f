"""The examples in the package's docstrings run and give what they show."""
import doctest

import iridis
import iridis.color
import iridis.thinfilm
import iridis.tmm
import iridis.vision
from iridis import _native


def test_docstring_examples():
    finder, runner = doctest.DocTestFinder(), doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    tests = []
    for mod in (iridis, iridis.tmm, iridis.thinfilm, iridis.color, iridis.vision):
        tests += finder.find(mod)
    for name in ("coh_tmm",):
        tests += finder.find(getattr(_native, name), name=f"iridis.tmm.{name}", globs={})
    examples = sum(len(t.examples) for t in tests)
    for t in tests:
        runner.run(t)
    result = runner.summarize(verbose=False)
    assert examples >= 15 and result.failed == 0, result
