"""Euler elastica in closed form: ``fit`` points of a plane, ``between`` two end points
with their tangents and a length, the ``Elastica`` they give, and Jacobi's elliptic
functions (``Elliptic``)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

Array = Any
"""A numpy array, or a list (of lists) without numpy."""

class Elastica:
    """A planar elastica (or a line or a circular arc, its limits), parameterized by
    t ∈ [0, 1] at constant speed; in 3-D when fitted to 3-D points."""

    @property
    def family(self) -> str:
        """``"inflectional"``, ``"noninflectional"``, ``"line"`` or ``"arc"``."""
    @property
    def params(self) -> Dict[str, Any]:
        """Its parameters as reports write them: for an elastica ``k, s0, l, S, phi, x0,
        y0`` with p(t) = S·R(φ)·f(s0 + l·t) + (x0, y0) in its plane's coordinates."""
    @property
    def dim(self) -> int:
        """2, or 3 for a curve fitted to 3-D points."""
    @property
    def plane(self) -> Optional[Dict[str, Array]]:
        """``{"origin", "u", "v", "normal"}`` of a 3-D curve's plane, else ``None``."""
    @property
    def length(self) -> float: ...
    @property
    def rms(self) -> Optional[float]:
        """RMS distance from the fitted points over arc length (``None`` unless fitted)."""
    @property
    def max(self) -> Optional[float]:
        """Largest distance of a fitted point (``None`` unless fitted)."""
    @property
    def converged(self) -> Optional[bool]: ...
    @property
    def residuals(self) -> Optional[Tuple[float, float, float]]:
        """``between``'s residuals: start angle, turning (radians), length (relative)."""
    @property
    def start(self) -> Array: ...
    @property
    def end(self) -> Array: ...
    @property
    def start_tangent(self) -> Array: ...
    @property
    def end_tangent(self) -> Array: ...
    def evaluate(self, t: Union[float, Sequence[float]]) -> Array:
        """The point at ``t``, or the (n, dim) points at every t of a sequence."""
    def tangent(self, t: Union[float, Sequence[float]]) -> Array:
        """The unit tangent at ``t`` (a number or a sequence)."""
    def curvature(self, t: Union[float, Sequence[float]]) -> Union[float, Array]:
        """Signed curvature at ``t`` (left turn positive in its plane)."""
    def sample(self, n: int) -> Array:
        """``n`` ≥ 2 points at equal arc length from t = 0 to 1, shape (n, dim)."""
    def inflections(self) -> List[float]:
        """The t of its inflections inside (0, 1)."""
    def max_curvature(self) -> float:
        """Its largest |curvature|."""

def fit(
    points: Any,
    constraint: str = "free",
    *,
    arc_length: Optional[Sequence[float]] = None,
    polish: bool = True,
    plane_tolerance: Optional[float] = None,
) -> Elastica:
    """The elastica (or line, or arc) closest to ``points``, an (n, 2) or (n, 3)
    array-like of n ≥ 3 points of one plane (3-D points must lie within
    ``plane_tolerance``, default 1e-6 of their extent, of their best plane).

    ``constraint``: ``"free"``, ``"end_points"`` (the first and last points are
    interpolated) or ``"end_points_and_length"``. ``arc_length``: the points' arc lengths
    when known (default: chord lengths). ``polish``: refine on the points as given after
    the fit on the unit-invariant 2⁻³⁰ grid, kept where it moves the curve by less than
    ~1e-6 of its length (parameters of exact points to ~1e-11; noisy data keep the grid's
    fit); ``False`` gives the CLI's FitCurves numbers exactly.
    """

def between(
    p0: Sequence[float],
    t0: Union[float, Sequence[float]],
    p1: Sequence[float],
    t1: Union[float, Sequence[float]],
    length: float,
) -> Elastica:
    """The elastica from 2-D point ``p0`` to ``p1`` with end tangents ``t0``, ``t1``
    (angles in radians, taken as unwrapped turning, or 2-vectors, turning within ±π) and
    arc length ``length`` (more than the chord), in closed form (``design::bvp``)."""

class Elliptic:
    """Jacobi's elliptic functions and integrals of one parameter m = k² ∈ [0, 1]."""

    def __init__(self, m: float) -> None: ...
    @property
    def m(self) -> float: ...
    def K(self) -> float:
        """The complete integral of the first kind K(m), the quarter period."""
    def E(self, u: Union[None, float, Sequence[float]] = None) -> Union[float, Array]:
        """``E()``: the complete integral E(m); ``E(u)``: Jacobi's epsilon function
        E(u|m) = ∫₀ᵘ dn² = E(am u | m)."""
    def sn(self, u: Union[float, Sequence[float]]) -> Union[float, Array]: ...
    def cn(self, u: Union[float, Sequence[float]]) -> Union[float, Array]: ...
    def dn(self, u: Union[float, Sequence[float]]) -> Union[float, Array]: ...
    def am(self, u: Union[float, Sequence[float]]) -> Union[float, Array]:
        """The amplitude am(u|m), continuous and increasing in u."""
