#!/usr/bin/env python3
"""Makes the triangle meshes of the kidney template (templates/kidney.yaml).

Usage: python3 scripts/make_kidney.py [OUTDIR]      (default: templates/ beside this script)

Writes three ASCII PLY files in millimetres, each a closed triangle mesh wound outwards:
  kidney.ply          the capsule (the template's skin)
  kidney-medulla.ply  seven renal pyramids (the medulla), one closed mesh each
  kidney-pelvis.ply   the renal pelvis with one calyx reaching towards each pyramid's tip

The model is a right kidney standing upright: long axis +Y (110 mm), the convex lateral border
towards +X (60 mm wide), front to back along Z (36 mm), the hilum on the medial (-X) side.
Everything is first built in a simple frame where the capsule is an ellipsoid, then bent into
the bean shape and dented at the hilum by one smooth map that is one-to-one, so surfaces that
do not touch before the map do not touch after it.

Python 3 standard library only; the output is deterministic (same bytes on every run).
"""

import math
import os
import sys

# Capsule semi-axes (mm) in the ellipsoid frame, before bending.
A, B, C = 28.0, 55.0, 18.0
# Bending (the centre line moves towards +X in the middle) and the hilum dent.
BEND = 4.0
DENT = 11.0
# Renal sinus centre (where the pelvis sits) and the pyramids.
SINUS = (-13.0, 0.0, 0.0)
PYRAMID_ANGLES = (-110.0, -75.0, -40.0, -5.0, 30.0, 66.0, 104.0)  # degrees about SINUS, XY plane
CORTEX = 0.80      # pyramid bases lie at this fraction of the way out to the capsule
PAPILLA = 0.45     # pyramid tips lie at this fraction of the way from the sinus to the base


def deform(p):
    """The bean: bend the centre line and push the medial surface in at the hilum."""
    x, y, z = p
    t = y / B
    x += BEND * (1.0 - t * t)
    if x < 0.0:
        s = -x / A
        x += DENT * s * s * math.exp(-(y / 16.0) ** 2) * math.exp(-(z / 11.0) ** 2)
    return (x, y, z)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def uv_sphere(rings, segments, point):
    """A closed mesh of `rings` latitude bands and `segments` longitudes; point(theta, phi)
    gives the vertex at polar angle theta (0 at the north pole, about `axis`) and azimuth phi.
    Returns (vertices, triangles), triangles wound so that point's outside is the front."""
    verts = [point(0.0, 0.0)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            verts.append(point(theta, 2.0 * math.pi * j / segments))
    verts.append(point(math.pi, 0.0))
    south = len(verts) - 1
    tris = []
    for j in range(segments):
        tris.append((0, 1 + (j + 1) % segments, 1 + j))
    for i in range(rings - 2):
        a0, b0 = 1 + i * segments, 1 + (i + 1) * segments
        for j in range(segments):
            j1 = (j + 1) % segments
            tris.append((a0 + j, a0 + j1, b0 + j))
            tris.append((a0 + j1, b0 + j1, b0 + j))
    last = 1 + (rings - 2) * segments
    for j in range(segments):
        tris.append((south, last + j, last + (j + 1) % segments))
    return verts, tris


def signed_volume(verts, tris):
    return sum(dot(verts[a], cross(verts[b], verts[c])) for a, b, c in tris) / 6.0


def outward(verts, tris):
    """Turns the winding so that the mesh encloses a positive volume (normals outwards)."""
    if signed_volume(verts, tris) < 0.0:
        tris = [(a, c, b) for a, b, c in tris]
    return tris


def capsule():
    def point(theta, phi):
        st = math.sin(theta)
        return deform((A * st * math.cos(phi), B * math.cos(theta), C * st * math.sin(phi)))
    verts, tris = uv_sphere(40, 56, point)
    return verts, outward(verts, tris)


def capsule_point_towards(direction):
    """Where the ray from SINUS along `direction` leaves the ellipsoid (ellipsoid frame)."""
    o, d = SINUS, direction
    qa = (d[0] / A) ** 2 + (d[1] / B) ** 2 + (d[2] / C) ** 2
    qb = 2.0 * (o[0] * d[0] / A ** 2 + o[1] * d[1] / B ** 2 + o[2] * d[2] / C ** 2)
    qc = (o[0] / A) ** 2 + (o[1] / B) ** 2 + (o[2] / C) ** 2 - 1.0
    t = (-qb + math.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
    return add(o, scale(d, t))


def pyramids():
    """Returns the mesh of all pyramids and the list of their tips (ellipsoid frame)."""
    verts, tris, tips = [], [], []
    for angle in PYRAMID_ANGLES:
        a = math.radians(angle)
        d = (math.cos(a), math.sin(a), 0.0)
        outer = capsule_point_towards(d)
        base = add(SINUS, scale(sub(outer, SINUS), CORTEX))
        tip = add(SINUS, scale(sub(base, SINUS), PAPILLA))
        tips.append(tip)
        axis = unit(sub(base, tip))
        length = norm(sub(base, tip))
        # a frame across the axis: w along Z (the kidney's thickness), v in the XY plane
        w = (0.0, 0.0, 1.0)
        v = cross(w, axis)
        width = 0.36 * length * (1.0 if abs(angle) < 100 else 0.8)   # half-width in the XY plane
        depth = min(0.30 * length, 0.45 * C)                        # half-thickness along Z

        def point(theta, phi):
            # theta 0: the rounded base (a dome), pi: the papilla at the tip
            s = theta / math.pi
            if s < 0.2:  # dome over the base
                k = s / 0.2
                along = length + 1.8 * math.cos(k * math.pi / 2.0)
                r = math.sin(k * math.pi / 2.0)
            else:
                k = (s - 0.2) / 0.8        # 0 at the base rim, 1 at the tip
                along = length * (1.0 - k)
                r = (1.0 - k) ** 0.85 * 0.88 + 0.12 * math.sin((1.0 - k) * math.pi / 2.0)
                if k > 0.9:  # round the papilla
                    r *= math.sin((1.0 - k) / 0.1 * math.pi / 2.0)
            c = add(tip, scale(axis, along))
            p = add(c, add(scale(v, r * width * math.cos(phi)), scale(w, r * depth * math.sin(phi))))
            return deform(p)

        pv, pt = uv_sphere(14, 20, point)
        pt = outward(pv, pt)
        offset = len(verts)
        verts.extend(pv)
        tris.extend((a + offset, b + offset, c + offset) for a, b, c in pt)
    return verts, tris, tips


def pelvis(tips):
    """A star-shaped body about the sinus: a flat core with one calyx towards each papilla and
    the start of the ureter towards the hilum."""
    centre = SINUS
    targets = []
    for tip in tips:
        d = sub(tip, centre)
        targets.append((unit(d), norm(d) - 3.0))
    targets.append(((-1.0, -0.25, 0.0), 11.5))  # the ureter's start, towards the hilum
    targets = [(unit(u), reach) for u, reach in targets]

    def base(u):
        return 1.0 / math.sqrt((u[0] / 6.0) ** 2 + (u[1] / 12.0) ** 2 + (u[2] / 5.0) ** 2)

    def radius(u):
        r = base(u)
        for d, reach in targets:
            c = max(-1.0, min(1.0, dot(u, d)))
            ang = math.acos(c)
            r += max(0.0, reach - base(d)) * math.exp(-(ang / 0.27) ** 2)
        return r

    def point(theta, phi):
        # poles on the Z axis (front and back), so calyces in the XY plane are well sampled
        u = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
        return deform(add(centre, scale(u, radius(u))))

    verts, tris = uv_sphere(30, 90, point)
    return verts, outward(verts, tris)


def write_ply(path, comment, verts, tris):
    lines = ["ply", "format ascii 1.0", "comment " + comment,
             "comment made by scripts/make_kidney.py; units mm",
             "element vertex %d" % len(verts),
             "property float x", "property float y", "property float z",
             "element face %d" % len(tris),
             "property list uchar int vertex_indices", "end_header"]
    for x, y, z in verts:
        lines.append("%.3f %.3f %.3f" % (x + 0.0, y + 0.0, z + 0.0))
    for a, b, c in tris:
        lines.append("3 %d %d %d" % (a, b, c))
    data = ("\n".join(lines) + "\n").replace("-0.000", "0.000")
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(data)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, os.pardir, "templates")
    os.makedirs(out, exist_ok=True)
    cv, ct = capsule()
    pv, pt, tips = pyramids()
    lv, lt = pelvis(tips)
    write_ply(os.path.join(out, "kidney.ply"), "kidney capsule (skin)", cv, ct)
    write_ply(os.path.join(out, "kidney-medulla.ply"), "kidney renal pyramids", pv, pt)
    write_ply(os.path.join(out, "kidney-pelvis.ply"), "kidney renal pelvis and calyces", lv, lt)


if __name__ == "__main__":
    main()
