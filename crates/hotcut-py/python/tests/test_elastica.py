"""`hotcut.elastica`: fits of exact elastica (mpmath) to 1e-9, 3-D planar points, the
boundary-value elastica, Jacobi functions against mpmath, arrays and lists alike."""

import math

import mpmath as mp
import numpy as np
import pytest

from hotcut import elastica
import exact

NAMES = ["k", "s0", "l", "S", "phi", "x0", "y0"]

# both families, gentle to strongly bent, at sizes from 0.4 to 1000 and placed anywhere
CASES = [
    ("inflectional", 0.6, 0.3, 2.5, 100.0, 0.2, 10.0, -5.0),
    ("inflectional", 0.3, 0.5, 2.0, 1000.0, -0.5, 100.0, 50.0),
    ("inflectional", 0.95, -1.0, 3.0, 0.4, 1.0, 3.0, 2.0),
    ("inflectional", 0.7, 0.0, 4.0, 250.0, -2.0, 1000.0, -300.0),
    ("noninflectional", 0.8, 0.2, 1.5, 50.0, 0.0, 0.0, 0.0),
    ("noninflectional", 0.5, 0.2, 1.5, 250.0, 2.5, -40.0, 7.0),
    ("noninflectional", 0.3, 0.1, 1.0, 0.4, 1.0, 3.0, 2.0),
]


def _check_params(e, case, tol):
    p = e.params
    assert p["type"] == "elastica" and p["family"] == case[0]
    for name, want in zip(NAMES, case[1:]):
        # lengths and places relative to their size (S = 1000 is known to ~1e-12 of itself)
        assert abs(p[name] - want) <= tol * max(1.0, abs(want)), (name, p[name], want)


@pytest.mark.parametrize("case", CASES)
def test_fit_of_exact_points_returns_the_parameters(case):
    pts, s = exact.points(*case, 200)
    # points alone (chord lengths) and with their exact arc lengths
    for e in (elastica.fit(pts), elastica.fit(pts, arc_length=s)):
        _check_params(e, case, 1e-9)
        assert e.rms < 1e-9 * e.length and e.dim == 2
        assert e.family == case[0]
        assert abs(e.length - abs(case[3]) * case[4]) < 1e-9 * e.length
        assert np.allclose(e.start, pts[0], atol=1e-9) and np.allclose(e.end, pts[-1], atol=1e-9)


def test_unpolished_fit_is_the_cli_fit_and_close():
    case = CASES[0]
    pts, _ = exact.points(*case, 200)
    raw = elastica.fit(pts, polish=False)
    _check_params(raw, case, 1e-4)  # the 2^-30 grid of the unit-invariant fit
    assert raw.rms >= elastica.fit(pts).rms


@pytest.mark.parametrize("case", CASES[:3])
def test_a_planar_curve_in_3d_fits_as_in_its_plane(case):
    pts, _ = exact.points(*case, 120)
    flat = elastica.fit(pts)
    # the plane turned and moved: the same shape, the same length and residuals
    a, b = 0.7, -1.1
    rot = np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]]) @ np.array(
        [[1, 0, 0], [0, math.cos(b), -math.sin(b)], [0, math.sin(b), math.cos(b)]]
    )
    p3 = np.array([[x, y, 0.0] for x, y in pts]) @ rot.T + np.array([5.0, -3.0, 12.0])
    e = elastica.fit(p3)
    assert e.dim == 3 and e.plane is not None
    assert e.params["k"] == pytest.approx(flat.params["k"], abs=1e-9)
    assert e.length == pytest.approx(flat.length, rel=1e-9)
    assert np.allclose(e.sample(len(p3)), p3, atol=1e-8 * e.length)
    assert np.allclose(e.evaluate([0.0, 1.0]), p3[[0, -1]], atol=1e-8 * e.length)
    t = np.asarray(e.tangent(0.3))
    assert abs(np.dot(t, e.plane["normal"])) < 1e-12 and abs(np.linalg.norm(t) - 1) < 1e-12
    bent = p3.copy()
    bent[5] += 0.01 * e.length * np.asarray(e.plane["normal"])
    with pytest.raises(ValueError, match="not planar"):
        elastica.fit(bent)
    assert elastica.fit(bent, plane_tolerance=0.02 * e.length).dim == 3


def test_between_meets_its_end_data():
    e = elastica.between((0, 0), 0.4, (10, 0), -0.4, 10.5)
    assert max(abs(r) for r in e.residuals) < 1e-10
    assert np.allclose(e.start, (0, 0), atol=1e-9) and np.allclose(e.end, (10, 0), atol=1e-9)
    assert e.length == pytest.approx(10.5, rel=1e-12)
    t0, t1 = e.start_tangent, e.end_tangent
    assert math.atan2(t0[1], t0[0]) == pytest.approx(0.4, abs=1e-9)
    assert math.atan2(t1[1], t1[0]) == pytest.approx(-0.4, abs=1e-9)
    # tangents as vectors give the same curve
    v = elastica.between((0, 0), (math.cos(0.4), math.sin(0.4)), (10, 0), (math.cos(0.4), -math.sin(0.4)), 10.5)
    assert np.allclose(v.sample(9), e.sample(9), atol=1e-9)
    # scaled by 1000 (mm → m): the same shape
    m = elastica.between((0, 0), 0.4, (0.01, 0), -0.4, 0.0105)
    assert np.allclose(np.asarray(m.sample(9)) * 1000, e.sample(9), atol=1e-9)
    with pytest.raises(ValueError):
        elastica.between((0, 0), 0.4, (10, 0), -0.4, 9.0)  # shorter than the chord


@pytest.mark.parametrize("m", [0.0, 0.3, 0.5, 0.9, 0.999])
def test_elliptic_against_mpmath(m):
    e = elastica.Elliptic(m)
    assert e.K() == pytest.approx(float(mp.ellipk(m)), rel=1e-14)
    assert e.E() == pytest.approx(float(mp.ellipe(m)), rel=1e-14)
    for u in (-2.0, 0.3, 1.0, 5.0):
        for f in ("sn", "cn", "dn"):
            assert getattr(e, f)(u) == pytest.approx(float(mp.ellipfun(f, u, m=m)), abs=1e-14)
        am = e.am(u)
        assert math.sin(am) == pytest.approx(e.sn(u), abs=1e-14)
        assert e.E(u) == pytest.approx(float(mp.ellipe(am, m)), abs=1e-13)
    us = np.linspace(-3, 3, 7)
    assert np.allclose(e.sn(us), [e.sn(float(u)) for u in us], atol=0)
    with pytest.raises(ValueError):
        elastica.Elliptic(1.5)


def test_arrays_and_lists_give_the_same_answers():
    pts, s = exact.points(*CASES[0], 200)
    as_list = [list(p) for p in pts]
    as_tuple = tuple(tuple(p) for p in pts)
    as_array = np.array(pts)
    fits = [elastica.fit(x) for x in (as_list, as_tuple, as_array, as_array.astype(np.float32).astype(float))]
    for f in fits[1:3]:
        assert f.params == fits[0].params
    assert fits[0].params["k"] == pytest.approx(fits[3].params["k"], abs=1e-6)
    e = fits[0]
    assert np.asarray(e.evaluate(np.array([0.1, 0.5]))).tolist() == np.asarray(e.evaluate([0.1, 0.5])).tolist()
    assert elastica.fit(pts, arc_length=np.array(s)).params == elastica.fit(pts, arc_length=s).params


def test_bad_points_are_value_errors():
    with pytest.raises(ValueError, match="at least 3"):
        elastica.fit([(0, 0), (1, 1)])
    with pytest.raises(ValueError, match="not finite"):
        elastica.fit([(0, 0), (1, float("nan")), (2, 0)])
    with pytest.raises(ValueError, match="coordinates"):
        elastica.fit([(0, 0), (1, 1, 1), (2, 0)])
    with pytest.raises(TypeError):
        elastica.fit([(0, 0), "ab", (2, 0)])
    with pytest.raises(ValueError, match="shape"):
        elastica.fit(np.zeros((5, 4)))
    with pytest.raises(ValueError, match="constraint"):
        elastica.fit([(0, 0), (1, 1), (2, 0)], constraint="tight")
    with pytest.raises(ValueError, match="increasing"):
        elastica.fit([(0, 0), (1, 1), (2, 0)], arc_length=[0, 2, 1])
    e = elastica.fit([(0, 0), (1, 0.5), (2, 0.6), (3, 0.5), (4, 0)])
    with pytest.raises(ValueError):
        e.sample(1)


def test_a_panic_in_rust_is_a_runtime_error():
    import hotcut

    with pytest.raises(RuntimeError, match="internal error.*boom"):
        hotcut._native._panic_for_test("boom")


def test_fit_is_the_same_in_mm_and_m_and_under_rigid_motion():
    rng = np.random.default_rng(7)
    for case in CASES[:5]:
        pts, _ = exact.points(*case, 150)
        size = abs(case[3]) * case[4]
        noisy = np.array(pts) + rng.normal(scale=1e-3 * size, size=(150, 2))
        mm = elastica.fit(noisy)
        m = elastica.fit(noisy / 1000)
        assert m.family == mm.family
        assert np.allclose(np.asarray(m.sample(33)) * 1000, mm.sample(33), atol=2e-6 * mm.length)
        assert m.rms * 1000 == pytest.approx(mm.rms, rel=1e-6)
        a = 0.8
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        moved = elastica.fit(noisy @ rot.T + [300.0, -70.0])
        back = (np.asarray(moved.sample(33)) - [300.0, -70.0]) @ rot
        assert np.allclose(back, mm.sample(33), atol=2e-6 * mm.length)
