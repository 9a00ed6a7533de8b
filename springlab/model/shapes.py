"""A URDF link's geometry, as the points that bound it: where a spring may be attached on a real arm.

A URDF gives each link's shape twice: ``<collision>`` (what a planner keeps clear) and
``<visual>`` (what a viewer draws). springlab reads the collision shapes (the visual ones where a
link has none): boxes, cylinders, spheres, capsules and meshes (STL, OBJ, COLLADA, read with
trimesh, a well-kept mesh library, rather than three hand-written readers). Each shape becomes
points in its link's frame whose convex hull is the shape: a box's corners, a mesh's hull
vertices, and for round shapes points on their rims and poles (:data:`ROUND_POINTS` per circle;
the hull then lies inside the shape by at most 1 - cos(pi / ROUND_POINTS) of its radius, 0.12 %).

Mesh paths are resolved as ROS does (:func:`resolve_mesh`): ``package://PKG/rest`` in the
folders given, in a folder named PKG above the URDF (or beside one of those folders), in
``ROS_PACKAGE_PATH`` and under ``AMENT_PREFIX_PATH``'s ``share``; an absolute path or ``file://``
path as it is; a relative one (also after ``file://``) from the URDF's folder. A COLLADA mesh in
other units (``<unit meter="0.001">``) is converted to metres, as ROS's viewers read it (Pinocchio's
loader keeps the numbers as they are: such a file is where the two differ). A mesh file over
:data:`MAX_MESH_BYTES` is skipped. A mesh that cannot be found or read is named in a note and left
out (the link then bounds springs by its other shapes, or by the default reach):
:class:`~springlab.errors.MeshError`, caught by the reader.

Refused with the URDF (:class:`RefusedMeshError`, which the reader passes on), since either would
put a false outline where springs attach: a ``package://`` path whose normalised rest leaves its
package's folder (``package://pkg/../../x.stl``) or that names no package (``package://../x.stl``),
and a COLLADA unit that is not a finite positive number of metres (``meter="-1"`` would mirror
the mesh, ``meter="0"`` shrink it to a point).
"""

from __future__ import annotations

import functools
import math
import os
import posixpath
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from springlab.errors import MeshError, SpringlabError
from springlab.model.rotations import rot_rpy

ROUND_POINTS = 64
"""Points per circle on a cylinder's rims, a sphere's or capsule's circles."""


class RefusedMeshError(MeshError):
    """A mesh the URDF names that would give its link a false outline (a ``package://`` path out of
    its package, a COLLADA unit that is not a length): the URDF is refused, where a mesh that cannot
    be found or read is only left out with a note."""


@dataclass(frozen=True)
class Shape:
    """One ``<collision>`` (or ``<visual>``) geometry of a link.

    :ivar kind: 'box', 'cylinder', 'sphere', 'capsule' or 'mesh'
    :ivar origin: (4, 4) the shape's frame in its link's frame
    :ivar size: box: (x, y, z) m; cylinder, capsule: (radius, length) m; sphere: (radius,) m
    :ivar filename: a mesh's file name as the URDF writes it
    :ivar scale: a mesh's scale per axis
    """

    kind: str
    origin: np.ndarray
    size: tuple = ()
    filename: str = ""
    scale: tuple = (1.0, 1.0, 1.0)


def _numbers(text, count, default):
    try:
        values = [float(v) for v in (text or "").split()]
    except ValueError:
        return None
    if not values:
        return tuple(default) if default is not None else None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        return None
    return tuple(values)


def _frame(element) -> np.ndarray | None:
    T = np.eye(4)
    origin = element.find("origin")
    if origin is not None:
        xyz = _numbers(origin.get("xyz"), 3, (0, 0, 0))
        rpy = _numbers(origin.get("rpy"), 3, (0, 0, 0))
        if xyz is None or rpy is None:
            return None
        T[:3, 3], T[:3, :3] = xyz, rot_rpy(*rpy)
    return T


def link_shapes(text: str) -> tuple[dict, list]:
    """Each link's shapes in a URDF text: link name -> (collision shapes, visual shapes), each a
    tuple of :class:`Shape` (links with neither are left out), and notes on what was skipped (an
    unknown geometry, a missing or malformed size, scale or origin: named)."""
    if not isinstance(text, str):
        raise SpringlabError(f"text must be a URDF's text (a string), got {type(text).__name__}")
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        raise SpringlabError(f"text is not valid XML: {err}") from None
    out, notes = {}, []
    for link in root.findall("link"):
        name = link.get("name")
        found = []
        for tag in ("collision", "visual"):
            shapes = []
            for element in link.findall(tag):
                geometry = element.find("geometry")
                if geometry is None or len(geometry) == 0:
                    continue
                g = geometry[0]
                T = _frame(element)
                shape = None if T is None else _shape(g, T)
                if g.tag not in KINDS:
                    notes.append(f"link {name!r}: a <{tag}> <{g.tag}> was skipped (springlab reads "
                                 f"{', '.join(KINDS)})")
                elif shape is None:
                    what = "filename" if g.tag == "mesh" and not g.get("filename") else "size, scale or origin"
                    notes.append(f"link {name!r}: a <{tag}> <{g.tag}> with a missing or malformed {what} was skipped")
                else:
                    shapes.append(shape)
            found.append(tuple(shapes))
        if any(found):
            out[name] = tuple(found)
    return out, notes


KINDS = ("box", "cylinder", "sphere", "capsule", "mesh")
"""The URDF geometries springlab reads."""


def _shape(g, T) -> Shape | None:
    if g.tag == "box":
        size = _numbers(g.get("size"), 3, None)
        return None if size is None or min(size) < 0 else Shape("box", T, size)
    if g.tag in ("cylinder", "capsule"):
        r, length = _numbers(g.get("radius"), 1, None), _numbers(g.get("length"), 1, None)
        return None if r is None or length is None or r[0] < 0 or length[0] < 0 else Shape(g.tag, T, r + length)
    if g.tag == "sphere":
        r = _numbers(g.get("radius"), 1, None)
        return None if r is None or r[0] < 0 else Shape("sphere", T, r)
    if g.tag == "mesh" and g.get("filename"):
        scale = _numbers(g.get("scale"), 3, (1, 1, 1))
        return None if scale is None else Shape("mesh", T, (), g.get("filename"), scale)
    return None


def resolve_mesh(filename: str, folder: Path | None, package_dirs=()) -> Path | None:
    """The file a URDF's mesh name points to, or None (see the module docstring for the search).

    :raises RefusedMeshError: for a ``package://`` path that names no package or whose rest, once
        normalised (``a/../b`` is ``b``; ROS joins it to the package's folder, so leading slashes
        stay inside), leaves the package's folder
    """
    if filename.startswith("file://"):
        filename = filename[len("file://"):]  # an absolute path, or (loosely) one relative to the URDF
    if not filename.startswith("package://"):
        path = Path(filename) if Path(filename).is_absolute() or folder is None else Path(folder) / filename
        return path if path.is_file() else None
    package, _, rest = filename[len("package://"):].lstrip("/").partition("/")
    rest = posixpath.normpath(rest.lstrip("/") or ".")
    if package in ("", ".", "..") or rest == ".." or rest.startswith("../"):
        why = (f"names no package ({package!r})" if package in ("", ".", "..") else
               f"leaves the folder of package {package!r} (its path normalised: {rest!r})")
        raise RefusedMeshError(f"mesh {filename!r} {why}: a package:// path is package://PACKAGE/PATH within the "
                               "package's folder; give the mesh's path inside its package", filename=filename)
    candidates = []
    for d in map(Path, package_dirs):
        candidates += [d / package / rest, d / rest] if d.name == package else [d / package / rest]
    if folder is not None:
        for above in (Path(folder).resolve(), *Path(folder).resolve().parents):
            candidates += [above / rest] if above.name == package else [above / package / rest]
    for d in filter(None, os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep)):
        candidates += [Path(d) / package / rest, Path(d) / rest] if Path(d).name == package else [Path(d) / package / rest]
    for d in filter(None, os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep)):
        candidates.append(Path(d) / "share" / package / rest)
    return next((c for c in candidates if c.is_file()), None)


def _circle(radius: float, z: float) -> np.ndarray:
    t = np.linspace(0.0, 2 * np.pi, ROUND_POINTS, endpoint=False)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t), np.full_like(t, z)])


def _ball(radius: float, centre_z: float = 0.0, half: int = 0) -> np.ndarray:
    """Points on a sphere (half = 0), or its upper (1) or lower (-1) half, centred at z = centre_z."""
    rings = [0.0] + [k * np.pi / 8 for k in range(1, 4)]
    pts = [np.array([[0.0, 0.0, centre_z + radius]]), np.array([[0.0, 0.0, centre_z - radius]])]
    for a in rings:
        for s in ((1, -1) if half == 0 else (half,)):
            pts.append(_circle(radius * math.cos(a), centre_z + s * radius * math.sin(a)))
    return np.vstack(pts)


MAX_MESH_BYTES = 64 * 2**20
"""The largest mesh file springlab reads (64 MiB; a link's scan of millions of triangles bounds it
no better than its hull): a larger one is skipped with a note."""


def _mesh_points(path: Path, scale, notes: list | None = None) -> np.ndarray:
    size = path.stat().st_size
    if size > MAX_MESH_BYTES:
        raise MeshError(f"{path}: {size / 2**20:.0f} MiB, more than springlab reads ({MAX_MESH_BYTES / 2**20:.0f} "
                        "MiB): give the link a simpler collision mesh", filename=str(path))
    points, units = _hull_of(str(path), path.stat().st_mtime_ns, size, tuple(float(v) for v in np.ravel(scale)))
    if units and notes is not None:
        notes.append(f"mesh {path.name} is in {units}: converted to metres")
    return points


@functools.lru_cache(maxsize=64)
def _mesh_of(path: str, mtime_ns: int, size: int, scale: tuple) -> tuple[np.ndarray, np.ndarray, str | None]:
    """A mesh file's vertices (m, scaled, read-only), triangles (vertex indices, read-only) and the unit
    it was converted from (None: metres), read once per file version (path, modification time, size)
    and scale."""
    import trimesh

    if path.lower().endswith(".dae"):
        _check_collada_unit(path)
    mesh = trimesh.load(path, force="mesh", process=False)
    units = getattr(mesh, "units", None)
    if units and units != "meters":  # a COLLADA file's <unit meter="0.001">: its own unit, as ROS's viewers take it
        mesh.convert_units("meters")
    else:
        units = None
    v = np.asarray(mesh.vertices, dtype=float) * np.asarray(scale, dtype=float)
    if len(v) == 0:
        raise MeshError(f"{path}: no vertices (an empty or unreadable mesh)", filename=path)
    if not np.all(np.isfinite(v)):
        raise MeshError(f"{path}: vertices that are not finite numbers", filename=path)
    faces = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 3)
    for a in (v, faces):
        a.setflags(write=False)
    return v, faces, units


@functools.lru_cache(maxsize=256)
def _hull_of(path: str, mtime_ns: int, size: int, scale: tuple) -> tuple[np.ndarray, str | None]:
    """A mesh file's hull points (m, read-only) and the unit it was converted from (None: metres),
    read once per file version (path, modification time, size) and scale: an arm's meshes are read
    again each time the arm is (the SO-101's take about a second)."""
    from scipy.spatial import ConvexHull, QhullError

    v, _, units = _mesh_of(path, mtime_ns, size, scale)
    if len(v) > 100_000:  # a scan's unmerged vertices: the hull needs each point once
        v = np.unique(v, axis=0)
    try:
        out = v[ConvexHull(v).vertices]
    except (QhullError, ValueError):  # flat or degenerate: its points bound it as well
        out = v
    out.setflags(write=False)
    return out, units


def _check_collada_unit(path: str) -> None:
    """Refuse a COLLADA file whose ``<asset><unit meter="...">`` (metres per unit of its numbers) is not
    a finite positive number. The file is read up to the end of its own ``<asset>`` (its first
    element); a file that is not XML is left to the mesh reader, which names it as unreadable."""
    depth, in_asset = 0, False
    with open(path, "rb") as file:
        try:
            for event, element in ET.iterparse(file, events=("start", "end")):
                tag = element.tag.rpartition("}")[2]
                if event == "start":
                    depth += 1
                    in_asset = tag == "asset" if depth == 2 else in_asset
                    meter = element.get("meter") if depth == 3 and in_asset and tag == "unit" else None
                    if meter is not None and not _positive_number(meter):
                        raise RefusedMeshError(
                            f"mesh {path}: its COLLADA unit <unit meter=\"{meter}\"> is not a finite positive "
                            "number of metres (a negative one would mirror the mesh, zero shrink it to a point): "
                            "give the file's unit in metres, e.g. <unit meter=\"0.001\"/> for millimetres, or "
                            "leave the <unit> out for metres", filename=path)
                    continue
                depth -= 1
                if depth == 1:
                    if tag == "asset":
                        return  # the file's own asset read: no unit (metres), or a good one
                    element.clear()  # an asset out of place: read on, keeping nothing
        except ET.ParseError:
            return


def _positive_number(text: str) -> bool:
    try:
        value = float(text)
    except ValueError:
        return False
    return math.isfinite(value) and value > 0


def shape_points(shape: Shape, folder: Path | None = None, package_dirs=(), notes: list | None = None) -> np.ndarray:
    """Points (m, in the link's frame) whose convex hull is the shape, (k, 3). A mesh that cannot be
    found or read raises :class:`~springlab.errors.MeshError` (``found`` says which), one that would
    give a false outline :class:`RefusedMeshError` (see the module docstring); a mesh in
    other units than metres is converted, with a line added to ``notes``."""
    if shape.kind == "box":
        h = np.asarray(shape.size) / 2
        local = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h
    elif shape.kind == "cylinder":
        r, length = shape.size
        local = np.vstack([_circle(r, -length / 2), _circle(r, length / 2)])
    elif shape.kind == "capsule":
        r, length = shape.size
        local = np.vstack([_ball(r, length / 2, 1), _ball(r, -length / 2, -1)])
    elif shape.kind == "sphere":
        local = _ball(shape.size[0])
    else:
        path = resolve_mesh(shape.filename, folder, package_dirs)
        if path is None:
            raise MeshError(f"mesh {shape.filename!r} not found: give the folder that holds its package",
                            filename=shape.filename, found=False)
        try:
            local = _mesh_points(path, shape.scale, notes)
        except MeshError:
            raise
        except Exception as err:  # trimesh raises many kinds on a file it cannot read
            raise MeshError(f"{path}: {err}", filename=str(path)) from None
    return local @ shape.origin[:3, :3].T + shape.origin[:3, 3]


@dataclass(frozen=True)
class Solid:
    """One collision shape of a body, as the collision check reads it (:mod:`springlab.design.collision`).

    :ivar link: the URDF link it belongs to
    :ivar kind: 'box', 'cylinder', 'sphere', 'capsule' or 'mesh'
    :ivar frame: (4, 4) the shape's frame in its body's frame (a cylinder's and a capsule's axis its z)
    :ivar size: as :class:`Shape`'s (m); () for a mesh
    :ivar vertices: a mesh's vertices (m, the shape's frame, scale applied), (k, 3); else (0, 3)
    :ivar faces: a mesh's triangles (indices into ``vertices``), (t, 3); else (0, 3)
    """

    link: str
    kind: str
    frame: np.ndarray
    size: tuple = ()
    vertices: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)), repr=False)
    faces: np.ndarray = field(default_factory=lambda: np.zeros((0, 3), dtype=np.int64), repr=False)


def shape_solid(shape: Shape, link: str, T_body: np.ndarray, folder: Path | None = None, package_dirs=()) -> Solid:
    """The shape as a :class:`Solid` of the body whose frame holds its link at ``T_body`` (4, 4). A mesh
    is read as :func:`shape_points` reads it (the same file, units and scale; the same errors)."""
    frame = np.asarray(T_body, dtype=float) @ shape.origin
    if shape.kind != "mesh":
        return Solid(link, shape.kind, frame, tuple(float(v) for v in shape.size))
    path = resolve_mesh(shape.filename, folder, package_dirs)
    if path is None:
        raise MeshError(f"mesh {shape.filename!r} not found: give the folder that holds its package",
                        filename=shape.filename, found=False)
    try:
        v, faces, _ = _mesh_of(str(path), path.stat().st_mtime_ns, path.stat().st_size,
                               tuple(float(x) for x in np.ravel(shape.scale)))
    except MeshError:
        raise
    except Exception as err:  # trimesh raises many kinds on a file it cannot read
        raise MeshError(f"{path}: {err}", filename=str(path)) from None
    return Solid(link, "mesh", frame, (), v, faces)
