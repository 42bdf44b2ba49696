"""`check_section` and `bezier_to_elastica`: the production constraints, the verdict, mm/m
and rigid-motion invariance, arrays and lists alike, and no leak over 10⁴ calls."""

import math
import resource
import sys

import numpy as np
import pytest

import hotcut

BLADE = {"length": 1200, "max_curvature": 0.01}


def arch(n=200, width=600.0, height=40.0):
    return [(width * i / (n - 1), height * math.sin(math.pi * i / (n - 1))) for i in range(n)]


PHASE = 0.4


def wave(n=200, width=900.0, height=40.0, waves=1.25):
    """A sine from phase 0.4: inflections where 2π·waves·u + 0.4 = jπ, none at the ends."""
    return [(width * i / (n - 1), height * math.sin(2 * math.pi * waves * i / (n - 1) + PHASE)) for i in range(n)]


def inflections_x(width, waves):
    top = 2 * math.pi * waves + PHASE
    return [width * (j * math.pi - PHASE) / (2 * math.pi * waves) for j in range(1, 20) if j * math.pi < top]


def test_a_gentle_arch_is_cuttable():
    c = hotcut.check_section(arch(), blade=BLADE)
    assert c["cuttable"] and c["fit_ok"] and c["violations"] == [] and c["inflections"] == []
    assert c["length"] == pytest.approx(607.0, abs=1.0)
    assert c["rms"] <= 0.5 and c["max"] <= 2.0
    assert c["elastica"].family in ("noninflectional", "arc", "inflectional")


def test_each_constraint_is_reported():
    short = hotcut.check_section(arch(), blade={"length": 500, "max_curvature": 0.01})
    assert not short["cuttable"]
    (v,) = short["violations"]
    assert v["constraint"] == "dimension" and v["limit"] == 500 and v["value"] > 600
    tight = hotcut.check_section(arch(), blade={"length": 1200, "max_curvature": 1e-4})
    assert [v["constraint"] for v in tight["violations"]] == ["blade_strain"]
    # 1.25 waves: 2 inflections within 2 allowed; 2.75 waves: 5 of them
    two = hotcut.check_section(wave(), blade=BLADE)
    assert len(two["inflections"]) == 2
    assert [p["point"][0] for p in two["inflections"]] == pytest.approx(inflections_x(900, 1.25), abs=0.5)
    assert not any(v["constraint"] == "shape" for v in two["violations"])
    five = hotcut.check_section(wave(400, 1800, waves=2.75), blade={"length": 3000, "max_curvature": 0.01})
    assert len(five["inflections"]) == 5
    assert any(v["constraint"] == "shape" and v["inflections"] == 5 for v in five["violations"])


def test_the_held_blade_is_judged_with_its_loads():
    # the arch extended to the 1200 mm blade: stable, pushing on its holders
    c = hotcut.check_section(arch(), blade=BLADE)
    b = c["blade"]
    assert b["stability"] == "Stable" and b["margin"] > 0.5
    assert b["inflections"] >= 0 and b["force_n"] >= 0.0
    assert len(b["tension_n"]) == 2 and len(b["moment_nm"]) == 2
    # the same blade in metres: the same margin, newtons and newton-metres
    m = hotcut.check_section(
        [(x / 1000, y / 1000) for x, y in arch()], blade={"length": 1.2, "max_curvature": 10.0}, units="m"
    )["blade"]
    assert m["margin"] == pytest.approx(b["margin"], rel=1e-6)
    assert m["force_n"] == pytest.approx(b["force_n"], rel=1e-6, abs=1e-12)
    assert m["moment_nm"] == pytest.approx(b["moment_nm"], rel=1e-6, abs=1e-12)
    # a stiffer section: the loads scale with E·w·t³
    thick = hotcut.check_section(arch(), blade={**BLADE, "thickness": 2.0})["blade"]
    assert thick["moment_nm"][0] == pytest.approx(8 * b["moment_nm"][0], rel=1e-9)
    # three waves on a blade with no room: it cannot hold them, so the section is not
    # cuttable as one piece
    waves = hotcut.check_section(wave(400, 1200, height=20.0, waves=3.25), blade={"length": 1250, "max_curvature": 0.01})
    assert waves["blade"]["stability"] != "Stable" and not waves["cuttable"]


def test_units_and_rigid_motion_do_not_change_the_verdict():
    mm = hotcut.check_section(wave(), blade=BLADE)
    m = hotcut.check_section(
        [(x / 1000, y / 1000) for x, y in wave()], blade={"length": 1.2, "max_curvature": 10.0}, units="m"
    )
    assert m["cuttable"] == mm["cuttable"] and len(m["inflections"]) == len(mm["inflections"])
    assert m["length"] * 1000 == pytest.approx(mm["length"], rel=1e-9)
    assert m["rms"] * 1000 == pytest.approx(mm["rms"], rel=1e-6)
    a = 0.9
    moved = [(x * math.cos(a) - y * math.sin(a) + 77, x * math.sin(a) + y * math.cos(a) - 5) for x, y in wave()]
    r = hotcut.check_section(moved, blade=BLADE)
    assert r["cuttable"] == mm["cuttable"] and len(r["inflections"]) == 2
    assert r["length"] == pytest.approx(mm["length"], rel=1e-9)
    # the same curve in 3-D, in a vertical plane: points come back in 3-D
    p3 = [(x, 250.0, y) for x, y in wave()]
    r3 = hotcut.check_section(p3, blade=BLADE)
    assert len(r3["inflections"][0]["point"]) == 3 and r3["length"] == pytest.approx(mm["length"], rel=1e-9)


def test_arrays_and_lists_give_the_same_answers():
    pts = wave()
    a = hotcut.check_section(np.array(pts), blade=BLADE)
    b = hotcut.check_section(pts, blade=BLADE)
    strip = lambda d: {k: v for k, v in d.items() if k not in ("elastica", "inflections", "max_abs_curvature")}
    assert strip(a) == strip(b)
    assert a["elastica"].params == b["elastica"].params


def test_bad_blades_and_points():
    with pytest.raises(ValueError, match="blade"):
        hotcut.check_section(arch(), blade={"length": 1200})
    with pytest.raises(ValueError, match="blade"):
        hotcut.check_section(arch(), blade={"length": 1200, "max_curvature": 0.01, "colour": "red"})
    with pytest.raises(ValueError, match="units"):
        hotcut.check_section(arch(), blade=BLADE, units="inch")
    with pytest.raises(ValueError, match="distinct"):
        hotcut.check_section([(0, 0)] * 10, blade=BLADE)
    with pytest.raises(ValueError, match="rms"):
        hotcut.check_section(arch(), blade=BLADE, tolerance={"rms": -1})


def test_bezier_to_elastica():
    r = hotcut.bezier_to_elastica([(0, 0), (200, 60), (400, 60), (600, 0)], 800)
    assert r["can_bend"] and r["why_not"] is None
    assert r["end_point_error"] < 1e-9 * r["length"]
    assert 1e-6 * r["length"] < r["max_deviation"] < 0.01 * r["length"]
    assert r["eq11_residual"] > 0 and r["elastica"].length == pytest.approx(r["length"], rel=1e-9)
    assert r["blade"]["elastica"].length == pytest.approx(800, rel=1e-12)
    short = hotcut.bezier_to_elastica([(0, 0), (200, 60), (400, 60), (600, 0)], 500)
    assert not short["can_bend"] and "shorter" in short["why_not"] and short["blade"] is None
    stiff = hotcut.bezier_to_elastica([(0, 0), (200, 60), (400, 60), (600, 0)], 800, max_curvature=1e-4)
    assert not stiff["can_bend"] and "max_curvature" in stiff["why_not"]
    # mm and m
    m = hotcut.bezier_to_elastica([(0, 0), (0.2, 0.06), (0.4, 0.06), (0.6, 0)], 0.8)
    assert m["max_deviation"] * 1000 == pytest.approx(r["max_deviation"], rel=1e-6)
    assert m["eq11_residual"] == pytest.approx(r["eq11_residual"], rel=1e-6)
    with pytest.raises(ValueError, match="4 control points"):
        hotcut.bezier_to_elastica([(0, 0), (1, 1), (2, 1), (3, 0), (4, 0)], 10)


def _rss_kb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() // 1024


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ten_thousand_checks_do_not_leak():
    pts = np.array(wave())
    for _ in range(300):  # warm up: allocator pools, numpy, caches
        hotcut.check_section(pts, blade=BLADE)
    before = _rss_kb()
    for _ in range(10_000):
        c = hotcut.check_section(pts, blade=BLADE)
    grown = _rss_kb() - before
    # a leak of even one point list per call (200 × 2 floats) would be ≥ 30 MB here
    assert grown < 4096, f"RSS grew by {grown} kB over 10⁴ calls"
    assert c["length"] > 0
