# SPDX-License-Identifier: GPL-3.0-or-later
# A box with nx x ny x nz cells: a thin plate when sz is small and nz = 1. argv: nx ny nz sx sy sz out
import sys
N=[int(x) for x in sys.argv[1:4]]; s=[float(x) for x in sys.argv[4:7]]; out=sys.argv[7]
idx={}; P=[]; T=[]
def vert(l):
    l=tuple(l)
    if l not in idx: idx[l]=len(P); P.append(tuple(s[k]*l[k]/N[k] for k in range(3)))
    return idx[l]
for a in range(3):
    for side in range(2):
        b,c=(a+1)%3,(a+2)%3
        if side==0: b,c=c,b
        for i in range(N[b]):
            for j in range(N[c]):
                def lat(di,dj):
                    l=[0,0,0]; l[a]=side*N[a]; l[b]=i+di; l[c]=j+dj; return vert(l)
                p00,p10,p11,p01=lat(0,0),lat(1,0),lat(1,1),lat(0,1)
                T.append((p00,p10,p11)); T.append((p00,p11,p01))
with open(out,'w') as f:
    f.write('ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'%(len(P),len(T)))
    for p in P: f.write('%.17g %.17g %.17g\n'%p)
    for t in T: f.write('3 %d %d %d\n'%t)
