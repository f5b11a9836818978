import os, sys, math, numpy as np, vtk
from vtk.util import numpy_support as ns
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import *

def smin(a, b, k):
    h = np.clip(0.5 + 0.5 * (b - a) / k, 0, 1)
    return b * (1 - h) + a * h - k * h * (1 - h)

def smax(a, b, k):
    return -smin(-a, -b, k)

def torus(x, y, z, cx, R, r):
    q = np.sqrt((x - cx) ** 2 + y ** 2) - R
    return np.sqrt(q ** 2 + z ** 2) - r

def polydata_to_np(pd):
    V = ns.vtk_to_numpy(pd.GetPoints().GetData()).astype(float)
    c = ns.vtk_to_numpy(pd.GetPolys().GetData()).reshape(-1, 4)
    assert (c[:, 0] == 3).all()
    return V, c[:, 1:].astype(int)

def implicit_mesh(f, lo, hi, n=80, target=5500, smooth_iter=15, passband=0.1):
    lo = np.array(lo, float); hi = np.array(hi, float)
    xs = [np.linspace(lo[i], hi[i], n) for i in range(3)]
    X, Y, Z = np.meshgrid(*xs, indexing='ij')
    vals = f(X, Y, Z).astype(np.float64)
    img = vtk.vtkImageData()
    img.SetDimensions(n, n, n)
    img.SetOrigin(*lo)
    img.SetSpacing(*((hi - lo) / (n - 1)))
    arr = ns.numpy_to_vtk(vals.ravel(order='F'), deep=True)  # x fastest
    arr.SetName('f')
    img.GetPointData().SetScalars(arr)
    mc = vtk.vtkFlyingEdges3D(); mc.SetInputData(img); mc.SetValue(0, 0.0)
    mc.ComputeNormalsOff(); mc.ComputeGradientsOff()
    mc.Update()
    conn = vtk.vtkPolyDataConnectivityFilter(); conn.SetInputConnection(mc.GetOutputPort())
    conn.SetExtractionModeToLargestRegion()
    tri = vtk.vtkTriangleFilter(); tri.SetInputConnection(conn.GetOutputPort())
    cl = vtk.vtkCleanPolyData(); cl.SetInputConnection(tri.GetOutputPort()); cl.Update()
    n0 = cl.GetOutput().GetNumberOfPolys()
    sm = vtk.vtkWindowedSincPolyDataFilter(); sm.SetInputConnection(cl.GetOutputPort())
    sm.SetNumberOfIterations(smooth_iter); sm.SetPassBand(passband)
    sm.NonManifoldSmoothingOn(); sm.NormalizeCoordinatesOn(); sm.BoundarySmoothingOff(); sm.FeatureEdgeSmoothingOff()
    dec = vtk.vtkQuadricDecimation(); dec.SetInputConnection(sm.GetOutputPort())
    dec.SetTargetReduction(1.0 - target / n0)
    dec.VolumePreservationOn()
    conn2 = vtk.vtkPolyDataConnectivityFilter(); conn2.SetInputConnection(dec.GetOutputPort())
    conn2.SetExtractionModeToLargestRegion()
    tri2 = vtk.vtkTriangleFilter(); tri2.SetInputConnection(conn2.GetOutputPort())
    cl2 = vtk.vtkCleanPolyData(); cl2.SetInputConnection(tri2.GetOutputPort()); cl2.Update()
    V, F = polydata_to_np(cl2.GetOutput())
    print('  MC %d tris -> %d after decimation' % (n0, len(F)))
    return V, F

# ---------------- shapes ----------------
def blobby(X, Y, Z):
    s = 0.0
    blobs = [((0, 0, 0), 1.0, 1.0)]
    dirs = [(1, 0.2, -0.3), (-1, 0.3, -0.3), (0.2, 1, -0.2), (-0.1, -0.9, 0.6)]
    for d in dirs:
        d = np.array(d, float); d /= np.linalg.norm(d)
        for k, (t, rad) in enumerate([(0.9, 0.55), (1.4, 0.45), (1.85, 0.4), (2.2, 0.42)]):
            blobs.append((tuple(d * t + np.array([0, 0, 0.15 * k * k * 0.3])), rad, 0.9))
    for c, rad, w in blobs:
        s = s + w * np.exp(-((X - c[0]) ** 2 + (Y - c[1]) ** 2 + (Z - c[2]) ** 2) / rad ** 2)
    return 0.5 - s

def pretzel2(X, Y, Z):
    return smin(torus(X, Y, Z, -1.1, 1.0, 0.35), torus(X, Y, Z, 1.1, 1.0, 0.35), 0.25)

def genus3(X, Y, Z):
    a = torus(X, Y, Z, -2.2, 1.0, 0.33)
    b = torus(X, Y, Z, 0.0, 1.0, 0.33)
    c = torus(X, Y, Z, 2.2, 1.0, 0.33)
    return smin(smin(a, b, 0.25), c, 0.25)

def twisted_torus(X, Y, Z):
    R = 1.6
    th = np.arctan2(Y, X)
    rho = np.sqrt(X ** 2 + Y ** 2)
    q1 = rho - R; q2 = Z
    a = 0.25 * (1.0 + 0.45 * np.sin(3 * th))   # radius varies along ring
    phi = 1.5 * th                              # elliptic section twisting 3*pi over the ring
    u = np.cos(phi) * q1 + np.sin(phi) * q2
    v = -np.sin(phi) * q1 + np.cos(phi) * q2
    ea, eb = 1.6 * a, 0.8 * a
    return (np.sqrt((u / ea) ** 2 + (v / eb) ** 2) - 1.0) * np.minimum(ea, eb)

def banana(X, Y, Z):
    R = 3.0; pmax = math.radians(65)
    phi = np.arctan2(Y, X)
    pc = np.clip(phi, -pmax, pmax)
    cx, cy = R * np.cos(pc), R * np.sin(pc)
    d = np.sqrt((X - cx) ** 2 + (Y - cy) ** 2 + Z ** 2)
    r = 0.7 * (1 - 0.45 * (pc / pmax) ** 2)
    return d - r

def holed_slab(X, Y, Z, half, rr, centres, hr, k=0.25):
    """Rounded box (half-extents half, edge radius rr) minus vertical holes of radius hr, smooth-max cut."""
    b = np.array(half, float)
    q = np.stack([np.abs(X), np.abs(Y), np.abs(Z)]) - (b - rr)[:, None, None, None]
    f = np.linalg.norm(np.maximum(q, 0), axis=0) + np.minimum(q.max(0), 0) - rr
    for cx, cy in centres:
        cyl = np.sqrt((X - cx) ** 2 + (Y - cy) ** 2) - hr
        f = smax(f, -cyl, k)
    return f

def plate4(X, Y, Z):
    # rounded box 6 x 6 x 1 (edge radius 0.4)
    return holed_slab(X, Y, Z, (3.0, 3.0, 0.5), 0.4, [(-1.4, -1.4), (1.4, -1.4), (-1.4, 1.4), (1.4, 1.4)], 0.7)

# The two below were added in Dec 2026 to cover genus 6 and a 2D (not in-a-row) torus arrangement.
def plate6(X, Y, Z):
    # rounded box 8 x 5.5 x 1.1, holes 3 x 2; rims stay >= 0.75 wide
    return holed_slab(X, Y, Z, (4.0, 2.75, 0.55), 0.4, [(x, y) for x in (-2.6, 0.0, 2.6) for y in (-1.3, 1.3)], 0.65)

QUAD_D = 1.85   # centre spacing of the 2 x 2 tori

def quad_torus(X, Y, Z):
    # With the row spacing of genus3 (2.2) the four blends enclose an empty centre, a 5th handle
    # (genus 5). The centre fills at spacing <= 2.0; 1.85 makes it about as thick as a tube
    # (0.66) while each torus keeps a hole of radius >= 0.5, so the genus is 4.
    c = QUAD_D / 2
    f = None
    for cx, cy in [(-c, -c), (c, -c), (c, c), (-c, c)]:
        t = torus(X, Y - cy, Z, cx, 1.0, 0.33)
        f = t if f is None else smin(f, t, 0.25)
    return f

SHAPES = [
    ('org_blobby_4limbs', blobby, (-3.2, -3.2, -2.5), (3.2, 3.2, 3.0), 'metaballs: central blob + 4 limb-like chains of Gaussian blobs'),
    ('org_pretzel_genus2', pretzel2, (-2.7, -1.6, -0.6), (2.7, 1.6, 0.6), 'smooth union (smin k=.25) of two tori R=1 r=.35'),
    ('org_triple_torus_genus3', genus3, (-3.8, -1.6, -0.6), (3.8, 1.6, 0.6), 'smooth union of three tori in a row'),
    ('org_twisted_torus', twisted_torus, (-2.4, -2.4, -0.7), (2.4, 2.4, 0.7), 'torus R=1.6 with elliptic twisting section and minor radius varying sin(3t)'),
    ('org_banana', banana, (0.5, -3.5, -1.0), (4.0, 3.5, 1.0), 'tapered capsule swept along a 130 deg circular arc (R=3)'),
    ('org_plate_4holes', plate4, (-3.3, -3.3, -0.8), (3.3, 3.3, 0.8), 'rounded slab 6x6x1 with 4 holes, smooth-max subtraction'),
    ('org_plate_6holes', plate6, (-4.3, -3.05, -0.85), (4.3, 3.05, 0.85), 'rounded slab 8x5.5x1.1 with 6 holes (3x2), smooth-max subtraction'),
    ('org_quad_torus_genus4', quad_torus, (-2.6, -2.6, -0.6), (2.6, 2.6, 0.6), 'four tori R=1 r=.33 in a 2x2 square (spacing 1.85), smooth union'),
]

if __name__ == '__main__':
    sel = sys.argv[1:]
    for name, fn, lo, hi, desc in SHAPES:
        if sel and name not in sel: continue
        print(name)
        try:
            V, F = implicit_mesh(fn, lo, hi)
            V, F, info = check(V, F)
            write_off(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '%s.off') % name, V, F)
            print('  OK', info)
        except Exception as e:
            import traceback; traceback.print_exc()
            print('  FAIL', name, e)
