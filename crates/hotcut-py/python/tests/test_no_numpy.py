"""Without numpy (as in Rhino 8's Python), and with `use_numpy(False)`, numbers come out as
lists, equal to the numpy arrays."""

import subprocess
import sys
import textwrap

import numpy as np

import hotcut
from hotcut import elastica


def test_lists_when_numpy_is_missing():
    code = textwrap.dedent(
        """
        import sys
        sys.modules["numpy"] = None  # import numpy now fails, as on a Python without it
        import hotcut
        from hotcut import elastica
        assert not hotcut.arrays_are_numpy()
        e = elastica.fit([(0, 0), (1, 0.5), (2, 0.6), (3, 0.5), (4, 0)])
        assert type(e.start) is list and type(e.sample(3)) is list and type(e.sample(3)[0]) is list
        c = hotcut.check_section([(x, (x / 9.0) ** 2) for x in range(40)], blade={"length": 100, "max_curvature": 1})
        assert type(c["max_abs_curvature"]["point"]) is list
        print(repr(e.sample(3)))
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    listed = eval(out.stdout)
    e = elastica.fit([(0, 0), (1, 0.5), (2, 0.6), (3, 0.5), (4, 0)])
    assert np.asarray(e.sample(3)).tolist() == listed


def test_use_numpy_false_gives_lists():
    e = elastica.fit([(0, 0), (1, 0.5), (2, 0.6), (3, 0.5), (4, 0)])
    arr = e.sample(5)
    assert isinstance(arr, np.ndarray) == hotcut.arrays_are_numpy()
    hotcut.use_numpy(False)
    try:
        lst = e.sample(5)
        assert type(lst) is list and np.asarray(arr).tolist() == lst
    finally:
        hotcut.use_numpy(True)
