"""The README's "From Python" scripts run as written (compas' needs compas, which the tests
do not install; the Grasshopper one gets stand-ins for Rhino's points)."""

import math
import os
import re

from conftest import REPO


def _blocks():
    text = (REPO / "README.md").read_text()
    section = text[text.index("## From Python"):text.index("## Layout")]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def test_the_plain_python_script_runs(capsys, monkeypatch):
    monkeypatch.chdir(REPO)
    exec(compile(_blocks()[0], "README plain", "exec"), {})
    out = capsys.readouterr().out
    assert "PreCut" in out and "/cutting/sections" in out


def test_the_grasshopper_script_runs_on_plain_points():
    class Point3d:  # what a Grasshopper list of points gives: X, Y, Z
        def __init__(self, x, y, z):
            self.X, self.Y, self.Z = x, y, z

    import hotcut

    points = [Point3d(3.0 * i, 100.0, 40 * math.sin(3.0 * i / 100)) for i in range(200)]

    def run(blade_length):
        scope = {"points": points, "blade_length": blade_length, "max_curvature": 0.01}
        try:
            exec(compile(_blocks()[1], "README grasshopper", "exec"), scope)
        finally:
            hotcut.use_numpy(True)
        return scope

    # a 1200 mm blade continues the section's wave (period ~630 mm) into more inflections:
    # it does not hold its shape, and the script says so
    long = run(1200.0)
    assert long["ok"] is False and len(long["why"]) == 1
    assert long["why"][0].startswith("blade Unstable"), long["why"]
    scope = run(800.0)
    assert scope["ok"] is True and scope["why"] == []
    blade = scope["blade"]
    assert len(blade) == 50 and all(type(p) is tuple and len(p) == 3 for p in blade)
    assert all(abs(p[1] - 100.0) < 1e-9 for p in blade)
