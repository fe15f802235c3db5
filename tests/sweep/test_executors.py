"""Tests of hexaleg.sweep.executors: the serial and process executors run a task, errors
travel in the future, and bad arguments are named hexaleg errors."""

from __future__ import annotations

import sys

import pytest

from hexaleg.errors import ExecutorError, HexalegError, InvalidParameterError
from hexaleg.sweep.executors import (
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


# --------------------------------------------------------------------------- the Dask probe


@pytest.fixture
def http_port():
    """A web server on a free local port (what Dask's dashboard is), in a thread."""
    import http.server
    import threading

    class Quiet(http.server.ThreadingHTTPServer):
        def handle_error(self, request, client_address):  # the probe hangs up: no noise
            pass

    class Handler(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = Quiet(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server.server_address[1]
    server.shutdown()
    server.server_close()


def _guarded(fn, guard=60.0):
    """Run ``fn`` in a thread; its exception, or fail if it hangs past ``guard`` s."""
    import threading

    box = {}

    def run():
        try:
            fn()
        except BaseException as e:
            box["error"] = e

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(guard)
    assert not thread.is_alive(), f"still waiting after {guard} s (a hang)"
    return box.get("error")


def test_a_port_that_speaks_http_is_refused_by_name(http_port, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr("hexaleg.sweep.executors.CONNECT_TIMEOUT", 1.0)
    address = f"tcp://127.0.0.1:{http_port}"

    def connect():
        with open_executor("dask", scheduler=address):
            pass

    error = _guarded(connect)
    assert isinstance(error, ExecutorError), error
    assert address in str(error) and "does not speak the Dask protocol" in str(error)
    assert "HTTP" in str(error) and "8786" in str(error)


def test_a_silent_port_is_refused_and_other_protocols_are_named():
    import socket

    from hexaleg.sweep.executors import check_scheduler

    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen()
        port = silent.getsockname()[1]
        error = _guarded(lambda: check_scheduler(f"127.0.0.1:{port}", 0.5))
        assert isinstance(error, ExecutorError) and "answers nothing" in str(error)
    error = _guarded(lambda: check_scheduler(f"tcp://127.0.0.1:{port}", 0.5))  # closed now
    assert isinstance(error, ExecutorError) and "cannot reach" in str(error)
    with pytest.raises(ExecutorError, match=r"http:// is not a Dask protocol"):
        check_scheduler("http://127.0.0.1:8787", 0.5)
    with pytest.raises(ExecutorError, match=r"no host:port"):
        check_scheduler("tcp://127.0.0.1", 0.5)


def test_a_real_scheduler_passes_the_probe():
    distributed = pytest.importorskip("distributed")
    from hexaleg.sweep.executors import check_scheduler

    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        check_scheduler(cluster.scheduler_address, 10.0)
