import os, sys, glob, numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import *
# optional mesh names (with or without .off) restrict the check, e.g. to newly added meshes
sel = set(a[:-4] if a.endswith('.off') else a for a in sys.argv[1:])
for p in sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '*.off'))):
    if sel and os.path.basename(p)[:-4] not in sel: continue
    V, F = read_off(p)
    V2, F2, info = check(V, F, fix_orientation=False)
    assert len(V2) == len(V)
    bad = self_intersections(V, F)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    def ang(p, q, r):
        u, v = q - p, r - p
        return np.degrees(np.arccos(np.clip(np.einsum('ij,ij->i', u, v) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1), -1, 1)))
    mina = np.min([ang(a, b, c), ang(b, c, a), ang(c, a, b)])
    print('%-28s V=%5d F=%5d genus=%d vol=%8.3f minangle=%5.1f selfint=%d' % (os.path.basename(p), info['V'], info['F'], info['genus'], info['volume'], mina, len(bad)))
