"""Meshes are optional: a URDF whose mesh files are missing still loads, with stand-ins.

Users' URDFs often come without their meshes, or with ``package://`` URIs that point into a ROS
workspace they do not have. Meshes change nothing in the dynamics (the inertias are in the URDF)
but Pinocchio refuses a URDF whose mesh it cannot open. :func:`with_available_meshes` rewrites
the URDF text before Pinocchio reads it: every mesh is resolved (``package://`` against the
package directories, relative paths against the URDF's directory) and written as an absolute
path; a mesh that cannot be found is replaced — a visual by the link's primitive collision
shape when it has one, otherwise (and for a collision) by the box of the link's inertia (the
uniform box with the same principal moments: a² = 6 (I_y + I_z − I_x) / m and cyclically,
from I_x = m (b² + c²) / 12, e.g. Meriam & Kraige, *Engineering Mechanics: Dynamics*, App. B), or
dropped when the link has no inertia — each with a note.
"""

from __future__ import annotations

import copy
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import numpy as np

PRIMITIVES = ("box", "cylinder", "sphere", "capsule")
"""URDF geometry elements that need no file."""


def resolve_mesh(filename: str, urdf_dir: Path, package_dirs: Sequence[Path]) -> Path | None:
    """The file a URDF mesh ``filename`` names, or None when it does not exist.

    ``package://pkg/rest`` is looked up as ``<dir>/pkg/rest`` and ``<dir>/rest`` in each package
    directory (and the URDF's directory and its parents, where ROS packages usually sit);
    ``file://`` and plain paths as given, relative ones against the URDF's directory.
    """
    if filename.startswith("package://"):
        rel = filename[len("package://"):]
        rest = rel.partition("/")[2]
        roots = [*package_dirs, urdf_dir, *urdf_dir.parents]
        for root in roots:
            for candidate in (Path(root) / rel, Path(root) / rest):
                if candidate.is_file():
                    return candidate.resolve()
        return None
    path = Path(filename[len("file://"):] if filename.startswith("file://") else filename)
    path = path if path.is_absolute() else urdf_dir / path
    return path.resolve() if path.is_file() else None


def with_available_meshes(urdf_text: str, urdf_dir: Path, package_dirs: Sequence[Path]
                          ) -> tuple[str, list[str]]:
    """The URDF with every mesh resolved to an absolute path or replaced (module docstring).

    Args:
        urdf_text: The URDF's XML.
        urdf_dir: Its directory (relative mesh paths start there).
        package_dirs: Where ``package://`` URIs resolve.

    Returns:
        The rewritten XML and one note per replaced or dropped mesh.
    """
    root = ET.fromstring(urdf_text)
    notes: list[str] = []
    for link in root.iter("link"):
        for tag in ("visual", "collision"):
            for element in list(link.findall(tag)):
                mesh = element.find("geometry/mesh")
                if mesh is None:
                    continue
                found = resolve_mesh(mesh.get("filename", ""), urdf_dir, package_dirs)
                if found is not None:
                    mesh.set("filename", str(found))
                    continue
                notes.append(_replace(link, element, tag, mesh.get("filename", "")))
    return ET.tostring(root, encoding="unicode"), notes


MISSING_COLLISION = "collision mesh"
"""How the note of a replaced collision mesh names it (``link L: collision mesh F not found;
…``): the run's warnings repeat those notes (:mod:`hexaleg.scenario.run_warnings`)."""


def _replace(link: ET.Element, element: ET.Element, tag: str, filename: str) -> str:
    """Replace a missing mesh in ``element`` (a visual or collision of ``link``); the note."""
    name = link.get("name", "?")
    if tag == "visual":
        for collision in link.findall("collision"):
            shape = collision.find("geometry")
            if shape is not None and len(shape) and shape[0].tag in PRIMITIVES:
                _set_geometry(element, copy.deepcopy(shape[0]), collision.find("origin"))
                return (f"link {name}: visual mesh {filename} not found; drawn with its "
                        f"collision {shape[0].tag}")
    box = _inertia_box(link)
    if box is None:
        link.remove(element)
        return f"link {name}: {tag} mesh {filename} not found and no inertia to size a box; dropped"
    size, origin = box
    shape = ET.Element("box", size=" ".join(f"{v:.6g}" for v in size))
    _set_geometry(element, shape, origin)
    return (f"link {name}: {tag} mesh {filename} not found; replaced by its inertia box "
            f"{' × '.join(f'{v:.3g}' for v in size)} m")


def _set_geometry(element: ET.Element, shape: ET.Element, origin: ET.Element | None) -> None:
    for child in list(element):
        if child.tag in ("geometry", "origin"):
            element.remove(child)
    if origin is not None:
        element.insert(0, copy.deepcopy(origin))
    geometry = ET.SubElement(element, "geometry")
    geometry.append(shape)


def _inertia_box(link: ET.Element) -> tuple[np.ndarray, ET.Element | None] | None:
    """Sides (m) of the uniform box with the link's moments about the axes of its inertial frame
    (products of inertia ignored: a drawing, not dynamics), and the inertial origin."""
    inertial = link.find("inertial")
    if inertial is None or inertial.find("mass") is None or inertial.find("inertia") is None:
        return None
    mass = float(inertial.find("mass").get("value", "0"))  # type: ignore[union-attr]
    i = inertial.find("inertia")
    assert i is not None
    moments = np.array([float(i.get(k, "0")) for k in ("ixx", "iyy", "izz")])
    if mass <= 0 or not np.all(np.isfinite(moments)):
        return None
    total = moments.sum()
    sides = np.sqrt(np.maximum(6.0 * (total - 2.0 * moments) / mass, 0.0))
    if not np.any(sides > 0):
        return None
    return np.maximum(sides, 1e-3), inertial.find("origin")
