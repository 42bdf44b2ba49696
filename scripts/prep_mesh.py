#!/usr/bin/env python3
"""Convert a source mesh to the benchmark OBJ format used by hotcut.

Output format (identical to the files in the shared data directory):
  - two '#' comment lines:
        # <model> - from <owner/repo:path> @ <12-char commit>
        # <V> vertices, <F> triangles; written by tools/meshprep.py
    (the second line names the tool that wrote the reference files; it is
    kept verbatim so that re-converted files are byte-identical to them)
  - 'v x y z' lines, each coordinate printed with 6 significant digits
    (printf '%.6g'), in source vertex order;
  - 'f i j k' lines (1-based), in source face order and orientation.
  - '\n' line endings, no normals, no texture coordinates.

Supported inputs (detected from the file extension, or --format):
  .obj   'v' and 'f' lines (f entries may be i, i/t, i//n, i/t/n; negative
         indices allowed); faces must be triangles.
  .off   OFF header, counts, vertices, faces ('3 a b c', 0-based).
  .mesh  MEDIT ASCII tetrahedral mesh: the boundary surface of the
         'Tetrahedra' is taken (faces that belong to exactly one tet),
         oriented outwards, and vertices not used by it are dropped
         (the remaining vertices keep their relative order).

Only the Python standard library is used.

Usage:
  prep_mesh.py SRC OUT --model NAME --source OWNER/REPO:PATH --commit HASH
  prep_mesh.py --stats FILE.obj      # print counts and bounding box as JSON
"""

import argparse
import json
import os
import sys


class MeshError(Exception):
    pass


# ---------------------------------------------------------------- readers

def read_obj(text):
    verts, faces = [], []
    for lineno, line in enumerate(text.splitlines(), 1):
        parts = line.split()
        if not parts:
            continue
        tag = parts[0]
        if tag == "v":
            if len(parts) < 4:
                raise MeshError("line %d: short vertex line" % lineno)
            verts.append(tuple(float(x) for x in parts[1:4]))
        elif tag == "f":
            idx = []
            for tok in parts[1:]:
                i = int(tok.split("/")[0])
                if i < 0:
                    i = len(verts) + i
                else:
                    i -= 1
                idx.append(i)
            if len(idx) != 3:
                raise MeshError("line %d: face with %d vertices (only "
                                "triangles are supported)" % (lineno, len(idx)))
            faces.append(tuple(idx))
    return verts, faces


def _tokens_no_comments(text):
    for line in text.splitlines():
        line = line.split("#", 1)[0]
        for tok in line.split():
            yield tok


def read_off(text):
    toks = _tokens_no_comments(text)
    head = next(toks)
    if head != "OFF":
        if head.startswith("OFF"):
            raise MeshError("unsupported OFF variant %r" % head)
        raise MeshError("not an OFF file (header %r)" % head)
    nv, nf, _ne = int(next(toks)), int(next(toks)), int(next(toks))
    verts = []
    for _ in range(nv):
        verts.append((float(next(toks)), float(next(toks)), float(next(toks))))
    faces = []
    for k in range(nf):
        n = int(next(toks))
        idx = tuple(int(next(toks)) for _ in range(n))
        if n != 3:
            raise MeshError("face %d has %d vertices (only triangles are "
                            "supported)" % (k, n))
        faces.append(idx)
    # Plain OFF only (no per-face colours, no COFF/NOFF variants).
    return verts, faces


def read_medit(text):
    """Return vertices and tetrahedra (0-based) of an ASCII MEDIT .mesh."""
    toks = list(_tokens_no_comments(text))
    pos = 0
    verts, tets = None, None
    dim = 3
    while pos < len(toks):
        kw = toks[pos]
        pos += 1
        if kw == "MeshVersionFormatted":
            pos += 1
        elif kw == "Dimension":
            dim = int(toks[pos])
            pos += 1
            if dim != 3:
                raise MeshError("only Dimension 3 is supported")
        elif kw == "End":
            break
        elif kw in ("Vertices", "Edges", "Triangles", "Quadrilaterals",
                    "Tetrahedra", "Hexahedra", "Corners", "RequiredVertices",
                    "Ridges", "RequiredEdges", "Normals", "Tangents"):
            n = int(toks[pos])
            pos += 1
            width = {"Vertices": dim + 1, "Edges": 3, "Triangles": 4,
                     "Quadrilaterals": 5, "Tetrahedra": 5, "Hexahedra": 9,
                     "Corners": 1, "RequiredVertices": 1, "Ridges": 1,
                     "RequiredEdges": 1, "Normals": dim,
                     "Tangents": dim}[kw]
            rows = [toks[pos + k * width: pos + (k + 1) * width]
                    for k in range(n)]
            pos += n * width
            if kw == "Vertices":
                verts = [tuple(float(x) for x in r[:3]) for r in rows]
            elif kw == "Tetrahedra":
                tets = [tuple(int(x) - 1 for x in r[:4]) for r in rows]
        else:
            raise MeshError("unsupported MEDIT keyword %r" % kw)
    if verts is None or tets is None:
        raise MeshError("MEDIT file needs Vertices and Tetrahedra sections")
    return verts, tets


def _orient3d(a, b, c, d):
    """Six times the signed volume of tet (a, b, c, d)."""
    bx, by, bz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    cx, cy, cz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    dx, dy, dz = d[0] - a[0], d[1] - a[1], d[2] - a[2]
    return (bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx)
            + bz * (cx * dy - cy * dx))


def tet_boundary(verts, tets):
    """Boundary triangles of a tet mesh, oriented outwards.

    Faces are listed by local face number j (the face opposite the tet's
    j-th vertex), then by tet order.  A face keeps the tet's vertex order,
    with its last two vertices swapped when needed so that the opposite
    vertex lies behind it (outward normal).  Unused vertices are dropped.
    """
    count = {}
    for t in tets:
        for j in range(4):
            key = tuple(sorted(t[:j] + t[j + 1:]))
            count[key] = count.get(key, 0) + 1
    bad = sum(1 for c in count.values() if c > 2)
    if bad:
        raise MeshError("%d tet faces are shared by more than two tets" % bad)
    faces = []
    for j in range(4):
        for t in tets:
            f = t[:j] + t[j + 1:]
            if count[tuple(sorted(f))] != 1:
                continue
            vol = _orient3d(verts[f[0]], verts[f[1]], verts[f[2]],
                            verts[t[j]])
            if vol == 0.0:
                raise MeshError("degenerate tetrahedron %r" % (t,))
            if vol > 0.0:           # opposite vertex in front: flip
                f = (f[0], f[2], f[1])
            faces.append(f)
    used = sorted({i for f in faces for i in f})
    remap = {old: new for new, old in enumerate(used)}
    return ([verts[i] for i in used],
            [tuple(remap[i] for i in f) for f in faces],
            len(verts) - len(used))


# ---------------------------------------------------------------- writer

def fmt(x):
    s = "%.6g" % x
    return s


def write_obj(path, verts, faces, title):
    n = len(verts)
    for f in faces:
        for i in f:
            if not 0 <= i < n:
                raise MeshError("face index %d out of range" % (i + 1))
    out = ["# %s" % title,
           "# %d vertices, %d triangles; written by tools/meshprep.py"
           % (len(verts), len(faces))]
    out.extend("v %s %s %s" % (fmt(v[0]), fmt(v[1]), fmt(v[2])) for v in verts)
    out.extend("f %d %d %d" % (f[0] + 1, f[1] + 1, f[2] + 1) for f in faces)
    data = ("\n".join(out) + "\n").encode("ascii")
    tmp = path + ".tmp"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def stats(path):
    with open(path, "r", encoding="ascii") as fh:
        verts, faces = read_obj(fh.read())
    lo = [min(v[k] for v in verts) for k in range(3)] if verts else [0] * 3
    hi = [max(v[k] for v in verts) for k in range(3)] if verts else [0] * 3
    return {"vertices": len(verts), "faces": len(faces),
            "bbox_min": lo, "bbox_max": hi}


# ---------------------------------------------------------------- main

def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("src", help="source mesh (.obj, .off, .mesh)")
    ap.add_argument("out", nargs="?", help="output .obj")
    ap.add_argument("--format", choices=["obj", "off", "mesh"])
    ap.add_argument("--model", help="model name for the header")
    ap.add_argument("--source", help="owner/repo:path for the header")
    ap.add_argument("--commit", help="source commit (first 12 chars shown)")
    ap.add_argument("--stats", action="store_true",
                    help="print vertex/face counts and bbox of SRC (an OBJ)")
    a = ap.parse_args(argv)

    try:
        if a.stats:
            print(json.dumps(stats(a.src)))
            return 0
        if not (a.out and a.model and a.source and a.commit):
            ap.error("OUT, --model, --source and --commit are required")
        fmt_ = a.format or os.path.splitext(a.src)[1].lstrip(".").lower()
        with open(a.src, "r", encoding="latin-1") as fh:
            text = fh.read()
        if fmt_ == "obj":
            verts, faces = read_obj(text)
        elif fmt_ == "off":
            verts, faces = read_off(text)
        elif fmt_ == "mesh":
            tv, tets = read_medit(text)
            verts, faces, dropped = tet_boundary(tv, tets)
            print("prep_mesh: boundary of %d tets: %d triangles; dropped %d "
                  "unused vertices" % (len(tets), len(faces), dropped),
                  file=sys.stderr)
        else:
            raise MeshError("unknown input format %r" % fmt_)
        title = "%s - from %s @ %s" % (a.model, a.source, a.commit[:12])
        write_obj(a.out, verts, faces, title)
    except (MeshError, ValueError, StopIteration, IndexError, OSError) as e:
        print("prep_mesh: %s: %s" % (a.src, e or type(e).__name__),
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
