"""hotcut from Python: run hotcut jobs, fit and evaluate Euler elastica, and check the
hot blade's production constraints while a design is dragged.

The numbers all come from hotcut's Rust crates (the same as the ``hotcut`` command line
tool's); this package is a thin layer over them. Arrays come out as numpy arrays when numpy
is installed, else as lists (Rhino's Python may lack numpy); ``use_numpy(False)`` asks for
lists. See ``__init__.pyi`` for the types and the README's "From Python" for examples.
"""

import atexit

from . import _native
from ._native import (
    HotcutError,
    JobError,
    RunError,
    __version__,
    arrays_are_numpy,
    bezier_to_elastica,
    check_section,
    run,
    use_numpy,
    validate,
)
from . import elastica

# a run stopped by Ctrl-C may still be unwinding when the script ends: its temporary
# folder goes with it
atexit.register(_native._remove_temporaries)

__all__ = [
    "HotcutError",
    "JobError",
    "RunError",
    "__version__",
    "arrays_are_numpy",
    "bezier_to_elastica",
    "check_section",
    "elastica",
    "run",
    "use_numpy",
    "validate",
]
