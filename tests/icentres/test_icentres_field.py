"""``mech icentres`` on every pair type against the velocity field solved from the constraints.

The reference is :mod:`oracles.velocity_field` on the cases of :mod:`oracles.field_cases`:
each mechanism is written once as YAML for mech and once as pin, slider and contact
constraints for the oracle, so the I-centres and the ω found by the I-centre method are
checked against a field mech had no part in.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cli_runner import mech, no_traceback, strict_json
from oracles.field_cases import IC_CASES
from oracles.velocity_field import icentre, velocity_field


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("case", sorted(IC_CASES))
def test_every_icentre_and_omega_matches_the_constraint_velocity_field(tmp_path, case):
    """Finite centres to 1e-9 of the mechanism's size, centres at infinity by direction, ω to 1e-9."""
    text, links, constraints, drive = IC_CASES[case]
    m = _write(tmp_path / f"{case}.yaml", text)
    p = mech("icentres", "--json", str(m))
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    n = len(links)
    assert d["count"] == n * (n - 1) // 2 == len(d["icentres"])
    field = velocity_field(links, "frame", constraints, drive)
    size = max(np.linalg.norm(np.subtract(c[1], e[1])) for c in constraints for e in constraints)
    for ic in d["icentres"]:
        a, b = ic["links"]
        P, direction = icentre(field, a, b)
        if P is None and direction is None:  # no relative motion (a link at rest on ground): any point
            continue
        if P is None:
            assert ic["at_infinity"] and ic["point"] is None, ic
            assert abs(abs(float(np.dot(direction, ic["direction"]))) - 1) < 1e-9, ic
        else:
            assert ic["point"] is not None, ic
            assert np.linalg.norm(np.array(ic["point"]) - P) <= 1e-9 * max(size, np.linalg.norm(P)), (ic, P)
    wmax = max(abs(x) for _, x in field.values())
    for row in d["omega"]:
        w = field[row["link"]][1]
        assert row["by_icentres"] is not None and abs(row["by_icentres"] - w) <= 1e-9 * wmax, (row, w)


def test_icentres_of_slot_gears_and_cam_are_the_textbook_points(tmp_path):
    """Closed forms independent of the field: the pitch point, the normal through the contact."""

    def ic(case, name):
        m = _write(tmp_path / f"{case}.yaml", IC_CASES[case][0])
        p = mech("icentres", "--json", str(m))
        assert p.returncode == 0, p.stderr
        return {i["name"]: i for i in strict_json(p.stdout)["icentres"]}[name]

    # Scotch yoke: I23 on the normal to the slot through the pin (y = r sin th) and on x = 0.
    assert ic("slot_scotch_yoke", "I23")["point"] == pytest.approx(
        [0, 0.1 * math.sin(math.radians(60))], abs=1e-12
    )
    # gears: the pitch point divides the centre line in the ratio of the radii
    assert ic("gears_external", "I23")["point"] == pytest.approx([0.05, 0], abs=1e-12)
    assert ic("gears_internal", "I23")["point"] == pytest.approx([-0.05, 0], abs=1e-12)  # outside O1O2
    # cam: the common normal through T meets the line of I12-I13 (y = 0): x = 0.01 - 0.04 cot(120 deg)
    x = 0.01 - 0.04 / math.tan(math.radians(120))
    assert ic("cam_offset_follower", "I23")["point"] == pytest.approx([x, 0], abs=1e-12)
