"""Exact elastica points, computed with mpmath (30 digits) from the closed forms of the
papers, independently of hotcut's own evaluation:

- inflectional    ζ(σ) = (2E(σ|m) − σ, 2k(1 − cn(σ|m))),
- noninflectional γ(σ) = ((1 − 2/m)σ + (2/k)E(σ/k|m), (2/k)(1 − dn(σ/k|m))),

with m = k², E(u|m) Jacobi's epsilon function, and p(t) = S·R(φ)·f(s0 + l·t) + (x0, y0).
"""

import mpmath as mp

mp.mp.dps = 30


def _epsilon(u, m):
    """E(u|m) = E(am(u)|m), the amplitude unwrapped over the periods."""
    sn, cn = mp.ellipfun("sn", u, m=m), mp.ellipfun("cn", u, m=m)
    am = mp.atan2(sn, cn) + 2 * mp.pi * mp.nint(u / (4 * mp.ellipk(m)))
    return mp.ellipe(am, m)


def unit(family, k, sigma):
    k, sigma = mp.mpf(k), mp.mpf(sigma)
    m = k * k
    if family == "inflectional":
        cn = mp.ellipfun("cn", sigma, m=m)
        return 2 * _epsilon(sigma, m) - sigma, 2 * k * (1 - cn)
    u = sigma / k
    dn = mp.ellipfun("dn", u, m=m)
    return (1 - 2 / m) * sigma + (2 / k) * _epsilon(u, m), (2 / k) * (1 - dn)


def points(family, k, s0, l, S, phi, x0, y0, n):
    """n points at equal arc length, and their arc lengths."""
    c, s = mp.cos(phi), mp.sin(phi)
    out, arc = [], []
    for i in range(n):
        t = mp.mpf(i) / (n - 1)
        x, y = unit(family, k, mp.mpf(s0) + mp.mpf(l) * t)
        out.append((float(S * (c * x - s * y) + x0), float(S * (s * x + c * y) + y0)))
        arc.append(float(abs(mp.mpf(l)) * S * t))
    return out, arc
