"""Tests of hexaleg.studies.sweep.executors: the serial and process executors run a task, errors
travel in the future, and bad arguments are named hexaleg errors."""

from __future__ import annotations

import sys

import pytest

from hexaleg.errors import ExecutorError, HexalegError, InvalidParameterError
from hexaleg.studies.sweep.executors import (
    EXECUTORS,
    SerialExecutor,
    default_workers,
    open_executor,
)


def test_serial_executor_runs_at_submit_and_keeps_the_exception():
    ex = SerialExecutor()
    ok = ex.submit(pow, 2, 10)
    assert ok.done() and ok.result() == 1024
    bad = ex.submit(int, "x")
    assert bad.done() and isinstance(bad.exception(), ValueError)
    with pytest.raises(ValueError):
        bad.result()


@pytest.mark.parametrize("kind", ["serial", "process"])
def test_serial_and_process_executors_run_a_task(kind):
    with open_executor(kind, workers=1 if kind == "process" else None) as ex:
        futures = [ex.submit(pow, 3, n) for n in range(4)]
        assert [f.result(timeout=60) for f in futures] == [1, 3, 9, 27]


def test_default_workers_is_at_least_one():
    assert isinstance(default_workers(), int) and default_workers() >= 1
    assert EXECUTORS[0] == "process"


def test_bad_executor_arguments_are_named_hexaleg_errors():
    with pytest.raises(InvalidParameterError, match=r"executor.*process, serial, dask") as e:
        with open_executor("threads"):
            pass
    assert isinstance(e.value, HexalegError)
    with pytest.raises(InvalidParameterError, match=r"workers"):
        with open_executor("process", workers=0):
            pass
    with pytest.raises(InvalidParameterError, match=r"scheduler"):
        with open_executor("dask"):
            pass
    with pytest.raises(InvalidParameterError, match=r"scheduler"):
        with open_executor("serial", scheduler="tcp://127.0.0.1:1"):
            pass


def test_dask_without_distributed_is_an_executor_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # `import distributed` fails
    with pytest.raises(ExecutorError, match=r"hexaleg\[dask\]"):
        with open_executor("dask", scheduler="tcp://127.0.0.1:1"):
            pass
