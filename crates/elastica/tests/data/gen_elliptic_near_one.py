#!/usr/bin/env python3
"""Generate elliptic_near_one.json: Jacobi functions and elliptic integrals near m = 1.

Companion of gen_elliptic_reference.py for the regime where 1 - m is tiny: 1 - m
log-uniform in [1e-16, 1e-3], |u| up to 100, and the quarter period. Half of the cases
give the parameter as m (a double), half as the modulus k (a double, m = k^2 exactly in
60-digit arithmetic, as the elastica use it). mpmath evaluates at the exact binary values.
Run: python3 gen_elliptic_near_one.py > elliptic_near_one.json
"""
import json
import random
from mpmath import mp, mpf, ellipfun, ellipk, ellipe, atan2, nint, pi, sqrt

mp.dps = 60
random.seed(20261201)


def ref(u, M):
    K, E = ellipk(M), ellipe(M)
    U = mpf(u)
    j = nint(U / (2 * K))
    r = U - 2 * K * j
    sn, cn, dn = (ellipfun(f, r, m=M) for f in ('sn', 'cn', 'dn'))
    phi = atan2(sn, cn)
    s = -1 if int(j) % 2 else 1
    return dict(sn=s * sn, cn=s * cn, dn=dn, am=j * pi + phi,
                eps=2 * j * E + ellipe(phi, M), K=K, E=E)


cases = []
for i in range(240):
    x = 10 ** random.uniform(-16, -3)
    by_k = i % 2 == 1
    if by_k:
        k = float(sqrt(1 - mpf(x)))
        if k >= 1:
            continue
        M = mpf(k) ** 2
        key = dict(k=repr(k))
    else:
        m = 1 - x
        if m >= 1:
            continue
        M = mpf(m)
        key = dict(m=repr(m))
    K = float(ellipk(M))
    us = [random.uniform(-100, 100) for _ in range(5)] + [K, -K, 3 * K, 90.0]
    for u in us:
        v = ref(u, M)
        cases.append(dict(u=repr(float(u)), **key,
                          **{n: mp.nstr(y, 30) for n, y in v.items()}))
import mpmath
print('{"generator": "gen_elliptic_near_one.py (mpmath %s, 60 digits)",' % mpmath.__version__)
print(' "cases": [')
print(',\n'.join(json.dumps(c) for c in cases))
print(']}')
