"""The Crocoddyl backend: a matched pair reads every frame right; a mismatch is refused with
both versions named, never a silent wrong contact point."""

from __future__ import annotations

import types

import numpy as np
import pytest

from hexaleg.optimal import backend


def test_a_missing_crocoddyl_names_the_extra(monkeypatch):
    import builtins
    real = builtins.__import__

    def no_crocoddyl(name, *args, **kwargs):
        if name == "crocoddyl":
            raise ImportError(name)
        return real(name, *args, **kwargs)

    backend.crocoddyl_module.cache_clear()
    monkeypatch.setattr(builtins, "__import__", no_crocoddyl)
    try:
        with pytest.raises(backend.BackendError, match=r"hexaleg\[optimal\]"):
            backend.crocoddyl_module()
    finally:
        monkeypatch.undo()
        backend.crocoddyl_module.cache_clear()


def test_the_installed_pair_reads_every_frame():
    crocoddyl = pytest.importorskip("crocoddyl")
    import pinocchio
    assert backend.misread_frames(crocoddyl, pinocchio) == 0
    assert backend.crocoddyl_module() is crocoddyl


def test_a_misreading_crocoddyl_is_counted():
    """A stand-in Crocoddyl whose contact reads every placement as the identity (what the
    mismatched binary does, with garbage) is caught frame by frame."""
    import pinocchio

    class Contact:
        def __init__(self, *args):
            pass

        def createData(self, data):
            return types.SimpleNamespace(jMf=pinocchio.SE3.Identity())

    fake = types.SimpleNamespace(StateMultibody=lambda m: types.SimpleNamespace(nv=m.nv),
                                 ContactModel3D=Contact)
    model = backend.probe_model(pinocchio)
    moved = sum(not np.allclose(f.placement.homogeneous, np.eye(4))
                for f in list(model.frames)[1:])
    assert backend.misread_frames(fake, pinocchio) == moved >= backend.PROBES


def test_the_backend_runs_one_openmp_thread():
    """Eigen's split products spin on a shared machine (module docstring of the backend): the
    checked Crocoddyl leaves the process on one OpenMP thread, whatever it was set to before."""
    pytest.importorskip("crocoddyl")
    import ctypes
    try:
        runtime = ctypes.CDLL(backend.OPENMP)
    except OSError:
        pytest.skip("no GNU OpenMP runtime")
    runtime.omp_set_num_threads(3)
    backend.crocoddyl_module.cache_clear()
    try:
        backend.crocoddyl_module()
        assert runtime.omp_get_max_threads() == 1
    finally:
        backend.crocoddyl_module.cache_clear()
