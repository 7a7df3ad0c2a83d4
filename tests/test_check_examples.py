"""Every shipped example, checked against its own ``answers``.

The claims in mechanisms/ come from outside mech: published textbook answers
(within their drawing accuracy), the slides' worked counts, and closed-form
solutions their authors derived by hand or in scratch scripts (each file says
which).  Every one must pass: a failure here is a wrong number in mech, to be
fixed at its cause.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from mech.check import PASS, check_file

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "mechanisms").glob("*.yaml"))


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_claimed_answer_in_the_examples_passes(path: Path) -> None:
    result = check_file(str(path))
    assert not result.problems, [p.message for p in result.problems]
    assert result.verdicts, f"{path.name} claims nothing"
    wrong = [(v.key, v.status, v.message) for v in result.verdicts if v.status != PASS]
    assert not wrong, wrong
