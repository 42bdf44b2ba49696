"""Per-call cost of the Python bindings against the Rust call behind them, measured in one
process on one build (issue 41: ≤ 20 µs overhead for `fit` on 200 points; `check_section`
and `bezier_to_elastica` within 1 ms for a 200-point section).

    pip install ./crates/hotcut-py numpy   # a release wheel
    python crates/hotcut-py/python/bench/overhead.py

Prints the median of 15 rounds, each the mean over many calls.
"""

import math
import statistics
import time

import hotcut
from hotcut import elastica

try:
    import numpy as np
except ImportError:  # lists only
    np = None

ROUNDS = 15


def per_call(f, n):
    times = []
    for _ in range(ROUNDS):
        t = time.perf_counter()
        for _ in range(n):
            f()
        times.append((time.perf_counter() - t) / n)
    return statistics.median(times)


def overhead(call, pts, n=100):
    """Median over ROUNDS of (Python call − Rust call), each round timing both, interleaved,
    so drifts of the machine cancel."""
    diffs, py = [], []
    for _ in range(ROUNDS * 2):
        rust = hotcut._native._rust_fit_seconds(pts, n)
        t = time.perf_counter()
        for _ in range(n):
            call()
        here = (time.perf_counter() - t) / n
        diffs.append(here - rust)
        py.append(here)
    return statistics.median(py), statistics.median(diffs)


def main():
    pts = [(3.0 * i, 40 * math.sin(3.0 * i / 100)) for i in range(200)]
    rows = []
    rust = statistics.median(hotcut._native._rust_fit_seconds(pts, 200) for _ in range(ROUNDS))
    rows.append(("fit, 200 points: Rust call", rust))
    py_list, over_list = overhead(lambda: elastica.fit(pts), pts)
    rows.append(("fit, 200 points: from Python, list of tuples", py_list))
    if np is not None:
        arr = np.array(pts)
        py_arr, over_arr = overhead(lambda: elastica.fit(arr), pts)
        rows.append(("fit, 200 points: from Python, numpy array", py_arr))
    blade = {"length": 1200, "max_curvature": 0.01}
    rows.append(("check_section, 200 points", per_call(lambda: hotcut.check_section(pts, blade=blade), 100)))
    cp = [(0, 0), (200, 60), (400, 60), (600, 0)]
    rows.append(("bezier_to_elastica", per_call(lambda: hotcut.bezier_to_elastica(cp, 800), 200)))
    e = elastica.fit(pts)
    rows.append(("Elastica.sample(200)", per_call(lambda: e.sample(200), 2000)))
    rows.append(("overhead of fit, list (median of Python − Rust)", over_list))
    if np is not None:
        rows.append(("overhead of fit, numpy (median of Python − Rust)", over_arr))
    width = max(len(r[0]) for r in rows)
    for name, t in rows:
        print(f"{name:<{width}}  {t * 1e6:9.1f} µs")


if __name__ == "__main__":
    main()
