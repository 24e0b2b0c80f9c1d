"""The worked example of docs/nonlinear_core.md §8 runs as printed: its code block is executed and
every number it prints matches the documented output to 1e-6 relative (absolute 1e-12 for values at
round-off, e.g. the ζ of a stuck point). A change of the nonlinear core that moves a result, or an
API change that breaks the example, fails here."""
import contextlib
import io
import re
from pathlib import Path

import numpy as np

DOC = Path(__file__).resolve().parents[2] / "docs" / "nonlinear_core.md"
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _blocks(section: str) -> tuple[str, str]:
    """(python code, printed output) of the section titled ``section``."""
    text = DOC.read_text().split(f"## {section}", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    output = re.search(r"Output[^\n]*\n\n```\n(.*?)```", text, re.S).group(1)
    return code, output


def test_worked_example_prints_the_documented_output():
    code, expected = _blocks("8. Worked example")
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(code, str(DOC), "exec"), {"__name__": "worked_example"})
    got_lines, want_lines = printed.getvalue().strip().splitlines(), expected.strip().splitlines()
    assert len(got_lines) == len(want_lines)
    for got, want in zip(got_lines, want_lines):
        assert NUMBER.sub("#", got) == NUMBER.sub("#", want), (got, want)   # same text around numbers
        g = np.array(NUMBER.findall(got), float)
        w = np.array(NUMBER.findall(want), float)
        np.testing.assert_allclose(g, w, rtol=1e-6, atol=1e-12, err_msg=got)
