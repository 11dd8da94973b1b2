#!/usr/bin/env python3
"""Writes the mesh files of assets/robots/arm4.urdf, one per format the loader reads:
arm4_turret.stl (binary STL, a hexagonal housing), arm4_upper_arm.obj with
arm4_upper_arm.mtl (a tapered octagonal beam, faces as polygons and no normals, its colour
in the material library) and arm4_hand.dae (COLLADA: a palm and two fingers placed by node
transforms, with its own material colour). Triangles wind counter-clockwise seen from
outside. Run from anywhere: python3 assets/robots/meshes/make_arm4_meshes.py
Original geometry written for stiction (CC0, as ../LICENSE)."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def prism(sides, radius, z0, z1):
    """A regular prism about z: triangles (three corners each), outward."""
    ring = [(radius * math.cos(2 * math.pi * k / sides), radius * math.sin(2 * math.pi * k / sides))
            for k in range(sides)]
    tris = []
    for k in range(sides):
        (x0, y0), (x1, y1) = ring[k], ring[(k + 1) % sides]
        a, b, c, d = [x0, y0, z0], [x1, y1, z0], [x1, y1, z1], [x0, y0, z1]
        tris += [[a, b, c], [a, c, d]]
        tris.append([[0, 0, z1], [x0, y0, z1], [x1, y1, z1]])  # top, normal +z
        tris.append([[0, 0, z0], [x1, y1, z0], [x0, y0, z0]])  # bottom, normal -z
    return tris


def write_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"arm4 turret: binary STL written by make_arm4_meshes.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            n = unit(cross(sub(t[1], t[0]), sub(t[2], t[0])))
            f.write(struct.pack("<12fH", *n, *t[0], *t[1], *t[2], 0))


def write_obj(path, mtl):
    """A beam along x from -0.03 to 0.35 m, octagonal, tapering from 45 to 30 mm radius."""
    sides, x0, x1, r0, r1 = 8, -0.03, 0.35, 0.045, 0.030
    lines = ["# arm4 upper arm: written by make_arm4_meshes.py (no normals: the loader makes them)",
             f"mtllib {os.path.basename(mtl)}", "o upper_arm"]
    for x, r in ((x0, r0), (x1, r1)):
        for k in range(sides):
            phi = 2 * math.pi * (k + 0.5) / sides
            lines.append(f"v {x:.4f} {r * math.cos(phi):.5f} {r * math.sin(phi):.5f}")
    lines.append("usemtl orange")
    for k in range(sides):  # quads, counter-clockwise from outside
        a, b = 1 + k, 1 + (k + 1) % sides
        lines.append(f"f {a} {b} {b + sides} {a + sides}")
    lines.append("f " + " ".join(str(1 + k) for k in reversed(range(sides))))  # end at x0: -x
    lines.append("f " + " ".join(str(1 + sides + k) for k in range(sides)))  # end at x1: +x
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(mtl, "w") as f:
        f.write("# arm4 upper arm's material\nnewmtl orange\nKa 0 0 0\nKd 0.93 0.50 0.08\n"
                "Ks 0.3 0.3 0.3\nd 1\n")


def box(lo, hi):
    """An axis-aligned box's twelve triangles, outward."""
    x = [lo[0], hi[0]]
    y = [lo[1], hi[1]]
    z = [lo[2], hi[2]]
    p = lambda i, j, k: [x[i], y[j], z[k]]
    quads = [
        (p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)),  # +x
        (p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)),  # -x
        (p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)),  # +y
        (p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)),  # -y
        (p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)),  # +z
        (p(0, 1, 0), p(1, 1, 0), p(1, 0, 0), p(0, 0, 0)),  # -z
    ]
    tris = []
    for a, b, c, d in quads:
        tris += [[a, b, c], [a, c, d]]
    return tris


def collada_geometry(gid, tris):
    pos = " ".join(f"{v:.4f}" for t in tris for corner in t for v in corner)
    nrm = []
    for t in tris:
        n = unit(cross(sub(t[1], t[0]), sub(t[2], t[0])))
        nrm += n * 3
    nrm = " ".join(f"{v:.4f}" for v in nrm)
    count = 3 * len(tris)
    idx = " ".join(f"{i} {i}" for i in range(count))
    return f"""    <geometry id="{gid}" name="{gid}"><mesh>
      <source id="{gid}-pos"><float_array id="{gid}-pos-a" count="{3 * count}">{pos}</float_array>
        <technique_common><accessor source="#{gid}-pos-a" count="{count}" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <source id="{gid}-nrm"><float_array id="{gid}-nrm-a" count="{3 * count}">{nrm}</float_array>
        <technique_common><accessor source="#{gid}-nrm-a" count="{count}" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <vertices id="{gid}-vtx"><input semantic="POSITION" source="#{gid}-pos"/></vertices>
      <triangles material="grip" count="{len(tris)}"><input semantic="VERTEX" source="#{gid}-vtx" offset="0"/><input semantic="NORMAL" source="#{gid}-nrm" offset="1"/><p>{idx}</p></triangles>
    </mesh></geometry>
"""


def write_dae(path):
    """A palm (x 0..0.045) and a finger geometry used twice, each finger placed by its node's
    translation at y = +-0.028 (so the loader must apply the node transforms)."""
    palm = box([0.0, -0.045, -0.028], [0.045, 0.045, 0.028])
    finger = box([0.0, -0.008, -0.018], [0.065, 0.008, 0.018])
    nodes = ['      <node id="palm"><instance_geometry url="#palm-mesh"><bind_material><technique_common>'
             '<instance_material symbol="grip" target="#grip-material"/></technique_common>'
             '</bind_material></instance_geometry></node>']
    for name, y in (("finger_l", 0.028), ("finger_r", -0.028)):
        nodes.append(f'      <node id="{name}"><translate>0.045 {y} 0</translate>'
                     '<instance_geometry url="#finger-mesh"><bind_material><technique_common>'
                     '<instance_material symbol="grip" target="#grip-material"/></technique_common>'
                     '</bind_material></instance_geometry></node>')
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<!-- arm4 hand: written by make_arm4_meshes.py -->
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_effects>
    <effect id="grip-effect"><profile_COMMON><technique sid="common"><phong>
      <diffuse><color>0.16 0.55 0.36 1</color></diffuse>
    </phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials><material id="grip-material" name="grip"><instance_effect url="#grip-effect"/></material></library_materials>
  <library_geometries>
{collada_geometry("palm-mesh", palm)}{collada_geometry("finger-mesh", finger)}  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
{chr(10).join(nodes)}
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""
    with open(path, "w") as f:
        f.write(text)


if __name__ == "__main__":
    write_stl(os.path.join(HERE, "arm4_turret.stl"), prism(6, 0.075, -0.03, 0.05))
    write_obj(os.path.join(HERE, "arm4_upper_arm.obj"), os.path.join(HERE, "arm4_upper_arm.mtl"))
    write_dae(os.path.join(HERE, "arm4_hand.dae"))
