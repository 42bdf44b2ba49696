"""hotcut from Python: run hotcut jobs, fit and evaluate Euler elastica, and check the hot
blade's production constraints while a design is dragged.

Lengths are in the caller's units throughout (a job's ``units`` say which); arrays come out
as numpy arrays when numpy is installed and ``use_numpy(False)`` was not called, else as
lists of lists. Points may be given as any sequence of 2 or 3 numbers per point (lists,
tuples, numpy arrays, Rhino ``Point3d``, compas ``Point``).
"""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, TypedDict, Union

from . import elastica as elastica
from .elastica import Elastica

__version__: str

Job = Union[str, "os.PathLike[str]", Dict[str, Any]]
"""A job: a path to a job file, RON text (a ``str`` holding ``(``), or a dict with the job
file's fields in its JSON form (``schemas/job.schema.json``): enum variants as one-key
dicts, ``{"HeightField": {"z": ..., "x": (0, 400), "y": (0, 1500)}}``, ``{"Analyze": {}}``."""

Points = Any
"""An (n, 2) or (n, 3) array-like of points."""

class HotcutError(Exception):
    """Base class of the errors hotcut raises (bad input raises ``ValueError`` or
    ``TypeError``; a bug in hotcut, ``RuntimeError``)."""

class JobError(HotcutError):
    """A job that is not valid. Nothing was written. ``str(e)`` is what the CLI prints."""

    message: str
    """What is wrong with the first field found."""
    path: str
    """The job file (for text and dict jobs, ``<job text>`` / ``<job dict>`` in ``base``)."""
    pointer: Optional[str]
    """JSON pointer of the field, e.g. ``/tolerance/rms``."""
    line: Optional[int]
    """Line of a RON job's error (1-based), else ``None``."""
    col: Optional[int]
    """Column of a RON job's error (1-based), else ``None``."""
    errors: List[Dict[str, Any]]
    """Every problem found: ``message``, ``path``, ``pointer``, ``line``, ``col``, ``text``."""

class RunError(HotcutError):
    """A valid job whose run failed, or that cut nothing."""

    report: Optional[Dict[str, Any]]
    """The report of a run that cut nothing (runs in memory); else ``None``."""

def run(
    job: Job,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    progress: Optional[Callable[[str, int, int], Any]] = None,
    base: Optional[Union[str, "os.PathLike[str]"]] = None,
    max_work: Optional[float] = None,
    max_memory_gb: Optional[float] = None,
    max_output_mb: Optional[float] = None,
) -> Dict[str, Any]:
    """Runs a job as ``hotcut run`` does and returns its report, the data of
    ``report.json``.

    ``out``: write the job's outputs to ``out/<job name>/``, replacing the earlier ones as a
    whole; ``None`` writes nothing. ``progress(label, done, total)`` is called from this
    thread as steps advance (``total`` 0: not counted). ``base``: the folder relative file
    names of a text or dict job are read from (default: the current one). The limits are
    the CLI's ``--max-work``, ``--max-memory`` and ``--max-output``.

    The run goes on another thread with the GIL released. Ctrl-C (``KeyboardInterrupt``)
    or an exception raised by ``progress`` returns within a second; the run stops at its
    next progress step (``Compare``'s processes and ``RuledBlocks``' per-block strategy
    report none and finish in the background) and is not put in place, so the earlier
    output stays whole.

    Raises ``JobError`` for an invalid job (nothing written), ``RunError`` when the run
    fails or cuts nothing.
    """

def validate(
    job: Job,
    *,
    base: Optional[Union[str, "os.PathLike[str]"]] = None,
    max_work: Optional[float] = None,
    max_memory_gb: Optional[float] = None,
    max_output_mb: Optional[float] = None,
) -> Dict[str, Any]:
    """Checks a job as ``hotcut validate`` does (syntax, schema, semantics, the work and
    memory its run would take) without running it. Returns ``{"name", "task", "estimate",
    "warnings"}``; raises ``JobError``."""

class Violation(TypedDict, total=False):
    constraint: str
    """``"dimension"`` (longer than the blade), ``"shape"`` (too many inflections) or
    ``"blade_strain"`` (bent tighter than the blade takes)."""

class SectionPoint(TypedDict):
    s: float
    """Arc length from the first point."""
    point: Sequence[float]
    curvature: float

class HeldBlade(TypedDict):
    margin: float
    """Stability margin: the smallest eigenvalue of the held blade's second variation over a
    straight, unloaded blade's (unit-free; ≤ 0 where it buckles out of the shape)."""
    stability: str
    """``"Stable"``, ``"Marginal"`` (below ``blade["min_margin"]``, default 0.05) or
    ``"Unstable"``."""
    inflections: int
    """Inflections of the whole blade, its extension included."""
    turning: float
    lead_in: float
    """Where the section sits along the blade: the blade's length before it."""
    force_n: float
    """The force on either holder, N (the blade's section from ``blade``: thickness, width,
    youngs_modulus, or a 1 mm × 25 mm spring-steel strip)."""
    tension_n: Sequence[float]
    moment_nm: Sequence[float]

class SectionCheck(TypedDict):
    cuttable: bool
    """No constraint broken, the elastica within tolerance and its blade holding its shape:
    one blade cuts it."""
    blade: Optional[HeldBlade]
    """The elastica extended to the blade's length where along it the blade holds best."""
    fit_ok: bool
    length: float
    inflections: List[SectionPoint]
    max_abs_curvature: SectionPoint
    suppressed_inflections: int
    smoothing_rms: float
    violations: List[Violation]
    tolerance: Sequence[float]
    """(rms, max) the elastica is held to."""
    rms: Optional[float]
    max: Optional[float]
    fit_error: Optional[str]
    elastica: Optional[Elastica]

def check_section(
    points: Points,
    blade: Dict[str, Any],
    tolerance: Optional[Dict[str, Any]] = None,
    *,
    units: str = "mm",
    samples: Optional[int] = None,
    plane_tolerance: Optional[float] = None,
) -> SectionCheck:
    """One section (points of a plane, 2-D or 3-D) against the production constraints of
    the thesis §5.1 — its length against the blade's, its inflections against
    ``max_inflections``, its curvature against ``max_curvature`` — and how close one
    elastica comes (RMS and largest distance against the tolerance), and whether the blade
    extended along that elastica holds its shape, with the loads on its holders.

    ``blade`` and ``tolerance`` are dicts with the job file's ``Blade(..)`` and
    ``Tolerance(..)`` fields (``{"length": 1200, "max_curvature": 0.01}``); omitted
    tolerances take their millimetre defaults scaled by ``units`` (``"mm"`` or ``"m"``).
    ``samples``: curvature samples of the sign test (default 2 per point, 64 to 2000, to
    answer within a millisecond; the ``Analyze`` task reads 2000 per section).
    """

class BladeEnd(TypedDict):
    position: Sequence[float]
    angle: float

class BladeShape(TypedDict):
    ends: List[BladeEnd]
    lead_in: float
    lead_out: float
    max_abs_curvature: float
    inflections: int
    elastica: Elastica

class BezierElastica(TypedDict):
    elastica: Elastica
    """The elastica with the Bézier's end points, end tangents and length."""
    length: float
    max_deviation: float
    """Largest distance between the two curves at equal arc length."""
    rms_deviation: float
    end_point_error: float
    end_angle_error: float
    relative_length_error: float
    max_curvature: float
    inflections: int
    eq11_residual: float
    """RMS residual of the affine curvature law κ = λ₂x − λ₁y + α on the Bézier, times its
    length ("Hot Blade Cuttings" eq. 11): 0 for an elastica."""
    polygon_angles_deg: Sequence[float]
    discrete_distance: float
    can_bend: bool
    """The blade extended to ``blade_length`` along this elastica stays within the limits."""
    why_not: Optional[str]
    blade: Optional[BladeShape]

def bezier_to_elastica(
    control_points: Points,
    blade_length: float,
    *,
    max_curvature: Optional[float] = None,
    max_inflections: Optional[int] = None,
    plane_tolerance: Optional[float] = None,
) -> BezierElastica:
    """A cubic Bézier design curve (4 control points, 2-D or planar 3-D) against the
    elastica with the same end points, end tangents and length ("Designing for Robotic
    Hot-Blade Cutting" §4): the piece, its deviation, the eq. (11) residual, and whether a
    blade of ``blade_length`` bends to it within ``max_curvature`` and
    ``max_inflections``."""

def use_numpy(flag: bool) -> None:
    """``False``: arrays come out as lists from now on; ``True``: as numpy arrays when numpy
    can be imported (the default; ``HOTCUT_ARRAYS=list`` in the environment starts with
    lists)."""

def arrays_are_numpy() -> bool:
    """Whether arrays come out as numpy arrays."""
