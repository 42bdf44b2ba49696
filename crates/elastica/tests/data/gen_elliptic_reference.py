#!/usr/bin/env python3
"""Generate elliptic_reference.json: Jacobi functions and elliptic integrals at 60 digits.

Independent reference for tests/elliptic_reference.rs. Uses mpmath (ellipfun, ellipk,
ellipe), evaluating in 60-digit arithmetic at the exact binary values of the f64 inputs.
Run: python3 gen_elliptic_reference.py > elliptic_reference.json
"""
import json
import random
from mpmath import mp, mpf, ellipfun, ellipk, ellipe, atan2, nint, pi, tanh, cosh, asinh, sinh, atan

mp.dps = 60
random.seed(20261122)

ms = [0.0, 1e-300, 1e-16, 1e-12, 1e-9, 1e-6, 1e-3, 0.01, 0.1, 0.25, 0.3, 0.5, 0.7, 0.8,
      0.9, 0.99, 0.999, 0.999999, 1 - 1e-8, 1 - 1e-10, 1 - 1e-12, 1 - 1e-14,
      1 - 2.0 ** -52, 1 - 2.0 ** -53, 1.0]
ms += [random.random() for _ in range(10)]
ms += [1 - 10 ** random.uniform(-15, -1) for _ in range(6)]


def ref(u, m):
    U, M = mpf(u), mpf(m)
    if M == 1:
        sn, cn, dn = tanh(U), 1 / cosh(U), 1 / cosh(U)
        return dict(sn=sn, cn=cn, dn=dn, am=atan(sinh(U)), eps=tanh(U), K=None, E=mpf(1))
    K, E = ellipk(M), ellipe(M)
    j = nint(U / (2 * K))
    r = U - 2 * K * j
    sn, cn, dn = (ellipfun(f, r, m=M) for f in ('sn', 'cn', 'dn'))
    phi = atan2(sn, cn)
    s = -1 if int(j) % 2 else 1
    return dict(sn=s * sn, cn=s * cn, dn=dn, am=j * pi + phi,
                eps=2 * j * E + ellipe(phi, M), K=K, E=E)


cases = []
for m in ms:
    K = float(ellipk(mpf(m))) if m < 1 else 30.0
    us = [0.0, 1e-8, 0.3, -0.7, 1.0, 2.5, K / 2, K, K * (1 - 1e-9), K * (1 + 1e-9), 2 * K, 3 * K,
          -K, 4 * K + 0.1, 1000.0, -1000.0, 999.9, 123.456]
    us += [random.uniform(-1000, 1000) for _ in range(6)]
    us += [random.uniform(-3 * K, 3 * K) for _ in range(6)]
    for u in us:
        if abs(u) > 1000:
            continue
        v = ref(u, m)
        cases.append(dict(u=repr(float(u)), m=repr(float(m)),
                          **{k: (None if x is None else mp.nstr(x, 30)) for k, x in v.items()}))
import mpmath
print('{"generator": "gen_elliptic_reference.py (mpmath %s, 60 digits)",' % mpmath.__version__)
print(' "cases": [')
print(',\n'.join(json.dumps(c) for c in cases))
print(']}')
