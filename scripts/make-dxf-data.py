#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes line drawings (cellforge's text format: j x y / e a b / a i j rx ry rot large ccw) as
DXF with ezdxf, a third-party writer, for test_io_dxf_drawing: each drawing in R12, R2000 and
R2018 (R12 only when it has no elliptical arcs: R12 has no ELLIPSE).

    make-dxf-data.py OUT_DIR DRAWING.txt|DIR...   (a DIR: its *.txt)
    make-dxf-data.py --plain OUT_DIR DRAWING.txt... (R2000 only, no decoys: <stem>.dxf, the
                                                     examples' bundled DXF drawings)

Writes OUT_DIR/<stem>.<version>.dxf. The strokes are spread over the entity kinds: chains of
edges become LINEs, LWPOLYLINEs (POLYLINE in R12) or blocks placed by INSERT (rotated, scaled,
moved; the block's points carried back by the inverse placement); circular arcs become ARCs or
bulged LWPOLYLINE segments, elliptical ones ELLIPSEs. Strokes go on layers "Outline" and
"Detail"; decoys the reader must leave out go on layer "Notes" (TEXT, a LINE, a CIRCLE; the test
picks layers) and on a frozen layer "Frozen" (a LINE).
"""
import math
import os
import sys

import ezdxf


def read_drawing(path):
    pts, edges, arcs = [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if w[0] == "j":
                pts.append((float(w[1]), float(w[2])))
            elif w[0] == "e":
                edges.append((int(w[1]), int(w[2])))
            elif w[0] == "a":
                arcs.append((int(w[1]), int(w[2]), float(w[3]), float(w[4]), float(w[5]), w[6] == "1", w[7] == "1"))
    return pts, edges, arcs


def chains(n, edges):
    """Edges grouped into paths (greedy walks), each a list of junctions."""
    adj = [[] for _ in range(n)]
    for k, (a, b) in enumerate(edges):
        adj[a].append((k, b))
        adj[b].append((k, a))
    used = [False] * len(edges)
    out = []
    for k, (a, b) in enumerate(edges):
        if used[k]:
            continue
        used[k] = True
        path = [a, b]
        while True:
            nxt = next(((e, j) for e, j in adj[path[-1]] if not used[e]), None)
            if nxt is None:
                break
            used[nxt[0]] = True
            path.append(nxt[1])
        out.append(path)
    return out


def arc_centre(p0, p1, rx, ry, rot, large, ccw):
    """SVG's endpoint-to-centre conversion (the SVG specification, implementation notes)."""
    c, s = math.cos(rot), math.sin(rot)
    hx, hy = (p0[0] - p1[0]) / 2, (p0[1] - p1[1]) / 2
    qx, qy = c * hx + s * hy, -s * hx + c * hy
    lam = qx * qx / (rx * rx) + qy * qy / (ry * ry)
    k = 0.0
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    else:
        num = rx * rx * ry * ry - rx * rx * qy * qy - ry * ry * qx * qx
        den = rx * rx * qy * qy + ry * ry * qx * qx
        k = math.sqrt(max(0.0, num / den))
    if large == ccw:
        k = -k
    cqx, cqy = k * rx * qy / ry, -k * ry * qx / rx
    cx = c * cqx - s * cqy + (p0[0] + p1[0]) / 2
    cy = s * cqx + c * cqy + (p0[1] + p1[1]) / 2
    return (cx, cy), rx, ry


def param(p, centre, rx, ry, rot):
    c, s = math.cos(rot), math.sin(rot)
    dx, dy = p[0] - centre[0], p[1] - centre[1]
    return math.atan2((-s * dx + c * dy) / ry, (c * dx + s * dy) / rx)


def write(pts, edges, arcs, version, path, decoys=True):
    doc = ezdxf.new(version)
    msp = doc.modelspace()
    for name in ("Outline", "Detail", "Notes"):
        doc.layers.add(name)
    doc.layers.add("Frozen").freeze()
    layer = lambda k: {"layer": "Outline" if k % 2 == 0 else "Detail"}
    for k, path_ in enumerate(chains(len(pts), edges)):
        kind = k % 3
        if kind == 0:
            for a, b in zip(path_, path_[1:]):
                msp.add_line(pts[a], pts[b], dxfattribs=layer(k))
        elif kind == 1:
            closed = len(path_) > 3 and path_[0] == path_[-1]
            vs = [pts[j] for j in (path_[:-1] if closed else path_)]
            if version == "R12":
                msp.add_polyline2d(vs, close=closed, dxfattribs=layer(k))
            else:
                msp.add_lwpolyline(vs, close=closed, dxfattribs=layer(k))
        else:
            # A block placed at `ins`, rotated by `deg`, scaled (sx, sy): its points are the
            # drawing's under the inverse placement. Entities in it on layer "0" take the INSERT's.
            ins, deg, sx, sy = (0.25 * k, -0.5), 20.0 + 7 * k, 2.0, 0.5
            r = math.radians(deg)
            def inverse(p):
                dx, dy = p[0] - ins[0], p[1] - ins[1]
                return ((math.cos(r) * dx + math.sin(r) * dy) / sx, (-math.sin(r) * dx + math.cos(r) * dy) / sy)
            blk = doc.blocks.new(f"chain{k}")
            for a, b in zip(path_, path_[1:]):
                blk.add_line(inverse(pts[a]), inverse(pts[b]))
            msp.add_blockref(f"chain{k}", ins, dxfattribs={**layer(k), "xscale": sx, "yscale": sy, "rotation": deg})
    for k, (i, j, rx, ry, rot_deg, large, ccw) in enumerate(arcs):
        rot = math.radians(rot_deg)
        centre, rx, ry = arc_centre(pts[i], pts[j], rx, ry, rot, large, ccw)
        a, b = (pts[i], pts[j]) if ccw else (pts[j], pts[i])  # DXF's arcs run counter-clockwise
        if abs(rx - ry) <= 1e-12 * max(rx, ry):
            if k % 2 == 0 or version == "R12":
                start = math.degrees(math.atan2(a[1] - centre[1], a[0] - centre[0]))
                end = math.degrees(math.atan2(b[1] - centre[1], b[0] - centre[0]))
                msp.add_arc(centre, rx, start, end, dxfattribs=layer(k))
            else:
                t0, t1 = param(pts[i], centre, rx, ry, rot), param(pts[j], centre, rx, ry, rot)
                sweep = (t1 - t0) % (2 * math.pi) if ccw else -((t0 - t1) % (2 * math.pi))
                msp.add_lwpolyline([(*pts[i], 0, 0, math.tan(sweep / 4)), pts[j]], format="xyseb",
                                   dxfattribs=layer(k))
        else:
            if version == "R12":
                raise ValueError("R12 has no ELLIPSE")
            # The major axis is the longer one; a minor axis as rx turns the parameter by -90°.
            major = (rx * math.cos(rot), rx * math.sin(rot)) if rx >= ry else (-ry * math.sin(rot), ry * math.cos(rot))
            mrot = rot if rx >= ry else rot + math.pi / 2
            big, small = max(rx, ry), min(rx, ry)
            t0, t1 = param(a, centre, big, small, mrot), param(b, centre, big, small, mrot)
            msp.add_ellipse(centre, (*major, 0), small / big, t0, t1, dxfattribs=layer(k))
    if not decoys:
        doc.saveas(path)
        return
    # Decoys: left out by choosing layers (Notes) or frozen (Frozen).
    msp.add_text("not a stroke", dxfattribs={"layer": "Notes"})
    msp.add_line((1e3, 1e3), (1e3 + 1, 1e3), dxfattribs={"layer": "Notes"})
    msp.add_circle((-1e3, 0), 2.0, dxfattribs={"layer": "Notes"})
    msp.add_line((-1e3, -1e3), (-1e3 + 1, -1e3), dxfattribs={"layer": "Frozen"})
    doc.saveas(path)


def main():
    args = sys.argv[1:]
    plain = bool(args) and args[0] == "--plain"
    if plain:
        args = args[1:]
    if len(args) < 2:
        sys.exit(__doc__)
    out = args[0]
    os.makedirs(out, exist_ok=True)
    written = 0
    sources = []
    for arg in args[1:]:
        if os.path.isdir(arg):
            sources += sorted(os.path.join(arg, f) for f in os.listdir(arg) if f.endswith(".txt"))
        else:
            sources.append(arg)
    for src in sources:
        pts, edges, arcs = read_drawing(src)
        stem = os.path.splitext(os.path.basename(src))[0]
        if plain:
            write(pts, edges, arcs, "R2000", os.path.join(out, f"{stem}.dxf"), decoys=False)
            written += 1
            continue
        elliptical = any(abs(rx - ry) > 1e-12 * max(rx, ry) for _, _, rx, ry, _, _, _ in arcs)
        for version in ("R12", "R2000", "R2018"):
            if version == "R12" and elliptical:
                continue
            write(pts, edges, arcs, version, os.path.join(out, f"{stem}.{version}.dxf"))
            written += 1
    print(f"make-dxf-data: {written} DXF files from {len(sources)} drawings in {out} (ezdxf {ezdxf.__version__})")


if __name__ == "__main__":
    main()
