#!/usr/bin/env python3
"""Writes the collision geometry files of this folder (docs/collision.md, "Geometry files").

  panda.yaml  the capsules of example-robot-data's panda_collision.urdf (each cylinder with the two
              spheres at its ends is one capsule), with panda.srdf's disabled pairs;
  jvrc1.yaml  one box per link of JVRC-1: the bounding box, in the link frame, of the upstream
              convex hull (jvrc_description/convex/jvrc1/<mesh>-ch.txt) placed by the URDF's
              collision origin.

Usage: make_geometry.py MODELS_DIR   (the folder of ../shared/models: jvrc1.urdf,
       jvrc_description/, example-robot-data/)
"""
import math
import os
import sys
import xml.etree.ElementTree as ET


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def origin_of(el):
    o = el.find("origin")
    xyz = [0.0, 0.0, 0.0]
    rpy = [0.0, 0.0, 0.0]
    if o is not None:
        if o.get("xyz"):
            xyz = [float(v) for v in o.get("xyz").split()]
        if o.get("rpy"):
            rpy = [float(v) for v in o.get("rpy").split()]
    return xyz, rpy


def fmt(v):
    return "[" + ", ".join("%.6g" % x for x in v) + "]"


def panda(models, out):
    urdf = os.path.join(models, "example-robot-data/robots/panda_description/urdf/panda_collision.urdf")
    root = ET.parse(urdf).getroot()
    lines = ["# The Panda's collision capsules, from example-robot-data's panda_collision.urdf (BSD-3):",
             "# each cylinder there carries a sphere at each end, i.e. one capsule. Written by",
             "# make_geometry.py; docs/collision.md.", "srdf: panda.srdf", "links:"]
    for link in root.findall("link"):
        caps = []
        for c in link.findall("collision"):
            g = c.find("geometry")
            cyl = g.find("cylinder")
            if cyl is None:
                continue
            xyz, rpy = origin_of(c)
            caps.append("    - {capsule: {radius: %s, length: %s}, xyz: %s, rpy: %s}" %
                        (cyl.get("radius"), cyl.get("length"), fmt(xyz), fmt(rpy)))
        if caps:
            lines.append("  %s:" % link.get("name"))
            lines.extend(caps)
    open(out, "w").write("\n".join(lines) + "\n")


def read_hull_points(path):
    with open(path) as f:
        toks = f.read().split()
    n = int(toks[1])
    return [[float(toks[4 + 3 * i + k]) for k in range(3)] for i in range(n)]


def jvrc1(models, out):
    root = ET.parse(os.path.join(models, "jvrc1.urdf")).getroot()
    convex = os.path.join(models, "jvrc_description/convex/jvrc1")
    lines = ["# JVRC-1's collision boxes: per link, the bounding box in the link frame of the upstream convex",
             "# hull (jvrc_description/convex/jvrc1/<mesh>-ch.txt, BSD-2) placed by the URDF's collision",
             "# origin. Written by make_geometry.py; docs/collision.md.", "links:"]
    for link in root.findall("link"):
        for c in link.findall("collision"):
            mesh = c.find("geometry/mesh")
            if mesh is None:
                continue
            stem = os.path.splitext(os.path.basename(mesh.get("filename")))[0]
            hull = os.path.join(convex, stem + "-ch.txt")
            if not os.path.exists(hull):
                continue
            xyz, rpy = origin_of(c)
            R = rpy_matrix(*rpy)
            pts = [[sum(R[i][k] * p[k] for k in range(3)) + xyz[i] for i in range(3)] for p in read_hull_points(hull)]
            lo = [min(p[i] for p in pts) for i in range(3)]
            hi = [max(p[i] for p in pts) for i in range(3)]
            size = [hi[i] - lo[i] for i in range(3)]
            centre = [0.5 * (hi[i] + lo[i]) for i in range(3)]
            lines.append("  %s:" % link.get("name"))
            lines.append("    - {box: %s, xyz: %s}" % (fmt(size), fmt(centre)))
    open(out, "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    here = os.path.dirname(os.path.abspath(__file__))
    panda(sys.argv[1], os.path.join(here, "panda.yaml"))
    jvrc1(sys.argv[1], os.path.join(here, "jvrc1.yaml"))
