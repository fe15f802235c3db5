"""Each finished stage of a design kept on disk, so that a killed or failed run resumes there.

:class:`StageFiles` is a hidden folder in the design's output directory
(``.hexaleg-design-stages``) that :class:`~hexaleg.design.chain.chain.DesignChain` writes as it
goes: one file a finished stage (``<stage>.pickle``, written whole through
:func:`hexaleg.config.write_file`: the old file or the new one, never half) and ``run.json``,
the key of the run that wrote them (:func:`run_key`). Guarantees:

* **one run's stages**: a folder whose key is not this run's (another robot, config, log,
  controller, hexaleg's code) is emptied before the first stage is written, so two runs never
  mix; the output folder's lock (:class:`~hexaleg.outputs.directory.OutputFolder`) keeps a
  second run out while one writes;
* **the robot is not in them**: every :class:`~hexaleg.robot.loaded.Robot` a stage refers to
  (the run's own, or a copy of it that came back from a forked process, as the co-design's
  spring rules' does) is written as a reference to the run's robot keyed by the robot's content
  (:func:`robot_key`), and so are the run's robot's Pinocchio model, data and geometry; the
  reader resolves it to this run's robot with that key, and a file that names a robot the run
  does not have is not read (:mod:`pickle`'s persistent ids, as :mod:`hexaleg.parallel.forked`
  does by address). Other objects of the run (the prepared nominal gait, recomputed first: a
  tenth of a second to a second, deterministic) are referred to by name;
* **only hexaleg's own data is read back**: the reader admits the classes of hexaleg, NumPy and
  a few built-in containers, nothing else (the Python docs' "Restricting Globals" recipe), and a
  file it cannot read is computed again;
* **cleared when the design is whole**: the command removes the folder once a design with every
  stage is published; a failed stage leaves the stages before it for the next run.

A stage file is a cache of this run's computation, not a result to exchange: the results are
``design.json`` and the page.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import io
import json
import pickle
import shutil
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from hexaleg.config import write_file
from hexaleg.design.chain.config import DesignParams
from hexaleg.design.fold import Mission
from hexaleg.robot.loaded import Robot
from hexaleg.scenario.scenario import Scenario

FOLDER = ".hexaleg-design-stages"
"""The hidden folder of a design's finished stages in its output directory."""
KEY_FILE = "run.json"
"""The file in :data:`FOLDER` holding the key of the run whose stages it keeps."""

_ALLOWED_MODULES = ("hexaleg.", "numpy", "collections", "copyreg", "datetime", "fractions")
"""Modules whose globals a stage file may name (:class:`_Reader`)."""
_ALLOWED_BUILTINS = frozenset({"complex", "dict", "float", "frozenset", "int", "list", "set",
                               "slice", "str", "tuple", "bytes", "bytearray", "range", "bool",
                               "object"})
"""Built-in names a stage file may name (containers and numbers, nothing that runs code)."""


def _file_digest(path: Path | None) -> str:
    """SHA-256 of a file's content, or "" when there is none or it cannot be read."""
    if path is None:
        return ""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return ""


@functools.cache
def _code_digest() -> str:
    """SHA-256 over hexaleg's own source files (their paths and contents, in sorted order): a
    stage file kept by other code, an upgrade or an edit in a development checkout, is never
    read back (the version alone would not change with an edit)."""
    root = Path(__file__).resolve().parents[2]  # the hexaleg package
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def run_key(scenario: Scenario, design: DesignParams, mission: Mission) -> str:
    """What makes two design runs the same computation, as a hex digest
    (:func:`scenario_key`): the scenario, the ``[design]`` settings as the chain reads them
    (the controller among them) and the ``[mission]``."""
    return scenario_key(scenario, {"design": repr(design), "mission": repr(mission)})


def scenario_key(scenario: Scenario, settings: Mapping[str, str]) -> str:
    """What makes two runs of a command the same computation, as a hex digest: hexaleg's code
    (its source files' digest), the robot (its name or description file, and the content of
    that file, its URDF and SRDF), the config's tables, the log and its cycle (the log's
    content) and the command's ``settings`` (name → their ``repr``)."""
    desc = scenario.description
    robot_file = Path(scenario.robot)
    parts = {
        "hexaleg": _code_digest(),
        "robot": scenario.robot,
        "robot_file": _file_digest(robot_file) if robot_file.suffix == ".toml" else "",
        "urdf": _file_digest(desc.urdf_path),
        "srdf": _file_digest(desc.srdf_path),
        "tables": scenario.tables,
        "run": scenario.data(),
        "log": _file_digest(Path(scenario.log)) if scenario.log else "",
        **settings,
    }
    text = json.dumps(parts, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


_ROBOT_PARTS = ("model", "data", "visual_model", "collision_model")
"""A robot's Pinocchio objects, which a stage refers to as parts of the run's robot."""


_SHAPE = ("halfSide", "radius", "halfLength")
"""The parameters of a geometry's primitive shape (box, sphere, cylinder, capsule, cone)."""


def _geometry(model: Any) -> bytes:
    """A geometry model as what defines it: each object's name, parent joint and frame,
    placement, mesh file and scale, shape type and primitive parameters (not the pickled model:
    a collision check fills its shapes' bounding boxes in place)."""
    parts = []
    for g in model.geometryObjects:
        shape = g.geometry
        parts.append(repr((g.name, g.parentJoint, g.parentFrame, str(g.meshPath),
                           np.asarray(g.meshScale).tolist(), g.placement.homogeneous.tolist(),
                           type(shape).__name__,
                           [np.asarray(getattr(shape, p)).tolist() for p in _SHAPE
                            if hasattr(shape, p)])))
    return "\n".join(parts).encode()


def robot_key(robot: Robot) -> str:
    """The robot's content as a hex digest: each of its attributes but its scratch ``data``
    (the Pinocchio model, the legs, poses, feet, soles, heading, the files it was loaded from;
    the geometry models as :func:`_geometry` describes them), pickled one by one in the order
    of their names. The same for the robot loaded again in another process, for a pickled copy
    of it and after a simulation used it; another robot, or the same one with any attribute
    changed, has another."""
    h = hashlib.sha256()
    for name, value in sorted(vars(robot).items()):
        if name == "data":
            continue
        text = _geometry(value) if name in ("visual_model", "collision_model") else \
            pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        h.update(name.encode())
        h.update(hashlib.sha256(text).digest())
    return h.hexdigest()


def _run_robots(shared: Mapping[str, object]) -> dict[str, Robot]:
    """The run's robots among ``shared``'s objects, by :func:`robot_key`."""
    return {robot_key(o): o for o in shared.values() if isinstance(o, Robot)}


class _Writer(pickle.Pickler):
    """Writes a robot as ``("robot", key)``, a part of the run's robot as ``("robot", key,
    part)``, a shared object as its name."""

    def __init__(self, file: io.BytesIO, shared: Mapping[str, object]) -> None:
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self._ids: dict[int, tuple[object, Any]] = {
            id(o): (o, name) for name, o in shared.items() if not isinstance(o, Robot)}
        for key, robot in _run_robots(shared).items():
            self._ids[id(robot)] = (robot, ("robot", key))
            for part in _ROBOT_PARTS:
                obj = getattr(robot, part)
                self._ids[id(obj)] = (obj, ("robot", key, part))
        self._keys: dict[int, tuple[Robot, str]] = {}  # robot keys computed, by address

    def persistent_id(self, obj: object) -> Any:
        obj_pid = self._ids.get(id(obj))
        if obj_pid is not None and obj_pid[0] is obj:
            return obj_pid[1]
        if isinstance(obj, Robot):  # another copy of a robot: its key, once
            keyed = self._keys.get(id(obj))
            if keyed is None or keyed[0] is not obj:
                keyed = self._keys[id(obj)] = (obj, robot_key(obj))
            return ("robot", keyed[1])
        return None


class _Reader(pickle.Unpickler):
    def __init__(self, file: io.BytesIO, shared: Mapping[str, object]) -> None:
        super().__init__(file)
        self._shared = shared
        self._robots: dict[str, Robot] | None = None  # keyed when a file names a robot

    def persistent_load(self, pid: Any) -> object:
        if isinstance(pid, tuple) and pid[:1] == ("robot",) and len(pid) in (2, 3):
            if self._robots is None:
                self._robots = _run_robots(self._shared)
            robot = self._robots.get(pid[1])
            if robot is None:
                raise pickle.UnpicklingError("a robot this run does not have")
            if len(pid) == 2:
                return robot
            if pid[2] not in _ROBOT_PARTS:
                raise pickle.UnpicklingError(f"unknown robot part {pid[2]!r}")
            return getattr(robot, pid[2])
        if not isinstance(pid, str) or pid not in self._shared:
            raise pickle.UnpicklingError(f"unknown shared object {pid!r}")
        return self._shared[pid]

    def find_class(self, module: str, name: str) -> Any:
        if (module == "builtins" and name in _ALLOWED_BUILTINS) or (
                module.startswith(_ALLOWED_MODULES)):
            return super().find_class(module, name)
        raise pickle.UnpicklingError(f"{module}.{name} is not read from a stage file")


class StageFiles:
    """A design's finished stages in ``directory`` (module docstring).

    Args:
        directory: The folder (:data:`FOLDER` in the output directory); made on the first
            stage written.
        key: This run's key (:func:`run_key`).

    Attributes:
        directory: The folder. key: The run's key. written: The stages written or read by this
            run, in order.
    """

    def __init__(self, directory: str | Path, key: str) -> None:
        self.directory = Path(directory)
        self.key = key
        self.written: list[str] = []
        self._mine = self._read_key() == key

    def _read_key(self) -> str | None:
        try:
            data = json.loads((self.directory / KEY_FILE).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return data.get("key") if isinstance(data, dict) else None

    def load(self, stage: str, shared: Mapping[str, object]) -> Any | None:
        """The stage's value as this run's earlier process left it, or None when there is none
        (another run's folder, no file, a file that cannot be read or that names a robot not
        among ``shared``'s).

        Args:
            stage: The stage's name.
            shared: This run's objects the stage may refer to, by name; the robots among them
                are the run's robots, which every robot the file refers to is read back as
                (by :func:`robot_key`).
        """
        if not self._mine:
            return None
        try:
            raw = (self.directory / f"{stage}.pickle").read_bytes()
            value = _Reader(io.BytesIO(raw), shared).load()
        except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError,
                IndexError, TypeError, ValueError):
            return None
        self.written.append(stage)
        return value

    def save(self, stage: str, value: Any, shared: Mapping[str, object]) -> None:
        """Write the stage's value whole; the folder made, or emptied of another run's stages,
        first. ``shared`` as :meth:`load`'s: its objects are written as their names, and every
        robot ``value`` refers to (the run's or a copy) as a reference keyed by its content."""
        if not self._mine:
            self.clear()
            self.directory.mkdir(parents=True, exist_ok=True)
            write_file(self.directory / KEY_FILE, json.dumps({"key": self.key}),
                       "the design's stage key")
            self._mine = True
        out = io.BytesIO()
        _Writer(out, shared).dump(value)
        write_file(self.directory / f"{stage}.pickle", out.getvalue(), f"the {stage} stage")
        self.written.append(stage)

    def clear(self) -> None:
        """Remove the folder and what it holds (a link there is removed, not followed)."""
        if self.directory.is_symlink():
            with contextlib.suppress(OSError):
                self.directory.unlink()
        else:
            shutil.rmtree(self.directory, ignore_errors=True)
        self._mine = False


__all__ = ["FOLDER", "KEY_FILE", "StageFiles", "robot_key", "run_key", "scenario_key"]
