"""Solids for 3D printing: manifold3d extrusions written as binary STL and 3MF.

Both writers are gearcad's own (a few lines each) so that the same part always gives the same
bytes: fixed STL header, fixed zip timestamps and number formatting in 3MF.
"""

from __future__ import annotations

import io
import struct
import zipfile
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import manifold3d as m3d
import numpy as np

from ..errors import DesignError
from ..geometry.inset import check_chamfer, inset_ring
from ..geometry.outline import Outline

__all__ = ["Solid", "extrude", "write_stl", "write_3mf", "SolidItem"]


@dataclass(frozen=True)
class Solid:
    """A watertight triangle mesh: vertices (n, 3) float64 mm, triangles (m, 3) int."""

    name: str
    vertices: np.ndarray
    triangles: np.ndarray
    volume: float

    @cached_property
    def xml(self) -> str:
        """Vertices and triangles as 3MF XML, formatted once (for the part and the assembly)."""
        v = np.round(self.vertices, 6) + 0.0  # + 0.0 turns −0.0 into 0.0: stable text
        t = self.triangles
        return (
            ('<vertex x="%.6f" y="%.6f" z="%.6f"/>\n' * len(v)) % tuple(v.ravel())
            + "</vertices><triangles>\n"
            + ('<triangle v1="%d" v2="%d" v3="%d"/>\n' * len(t)) % tuple(t.ravel().tolist())
        )

    @property
    def triangle_count(self) -> int:
        return len(self.triangles)


def _check(solid: m3d.Manifold, name: str) -> None:
    status = solid.status()
    if status != m3d.Error.NoError:
        raise DesignError(f"{name}: the solid is not a valid manifold ({status.name})")
    if solid.is_empty():
        raise DesignError(f"{name}: the solid is empty")


def extrude(outline: Outline, thickness: float, *, name: str, chamfer: float = 0.0) -> Solid:
    """The outline (outer ring and holes) extruded to ``thickness`` mm, optionally with its top
    and bottom edges chamfered by ``chamfer`` mm (45°)."""
    section = m3d.CrossSection([np.asarray(r, dtype=float) for r in outline.rings], m3d.FillRule.EvenOdd)
    if chamfer > 0:
        check_chamfer(outline, thickness, chamfer, name=name)
        solid = _chamfered(section, outline, thickness, chamfer, name)
    else:
        solid = m3d.Manifold.extrude(section, thickness)
    _check(solid, name)
    mesh = solid.to_mesh64()
    return Solid(
        name,
        np.asarray(mesh.vert_properties)[:, :3].copy(),
        np.asarray(mesh.tri_verts).astype(np.int64),
        float(solid.volume()),
    )


def _chamfered(section, outline: Outline, thickness: float, chamfer: float, name: str) -> m3d.Manifold:
    """A 45° chamfer on every top and bottom edge: each ring is lofted from its inset copy at
    z = 0 to itself at z = chamfer, straight up to thickness − chamfer, and in again at the top;
    the caps are the inset rings, triangulated.  manifold3d then checks the mesh."""
    rings = [np.asarray(r, dtype=float) for r in outline.rings]
    insets = [inset_ring(r, chamfer) for r in rings]
    levels = (0.0, chamfer, thickness - chamfer, thickness)
    verts, tris, base = [], [], 0
    for ring, inset in zip(rings, insets):
        n = len(ring)
        for z, pts in zip(levels, (inset, ring, ring, inset)):
            verts.append(np.column_stack([pts, np.full(n, z)]))
        k = np.arange(n)
        k1 = (k + 1) % n
        for level in range(3):
            lo, hi = base + level * n, base + (level + 1) * n
            # outward faces: material is to the left of the ring's direction
            tris.append(np.column_stack([lo + k, lo + k1, hi + k1]))
            tris.append(np.column_stack([lo + k, hi + k1, hi + k]))
        base += 4 * n
    cap = m3d.triangulate([np.asarray(r) for r in insets])
    starts = np.cumsum([0] + [4 * len(r) for r in rings])[:-1]
    lengths = [len(r) for r in rings]
    # map the triangulation's indices (rings concatenated) to the bottom and top levels
    owner = np.repeat(np.arange(len(rings)), lengths)
    local = np.concatenate([np.arange(n) for n in lengths])
    bottom = starts[owner] + local
    top = starts[owner] + 3 * np.repeat(lengths, lengths) + local
    cap = np.asarray(cap)
    tris.append(bottom[cap][:, ::-1])
    tris.append(top[cap])
    mesh = m3d.Mesh64(vert_properties=np.vstack(verts), tri_verts=np.vstack(tris).astype(np.uint64))
    return m3d.Manifold(mesh)


def _normals(v: np.ndarray, t: np.ndarray) -> np.ndarray:
    n = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0, length, 1.0)


def write_stl(path: Path, solid: Solid) -> int:
    """Binary STL (mm, float32); returns the triangle count."""
    v, t = solid.vertices, solid.triangles
    record = np.zeros(len(t), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    record["n"] = _normals(v, t)
    record["v"] = v[t]
    header = f"gearcad binary STL, mm: {solid.name}".encode("ascii", "replace")[:80].ljust(80, b" ")
    with path.open("wb") as fh:
        fh.write(header)
        fh.write(struct.pack("<I", len(t)))
        fh.write(record.tobytes())
    return len(t)


@dataclass(frozen=True)
class SolidItem:
    """A solid placed in a scene: turned by ``angle`` rad about z, then moved by ``offset``."""

    solid: Solid
    angle: float = 0.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)


_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    "</Types>\n"
)
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    "</Relationships>\n"
)


def _xml_name(name: str) -> str:
    return name.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;").replace(">", "&gt;")


def _model(items: list[SolidItem]) -> str:
    out = io.StringIO()
    out.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    out.write(
        '<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n'
    )
    out.write('<metadata name="Application">gearcad</metadata>\n<resources>\n')
    for k, item in enumerate(items, 1):
        s = item.solid
        out.write(f'<object id="{k}" type="model" name="{_xml_name(s.name)}"><mesh><vertices>\n')
        out.write(s.xml)
        out.write("</triangles></mesh></object>\n")
    out.write("</resources>\n<build>\n")
    for k, item in enumerate(items, 1):
        c, s_ = np.cos(item.angle), np.sin(item.angle)
        tx, ty, tz = item.offset
        m = [c, s_, 0.0, -s_, c, 0.0, 0.0, 0.0, 1.0, tx, ty, tz]
        out.write(f'<item objectid="{k}" transform="{" ".join(f"{v:.9f}" for v in m)}"/>\n')
    out.write("</build>\n</model>\n")
    return out.getvalue()


def write_3mf(path: Path, items: list[SolidItem]) -> int:
    """3MF package (mm) with one object per item placed by its transform; returns triangles."""
    # deflate level 1: a third of the default's time for a few percent more bytes
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=1) as z:
        for name, text in (
            ("[Content_Types].xml", _CONTENT_TYPES),
            ("_rels/.rels", _RELS),
            ("3D/3dmodel.model", _model(items)),
        ):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, text.encode("utf-8"), compresslevel=1)
    return sum(i.solid.triangle_count for i in items)
