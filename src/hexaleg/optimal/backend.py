"""The Crocoddyl this package runs on, imported once and checked to read Pinocchio's models.

Crocoddyl and Pinocchio are compiled separately and share C++ structures: a Crocoddyl built
against one Pinocchio release reads another's ``Model`` by the layout it was compiled with.
crocoddyl 3.2.1 (PyPI) on pin 4.1.0 imports cleanly and then reads every frame's placement as
garbage — a foot contact at the wrong point of the leg, or a ``MemoryError`` — while on pin 4.0.0
it reads them right (measured; ``pyproject.toml``'s ``optimal`` extra pins pin 4.0.x). The cause is
in the headers: pin 4.1's ``ModelTpl`` (``pinocchio/src/multibody/model.hxx``) declares four new
members — ``lowerAccelerationLimit``, ``upperAccelerationLimit``, ``lowerJerkLimit``,
``upperJerkLimit`` — between ``positionLimitMargin`` and ``frames``, so code compiled against 4.0's
layout reads ``frames`` (and every member after it: ``supports``, ``gravity``, ``name``) 64 bytes
off, while the members before (joints, inertias, limits) still read right. No Python-side
workaround reaches inside Crocoddyl's compiled residuals; only a crocoddyl built against pin 4.1
would. So before
any problem is built, :func:`crocoddyl_module` builds a contact on every frame of a Pinocchio
sample model and compares the placement Crocoddyl read (``ContactData3D.jMf``) with Pinocchio's.

The crocoddyl wheel is compiled with GNU OpenMP, and Eigen then splits every large enough matrix
product over ``omp_get_max_threads()`` threads (Eigen's ``parallelize_gemm``,
``Eigen/src/Core/products/Parallelizer.h``: above 50 000 multiply-adds, e.g. box-FDDP's backward
pass on the hexapod's 48 state dimensions), whose threads then spin at the next barrier. Measured
on the default robot's 40-knot solve with springs (2 cores, load 4–6): 45 % of the CPU in
libgomp's spin-wait, 11.5 s CPU for 10 iterations on two threads against 1.9 s on one, the
iterates equal bit for bit (the products of these sizes sum each entry in one order either way).
:func:`crocoddyl_module` therefore sets the process's OpenMP threads to one
(:func:`single_threaded`); the optimal stage's independent solves run in forked processes instead
(:mod:`hexaleg.parallel.forked`), and a forked child never meets a pool of OpenMP threads its
parent made (GNU OpenMP's pool does not survive a fork).
"""

from __future__ import annotations

import ctypes
from functools import cache
from types import ModuleType
from typing import Any

import numpy as np

from hexaleg.errors import HexalegError


class BackendError(HexalegError):
    """Crocoddyl is missing, or reads Pinocchio's models wrongly (a binary mismatch)."""


PAIR = ("crocoddyl 3.2.1 with pin 4.0: the only crocoddyl wheel is compiled against pin 4.0's "
        "Model, and pin 4.1 added four joint-limit vectors before the Model's frames, so on "
        "pin 4.1 it reads every frame, and the gravity, at the wrong place")
"""The pair the ``optimal`` extra pins, and why (module docstring)."""

PROBES = 8
"""Frames added to the sample model at distinct placements (its own frames sit at the identity,
which a misreading binary could return by chance)."""


def probe_model(pinocchio: ModuleType) -> Any:
    """Pinocchio's sample humanoid with :data:`PROBES` frames at distinct, known placements."""
    model = pinocchio.buildSampleModelHumanoidRandom()
    for k in range(PROBES):
        rotation = pinocchio.rpy.rpyToMatrix(0.1 * k, -0.2 * k, 0.3)
        placement = pinocchio.SE3(rotation, np.array([0.01 * (k + 1), -0.02 * k, 0.03]))
        model.addFrame(pinocchio.Frame(f"probe{k}", 1 + k, placement,
                                       pinocchio.FrameType.OP_FRAME))
    return model


def misread_frames(crocoddyl: ModuleType, pinocchio: ModuleType) -> int:
    """How many frames of :func:`probe_model` Crocoddyl reads at another placement than
    Pinocchio's (0 for a matched pair)."""
    model = probe_model(pinocchio)
    state = crocoddyl.StateMultibody(model)
    bad = 0
    for frame in range(1, model.nframes):
        contact = crocoddyl.ContactModel3D(state, frame, np.zeros(3), pinocchio.LOCAL,
                                           state.nv - 6, np.zeros(2))
        data = contact.createData(model.createData())
        bad += not np.allclose(data.jMf.homogeneous, model.frames[frame].placement.homogeneous)
    return bad


OPENMP = "libgomp.so.1"
"""The GNU OpenMP runtime the crocoddyl and Pinocchio wheels link (module docstring)."""


def single_threaded() -> bool:
    """Set this process's OpenMP threads to one (``omp_set_num_threads(1)``, the OpenMP API,
    read by Eigen at each product; module docstring); False where no GNU OpenMP runtime
    can be loaded (then no product is split)."""
    try:
        runtime = ctypes.CDLL(OPENMP)
    except OSError:
        return False
    runtime.omp_set_num_threads(1)
    return True


@cache
def crocoddyl_module() -> ModuleType:
    """The ``crocoddyl`` module, checked (module docstring).

    Raises:
        BackendError: crocoddyl is not installed (the ``optimal`` extra), or it misreads
            Pinocchio's models; the message names both versions.
    """
    try:
        import crocoddyl
    except ImportError as err:
        raise BackendError("the optimal motion needs Crocoddyl: pip install "
                           f"\"hexaleg[optimal]\" ({PAIR})") from err
    import pinocchio

    bad = misread_frames(crocoddyl, pinocchio)
    if bad:
        raise BackendError(f"crocoddyl {crocoddyl.__version__} misreads {bad} frame placements "
                           f"of a pin {pinocchio.__version__} model (a binary mismatch): install "
                           "the pair the optimal extra pins, pip install \"hexaleg[optimal]\" "
                           f"({PAIR})")
    single_threaded()
    return crocoddyl
