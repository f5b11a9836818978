import os, sys, math, numpy as np, gmsh
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import *
occ = lambda: gmsh.model.occ
PI = math.pi

def try_fillet(vol, curves, r):
    try:
        out = occ().fillet([vol], curves, [r], True)
        return out[0][1] if out else vol
    except Exception as e:
        print('  fillet failed:', e); return vol

def edges_of(vol):
    surfs = gmsh.model.getBoundary([(3, vol)], combined=False, oriented=False)
    cs = gmsh.model.getBoundary(surfs, combined=False, oriented=False)
    return sorted(set(abs(c) for d, c in cs if d == 1))

def circle_edges_where(vol, keep):
    """The circles among vol's edges whose bounding box (xmin, ymin, zmin, xmax, ymax, zmax) keep() accepts."""
    return [c for c in edges_of(vol) if gmsh.model.getType(1, c) == 'Circle' and keep(gmsh.model.getBoundingBox(1, c))]

def line_edges_where(vol, keep):
    """The straight lines among vol's edges whose bounding box keep() accepts."""
    return [c for c in edges_of(vol) if gmsh.model.getType(1, c) == 'Line' and keep(gmsh.model.getBoundingBox(1, c))]

def circ_edges(vol):
    occ().synchronize()
    return [c for c in edges_of(vol) if gmsh.model.getType(1, c) == 'Circle']

def flange():
    o = occ()
    d = o.addCylinder(0, 0, 0, 0, 0, 1, 5)
    holes = [(3, o.addCylinder(0, 0, -1, 0, 0, 3, 1.5))]
    for k in range(4):
        a = k * PI / 2 + PI / 4
        holes.append((3, o.addCylinder(3.4 * math.cos(a), 3.4 * math.sin(a), -1, 0, 0, 3, 0.5)))
    r, _ = o.cut([(3, d)], holes)
    o.synchronize()
    v = r[0][1]
    # fillet the outer rim edges (circles of radius 5)
    try_fillet(v, circle_edges_where(v, lambda bb: bb[3] - bb[0] > 9), 0.2)
    o.synchronize()

def lbracket():
    o = occ()
    a = o.addBox(0, 0, 0, 6, 4, 1)
    b = o.addBox(0, 0, 0, 1, 4, 6)
    r, _ = o.fuse([(3, a)], [(3, b)])
    h1 = o.addCylinder(3.8, 2, -1, 0, 0, 3, 0.8)
    h2 = o.addCylinder(-1, 2, 3.8, 3, 0, 0, 0.8)
    r, _ = o.cut(r, [(3, h1), (3, h2)])
    o.synchronize()
    v = r[0][1]
    # fillet the inner corner line x=1,z=1 (a line along y)
    inner = []
    for c in edges_of(v):
        bb = gmsh.model.getBoundingBox(1, c)
        if abs(bb[0] - 1) < 1e-6 and abs(bb[3] - 1) < 1e-6 and abs(bb[2] - 1) < 1e-6 and abs(bb[5] - 1) < 1e-6:
            inner.append(c)
    try_fillet(v, inner, 0.5)
    o.synchronize()

def mug():
    o = occ()
    c = o.addCylinder(0, 0, 0, 0, 0, 5, 2)
    # partial torus (handle) whose open ends are buried inside the cylinder
    t = o.addTorus(0, 0, 0, 1.3, 0.3, -1, 1.5 * PI)
    o.rotate([(3, t)], 0, 0, 0, 0, 0, 1, -0.75 * PI)   # gap centred on -x
    o.rotate([(3, t)], 0, 0, 0, 1, 0, 0, PI / 2)
    o.translate([(3, t)], 2.5, 0, 2.5)
    r, _ = o.fuse([(3, c)], [(3, t)])
    o.synchronize()

def tee():
    o = occ()
    a = o.addCylinder(-4, 0, 0, 8, 0, 0, 1.0)
    b = o.addCylinder(0, 0, 0, 0, 0, 4, 0.7)
    r, _ = o.fuse([(3, a)], [(3, b)])
    o.synchronize()

def elbow():
    o = occ()
    d1 = o.addDisk(3, 0, 0, 1.0, 1.0)
    d2 = o.addDisk(3, 0, 0, 0.6, 0.6)
    ann, _ = o.cut([(2, d1)], [(2, d2)])
    o.rotate(ann, 0, 0, 0, 1, 0, 0, PI / 2)
    o.revolve(ann, 0, 0, 0, 0, 0, 1, PI / 2)
    o.remove(ann)
    o.synchronize()

def box3holes():
    o = occ()
    b = o.addBox(0, 0, 0, 8, 3, 2)
    hs = [(3, o.addCylinder(x, 1.5, -1, 0, 0, 4, 0.6)) for x in (2, 4, 6)]
    r, _ = o.cut([(3, b)], hs)
    o.synchronize()
    v = r[0][1]
    try_fillet(v, line_edges_where(v, lambda bb: bb[5] - bb[2] > 1.5), 0.4)
    o.synchronize()

def cross_holes():
    o = occ()
    b = o.addBox(-2, -2, -2, 4, 4, 4)
    hx = o.addCylinder(-3, 0, 0, 6, 0, 0, 0.8)
    hy = o.addCylinder(0, -3, 0.2, 0, 6, 0, 0.6)
    r, _ = o.cut([(3, b)], [(3, hx), (3, hy)])
    o.synchronize()

def shaft():
    o = occ()
    a = o.addCylinder(0, 0, 0, 0, 0, 3, 2.0)
    b = o.addCylinder(0, 0, 3, 0, 0, 3, 1.4)
    c = o.addCylinder(0, 0, 6, 0, 0, 3, 0.9)
    r, _ = o.fuse([(3, a)], [(3, b), (3, c)])
    o.synchronize()
    v = r[0][1]
    # fillet the two outer end rims
    try_fillet(v, circle_edges_where(v, lambda bb: abs(bb[2]) < 1e-6 or abs(bb[2] - 9) < 1e-6), 0.25)
    o.synchronize()

def plate6holes():
    # added Dec 2026 to reach genus 6 (one handle per hole)
    o = occ()
    b = o.addBox(0, 0, 0, 9, 6, 1)
    hs = [(3, o.addCylinder(x, y, -1, 0, 0, 3, 0.7)) for x in (1.5, 4.5, 7.5) for y in (1.5, 4.5)]
    r, _ = o.cut([(3, b)], hs)
    o.synchronize()
    v = r[0][1]
    # pick the 4 box corners by position: the holes' seam lines are vertical Lines too
    corners = line_edges_where(v, lambda bb: bb[5] - bb[2] > 0.9 and min(abs(bb[0]), abs(bb[0] - 9)) < 1e-6 and
                               min(abs(bb[1]), abs(bb[1] - 6)) < 1e-6)
    assert len(corners) == 4, corners
    try_fillet(v, corners, 0.5)
    o.synchronize()

def flanged_bushing():
    # added Dec 2026 (turned parts): tube r 1.0..1.5, length 4 along z, flange r=2.6 t=0.5 at z=0
    o = occ()
    t = o.addCylinder(0, 0, 0, 0, 0, 4, 1.5)
    f = o.addCylinder(0, 0, 0, 0, 0, 0.5, 2.6)
    r, _ = o.fuse([(3, t)], [(3, f)])
    bore = o.addCylinder(0, 0, -1, 0, 0, 6, 1.0)
    r, _ = o.cut(r, [(3, bore)])
    o.synchronize()
    v = r[0][1]
    # the concave tube-flange junction: the circle r=1.5 at z=0.5
    junction = circle_edges_where(v, lambda bb: abs(bb[3] - bb[0] - 3.0) < 1e-3 and abs(bb[2] - 0.5) < 1e-6)
    assert len(junction) == 1, junction
    v = try_fillet(v, junction, 0.2)
    o.synchronize()
    # the flange's outer rims: the circles r=2.6 at z=0 and z=0.5
    rims = circle_edges_where(v, lambda bb: abs(bb[3] - bb[0] - 5.2) < 1e-3)
    assert len(rims) == 2, rims
    try_fillet(v, rims, 0.1)
    o.synchronize()

def pulley_vgroove():
    # added Dec 2026 (turned parts): closed (r, z) profile revolved 2*pi about z; r=3, width 2 (z -1..1),
    # V-groove 0.8 deep (flat bottom 0.3 wide at r=2.2, 0.9 wide at r=3), bore r=0.8,
    # annular pockets r 1.3..2.3, 0.4 deep on both faces (I/H cross-section)
    o = occ()
    prof = [(0.8, -1), (1.3, -1), (1.3, -0.6), (2.3, -0.6), (2.3, -1), (3.0, -1), (3.0, -0.45), (2.2, -0.15),
            (2.2, 0.15), (3.0, 0.45), (3.0, 1), (2.3, 1), (2.3, 0.6), (1.3, 0.6), (1.3, 1), (0.8, 1)]
    pts = [o.addPoint(x, 0, z) for x, z in prof]
    lines = [o.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
    s = o.addPlaneSurface([o.addCurveLoop(lines)])
    o.revolve([(2, s)], 0, 0, 0, 0, 0, 1, 2 * PI)
    o.remove([(2, s)], recursive=True)
    o.synchronize()

def spoked_wheel():
    # added Dec 2026 (turned parts): rim r 3.0..3.5 (width 1), hub r 0.5..1.0 (width 1.2), 5 round spokes r=0.25
    # from r=0.75 (inside the hub) to r=3.25 (inside the rim), fused; junctions left sharp
    o = occ()
    rim, _ = o.cut([(3, o.addCylinder(0, 0, -0.5, 0, 0, 1, 3.5))], [(3, o.addCylinder(0, 0, -1, 0, 0, 2, 3.0))])
    hub, _ = o.cut([(3, o.addCylinder(0, 0, -0.6, 0, 0, 1.2, 1.0))], [(3, o.addCylinder(0, 0, -1, 0, 0, 2, 0.5))])
    spokes = []
    for k in range(5):
        a = 2 * PI * k / 5
        c, s_ = math.cos(a), math.sin(a)
        spokes.append((3, o.addCylinder(0.75 * c, 0.75 * s_, 0, 2.5 * c, 2.5 * s_, 0, 0.25)))
    r, _ = o.fuse(rim, hub + spokes)
    o.synchronize()

SHAPES = [
    ('cad_flange_5holes', flange, 'disk r=5 t=1, central hole + 4 bolt holes, outer rims filleted', 0.3),
    ('cad_L_bracket_2holes', lbracket, 'L bracket (two 6x4x1 legs) with one round hole per leg, inner corner filleted', 0.3),
    ('cad_mug_torus_handle', mug, 'solid cylinder r=2 h=5 fused with torus handle (R=1.3,r=0.3)', 0.3),
    ('cad_tee_solid', tee, 'solid T: cylinder r=1 along x fused with cylinder r=0.7 along z', 0.3),
    ('cad_elbow_tube', elbow, 'thick-walled pipe (r 0.6..1.0) revolved 90 deg about z, annular end caps', 0.2),
    ('cad_box_3holes', box3holes, 'box 8x3x2 with 3 parallel through-holes, vertical edges filleted', 0.3),
    ('cad_cube_cross_holes', cross_holes, 'cube 4^3 with crossing through-holes along x (r=.8) and y (r=.6)', 0.3),
    ('cad_stepped_shaft', shaft, '3 coaxial cylinders r=2/1.4/0.9 fused, end rims filleted', 0.3),
    ('cad_plate_6holes', plate6holes, 'plate 9x6x1 with 6 through-holes r=0.7 (3x2), vertical edges filleted r=0.5', 0.3),
    ('cad_flanged_bushing', flanged_bushing, 'tube r 1.0..1.5 L=4 with flange r=2.6 t=0.5, junction filleted r=0.2, flange rims r=0.1', 0.23),
    ('cad_pulley_vgroove', pulley_vgroove, 'pulley r=3 w=2 revolved from an I/H profile: V-groove 0.8 deep, bore r=0.8, hub pockets', 0.26),
    ('cad_spoked_wheel', spoked_wheel, 'rim r 3..3.5 + hub r 0.5..1 joined by 5 round spokes r=0.25, sharp junctions', 0.2),
]

if __name__ == '__main__':
    sel = sys.argv[1:]
    for name, fn, desc, h0 in SHAPES:
        if sel and name not in sel: continue
        print(name)
        try:
            V, F = gmsh_surface_mesh(fn, h0=h0, name=name)
            V, F, info = check(V, F)
            write_off(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '%s.off') % name, V, F)
            print('  OK', info)
        except Exception as e:
            import traceback; traceback.print_exc()
            print('  FAIL', name, e)
