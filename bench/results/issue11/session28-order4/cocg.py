#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 28: Jacobi-preconditioned COCG iterations (to 1e-10) of the complex shifted
systems (D + z G) the L^3 and L^4 steps need (power_solve.h), against the L^2 complex solve, on
the unnormalized umbrella (measurement aid, not part of any build).

    cocg.py MESH.ply A1,A2,...

Needs numpy and scipy (Debian: python3-scipy)."""
import sys, numpy as np, scipy.sparse as sp
import os
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply
x,f=read_ply(sys.argv[1]); n=len(x)
e=np.unique(np.sort(np.r_[f[:,[0,1]],f[:,[1,2]],f[:,[2,0]]],axis=1),axis=0)
A=sp.csr_matrix((np.ones(2*len(e)),(np.r_[e[:,0],e[:,1]],np.r_[e[:,1],e[:,0]])),shape=(n,n))
d=np.asarray(A.sum(1)).ravel()
G=(sp.diags(d)-A).tocsr()   # symmetric: M=D (valence), generalized eigen G v = g D v, g in [0,2]
def cocg(z, b, tol=1e-10):
    S=(sp.diags(d)+z*G).tocsr(); dinv=1/S.diagonal()
    xk=np.zeros_like(b,dtype=complex); r=b.astype(complex); zz=dinv*r; p=zz.copy(); rho=(r*zz).sum()
    nb=np.linalg.norm(b)
    for k in range(1,5000):
        q=S@p; al=rho/(p*q).sum(); xk+=al*p; r-=al*q
        if np.linalg.norm(r)<tol*nb: return k
        zz=dinv*r; rn=(r*zz).sum(); p=zz+rn/rho*p; rho=rn
    return -1
b=d*x[:,0]
for a in [float(v) for v in sys.argv[2].split(",")]:
    c4=a**0.25; print("a=%g L4: 45deg %d 135deg %d" % (a, cocg(c4*np.exp(1j*np.pi/4),b), cocg(c4*np.exp(3j*np.pi/4),b)))
    c2=np.sqrt(a); c3=a**(1/3)
    print('a=%g  first-order(c=a) %d  first-order(c=sqrt a) %d  L2 complex(i sqrt a) %d  L3 real(c) %d  L3 complex(c e^2pi i/3) %d' % (a,
      cocg(a,b), cocg(c2,b), cocg(1j*c2,b), cocg(c3,b), cocg(c3*np.exp(2j*np.pi/3),b)))
