"""The README's Python example runs and prints what the README says."""
import contextlib
import io
import os
import re

from conftest import ROOT


def test_readme_example_runs_and_prints_the_documented_colour():
    text = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    section = text[text.index("## Python"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert len(code.strip().splitlines()) == 5, "the README promises a five-line example"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), {})
    lines = out.getvalue().splitlines()
    assert lines[0] == "#6d75ad"  # the colour the README's rough-film table gives for the smooth film
    assert lines[1].startswith("(3, 301)")
