"""Euler elastica in closed form: ``fit`` points of a plane, ``between`` two end points with
their tangents and a length, the ``Elastica`` they give, and Jacobi's elliptic functions
(``Elliptic``)."""

from ._native import Elastica, Elliptic, between, fit

__all__ = ["Elastica", "Elliptic", "between", "fit"]
