import numpy as np
from collections import defaultdict

def write_off(path, V, F):
    with open(path, 'w') as f:
        f.write('OFF\n%d %d 0\n' % (len(V), len(F)))
        for v in V:
            f.write('%.9g %.9g %.9g\n' % tuple(v))
        for t in F:
            f.write('3 %d %d %d\n' % tuple(t))

def read_off(path):
    toks = open(path).read().split()
    assert toks[0] == 'OFF'
    nv, nf = int(toks[1]), int(toks[2]); p = 4
    V = np.array(toks[p:p+3*nv], float).reshape(nv, 3); p += 3*nv
    F = np.array(toks[p:p+4*nf], int).reshape(nf, 4)
    assert (F[:, 0] == 3).all()
    return V, F[:, 1:]

def compact(V, F):
    used = np.unique(F)
    remap = -np.ones(len(V), int); remap[used] = np.arange(len(used))
    return V[used], remap[F]

def signed_volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return np.einsum('ij,ij->i', a, np.cross(b, c)).sum() / 6.0

def check(V, F, fix_orientation=True):
    """returns (V,F,info) ; raises AssertionError on failure"""
    F = np.asarray(F, int); V = np.asarray(V, float)
    V, F = compact(V, F)
    nv, nf = len(V), len(F)
    # degenerate
    assert (F[:, 0] != F[:, 1]).all() and (F[:, 1] != F[:, 2]).all() and (F[:, 0] != F[:, 2]).all(), 'repeated vertex in face'
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    mean_edge = np.mean(np.linalg.norm(b - a, axis=1))
    assert area.min() > 1e-8 * mean_edge**2, 'degenerate triangle, min area %g' % area.min()
    # duplicate vertex positions
    _, cnt = np.unique(np.round(V, 9), axis=0, return_counts=True)
    assert cnt.max() == 1, 'coincident vertices'
    # duplicate faces
    assert len(np.unique(np.sort(F, 1), axis=0)) == nf, 'duplicate faces'
    # directed edges
    de = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    dkeys = de[:, 0] * nv + de[:, 1]
    assert len(np.unique(dkeys)) == len(dkeys), 'directed edge repeated (non-manifold or inconsistent orientation)'
    rkeys = de[:, 1] * nv + de[:, 0]
    assert np.isin(rkeys, dkeys).all(), 'boundary edge / unmatched edge'
    E = len(dkeys) // 2
    # connected components via union-find over faces using vertices
    parent = np.arange(nv)
    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]; x = parent[x]
        return x
    for u, v in de:
        ru, rv = find(u), find(v)
        if ru != rv: parent[ru] = rv
    roots = set(find(i) for i in range(nv))
    assert len(roots) == 1, '%d components' % len(roots)
    # vertex manifoldness: link of each vertex a single cycle
    nxt = defaultdict(dict)
    for t in F:
        for i in range(3):
            v0, v1, v2 = t[i], t[(i+1) % 3], t[(i+2) % 3]
            nxt[v0][v1] = v2
    for v, d in nxt.items():
        start = next(iter(d)); x = start; n = 0
        while True:
            x = d[x]; n += 1
            if x == start: break
            assert n <= len(d)
        assert n == len(d), 'non-manifold vertex %d' % v
    vol = signed_volume(V, F)
    if vol < 0:
        assert fix_orientation, 'negative volume'
        F = F[:, ::-1].copy(); vol = -vol
    chi = nv - E + nf
    assert chi % 2 == 0
    g = (2 - chi) // 2
    return V, F, dict(V=nv, E=E, F=nf, chi=chi, genus=g, volume=vol, min_area=area.min(),
                      bbox=(V.min(0).round(3).tolist(), V.max(0).round(3).tolist()))

def self_intersections(V, F, max_report=5):
    """brute-ish triangle-triangle test using vtk OBB tree per candidate; use numpy grid bucketing"""
    import itertools
    tri = V[F]
    lo, hi = tri.min(1), tri.max(1)
    cell = np.mean(hi - lo) * 2
    buckets = defaultdict(list)
    for i in range(len(F)):
        a = np.floor(lo[i] / cell).astype(int); b = np.floor(hi[i] / cell).astype(int)
        for x in range(a[0], b[0]+1):
            for y in range(a[1], b[1]+1):
                for z in range(a[2], b[2]+1):
                    buckets[(x, y, z)].append(i)
    pairs = set()
    for lst in buckets.values():
        for i, j in itertools.combinations(lst, 2):
            if set(F[i]) & set(F[j]): continue
            if (lo[i] > hi[j]).any() or (lo[j] > hi[i]).any(): continue
            pairs.add((min(i, j), max(i, j)))
    bad = []
    for i, j in pairs:
        if tri_tri(tri[i], tri[j]):
            bad.append((i, j))
    return bad

def _seg_tri(p, q, t):
    # segment p-q intersects triangle t (strict-ish)
    e1 = t[1] - t[0]; e2 = t[2] - t[0]; d = q - p
    h = np.cross(d, e2); a = e1 @ h
    if abs(a) < 1e-14: return False
    f = 1.0 / a; s = p - t[0]; u = f * (s @ h)
    if u < 0 or u > 1: return False
    qq = np.cross(s, e1); v = f * (d @ qq)
    if v < 0 or u + v > 1: return False
    tt = f * (e2 @ qq)
    return 0 <= tt <= 1

def tri_tri(A, B):
    for k in range(3):
        if _seg_tri(A[k], A[(k+1) % 3], B): return True
        if _seg_tri(B[k], B[(k+1) % 3], A): return True
    return False

def orient_consistently(F):
    """BFS over faces so that each shared edge is traversed in opposite directions."""
    F = np.array(F, int).copy()
    edge_faces = defaultdict(list)
    for fi, t in enumerate(F):
        for i in range(3):
            a, b = t[i], t[(i+1) % 3]
            edge_faces[(min(a, b), max(a, b))].append(fi)
    seen = np.zeros(len(F), bool)
    from collections import deque
    for s in range(len(F)):
        if seen[s]: continue
        seen[s] = True; dq = deque([s])
        while dq:
            fi = dq.popleft(); t = F[fi]
            for i in range(3):
                a, b = t[i], t[(i+1) % 3]
                for fj in edge_faces[(min(a, b), max(a, b))]:
                    if fj == fi or seen[fj]: continue
                    u = F[fj]
                    # neighbour must contain b->a
                    same = any(u[k] == a and u[(k+1) % 3] == b for k in range(3))
                    if same: F[fj] = u[::-1]
                    seen[fj] = True; dq.append(fj)
    return F

def gmsh_surface_mesh(build, target=(3000, 8000), h0=0.5, name='m', extra_opts=None):
    """build(): creates OCC geometry and synchronizes. Returns V,F."""
    import gmsh
    goal = 0.5 * (target[0] + target[1])
    h = h0
    for it in range(8):
        gmsh.initialize()
        gmsh.option.setNumber('General.Terminal', 0)
        gmsh.model.add(name)
        build()
        gmsh.option.setNumber('Mesh.MeshSizeMin', h * 0.999)
        gmsh.option.setNumber('Mesh.MeshSizeMax', h)
        gmsh.option.setNumber('Mesh.MeshSizeFromCurvature', 0)
        gmsh.option.setNumber('Mesh.Algorithm', 6)
        if extra_opts:
            for k, v in extra_opts.items(): gmsh.option.setNumber(k, v)
        gmsh.model.mesh.generate(2)
        gmsh.model.mesh.removeDuplicateNodes()
        tags, coords, _ = gmsh.model.mesh.getNodes()
        coords = coords.reshape(-1, 3)
        idx = {int(t): i for i, t in enumerate(tags)}
        tris = []
        for dim, tag in gmsh.model.getEntities(2):
            etypes, etags, enodes = gmsh.model.mesh.getElements(dim, tag)
            for et, en in zip(etypes, enodes):
                assert et == 2, 'non-triangle element type %d' % et
                tris.append(np.array(en, int).reshape(-1, 3))
        gmsh.finalize()
        T = np.concatenate(tris)
        F = np.vectorize(idx.get)(T)
        V = coords
        n = len(F)
        print('  h=%.4f -> %d tris' % (h, n))
        if target[0] <= n <= target[1]:
            V, F = compact(V, F)
            return V, orient_consistently(F)
        h *= (n / goal) ** 0.5
    raise RuntimeError('could not hit target')
