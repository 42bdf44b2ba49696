"""Inputs a hostile-input campaign found mishandled, each now a clear error or the right
answer."""

import math
import shutil

import pytest

import hotcut
from hotcut import elastica
from conftest import JOBS

BLADE = {"length": 1200, "max_curvature": 0.01}
WAVE = [(900 * i / 199, 40 * math.sin(2 * math.pi * 1.25 * i / 199 + 0.4)) for i in range(200)]
ARCH = [(0, 0), (200, 60), (400, 60), (600, 0)]


def test_a_repeated_vertex_changes_nothing():
    base = hotcut.check_section(WAVE, BLADE)
    twice = hotcut.check_section(WAVE[:50] + [WAVE[49]] + WAVE[50:], BLADE)
    assert twice["fit_error"] is None
    assert twice["cuttable"] == base["cuttable"] and len(twice["inflections"]) == 2
    assert twice["rms"] == pytest.approx(base["rms"], rel=1e-6)


@pytest.mark.parametrize("scale", [1e-9, 1e-3, 1e3, 1e12])
def test_any_scale_keeps_its_points(scale):
    c = hotcut.check_section(
        [(x * scale, y * scale) for x, y in WAVE],
        {"length": 1200 * scale, "max_curvature": 0.01 / scale},
        {"rms": 0.5 * scale, "max": 2 * scale, "smoothing": 0.05 * scale, "bisection": 1e-6 * scale},
    )
    assert len(c["inflections"]) == 2 and c["length"] == pytest.approx(
        hotcut.check_section(WAVE, BLADE)["length"] * scale, rel=1e-9
    )


@pytest.mark.parametrize(
    "blade,tolerance,field",
    [
        ({"length": 0, "max_curvature": 0.01}, None, "blade/length"),
        ({"length": 1200, "max_curvature": -1}, None, "blade/max_curvature"),
        ({"length": 1200, "max_curvature": 0.01, "kerf": -1}, None, "blade/kerf"),
        (BLADE, {"bisection": 0}, "tolerance/bisection"),
        (BLADE, {"min_turning": -1}, "tolerance/min_turning"),
    ],
)
def test_blades_and_tolerances_in_the_ranges_of_a_job(blade, tolerance, field):
    with pytest.raises(ValueError, match=field):
        hotcut.check_section(WAVE, blade, tolerance)


@pytest.mark.parametrize("length", [0, -1, float("nan"), float("inf")])
def test_bezier_blade_length_must_be_positive(length):
    with pytest.raises(ValueError, match="blade_length"):
        hotcut.bezier_to_elastica(ARCH, length)


def test_integers_out_of_range_are_value_errors():
    e = elastica.fit(WAVE[:40])
    with pytest.raises(ValueError, match="sample"):
        e.sample(-1)
    with pytest.raises(ValueError, match="samples"):
        hotcut.check_section(WAVE, BLADE, samples=-1)
    with pytest.raises(ValueError, match="max_inflections"):
        hotcut.bezier_to_elastica(ARCH, 800, max_inflections=-1)
    with pytest.raises(ValueError, match="plane_tolerance"):
        elastica.fit([(x, y, 0.0) for x, y in WAVE], plane_tolerance=float("nan"))


def test_between_refuses_degenerate_end_points():
    with pytest.raises(ValueError, match="p0 and p1"):
        elastica.between([0, 0], 0, [0, 0], 0, 1)
    with pytest.raises(ValueError):
        elastica.between([0, 0], 0, [5e-324, 0], 0, 1e-323)


@pytest.mark.parametrize(
    "patch,pointer",
    [
        ({"surface": {"HeightField": {"z": "1", "x": [0, 1, 2], "y": [0, 1]}}}, "/surface/HeightField/x"),
        ({"task": None}, "/task"),
    ],
)
def test_dict_errors_name_the_field_not_a_hidden_json_line(patch, pointer):
    job = {"name": "x", "surface": {"HeightField": {"z": "1", "x": [0, 1], "y": [0, 1]}}, "task": {"Analyze": {}}}
    job.update(patch)
    with pytest.raises(hotcut.JobError) as e:
        hotcut.validate(job)
    assert e.value.pointer == pointer and e.value.line is None and e.value.col is None


def test_run_arguments_are_checked_before_running(tmp_path):
    with pytest.raises(TypeError, match="progress"):
        hotcut.run(JOBS / "precut-bump.ron", progress=5)
    f = tmp_path / "a-file"
    f.write_text("keep me")
    with pytest.raises(ValueError, match="not a folder"):
        hotcut.run(JOBS / "precut-bump.ron", f)
    assert f.read_text() == "keep me"
    with pytest.raises(ValueError, match="empty path"):
        hotcut.run(JOBS / "precut-bump.ron", "")


def test_a_path_with_parentheses_is_a_path(tmp_path):
    d = tmp_path / "dir (x)"
    d.mkdir()
    shutil.copy(JOBS / "precut-bump.ron", d / "job (1).ron")
    assert hotcut.validate(str(d / "job (1).ron"))["task"] == "PreCut"


def test_a_job_of_shared_lists_is_refused_not_walked_forever():
    x = [0]
    for _ in range(40):
        x = [x, x]  # 40 levels, 2⁴⁰ leaves
    job = {"name": "x", "surface": {"HeightField": {"z": "1", "x": [0, 1], "y": [0, 1]}},
           "task": {"Analyze": {}}, "outputs": x}
    with pytest.raises(hotcut.JobError, match="values"):
        hotcut.validate(job)


def test_the_environment_sets_only_the_start():
    import subprocess
    import sys

    code = (
        "import hotcut; from hotcut import elastica\n"
        "e = elastica.fit([(0, 0), (1, 0.5), (2, 0.6), (3, 0.5), (4, 0)])\n"
        "assert type(e.start) is list\n"
        "hotcut.use_numpy(True)\n"
        "assert type(e.start).__name__ == 'ndarray'\n"
    )
    env = dict(__import__("os").environ, HOTCUT_ARRAYS="list")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
