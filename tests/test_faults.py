"""Faults lose nothing (#58): each command that writes a folder, interrupted (SIGINT, SIGTERM,
SIGKILL) at a stage, run twice into one folder at once, and run into a full disk, leaves the
folder holding either the previous complete results or the new complete results, never a mix;
an interrupt ends with one line on stderr and 130 or 143, no traceback and no process left; the
next command accepts the folder. Inputs that grow without bound (nested TOML, a URDF of 10,000
links) are refused by name.

The commands run as the user runs them, as processes (``python -m hexaleg.cli``); a moment to
interrupt is a line the command prints on stderr, or its output folder's lock appearing (the run
computes). The README's suite runs the quick cases — ``simulate`` interrupted, the viewer's
Ctrl-C, nested TOML, a giant URDF; the reports (interrupted, killed, two at once, on a full disk:
about 25 s of CPU), ``design`` (a small one), ``codesign``, ``paper`` and the process-pool sweep
are marked slow, for the README suite's 5 minutes.

A full disk is a small tmpfs mounted for the test (as root, where ``mount`` works); elsewhere it
is simulated with a file-size limit (``RLIMIT_FSIZE``, set in the child before it starts: a write
beyond it fails with EFBIG as a full disk fails with ENOSPC, at the same call), and the test says
which it used.
"""

from __future__ import annotations

import base64
import contextlib
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from processes import HAS_PROC, children, end_session, wait_gone

from hexaleg.cli import main
from hexaleg.outputs.directory import STAGING
from hexaleg.parallel.lock import LOCK

CLI = [sys.executable, "-m", "hexaleg.cli"]
GUARD = 300.0
"""Seconds after which a command is a hang (a guard, not a speed assertion)."""
OTHER_GAIT = "[gait]\nperiod = 1.25\n"
"""A config whose report differs from the default's in every file (the old results)."""

pytestmark = pytest.mark.skipif(not HAS_PROC, reason="finds the commands' workers in /proc")


def _terminal() -> None:
    """In the child: SIGINT as at a terminal (a test runner's worker may start it ignored)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(args: list[str], cwd: Path, preexec: Callable[[], None] | None = None
          ) -> subprocess.Popen:
    def setup() -> None:
        _terminal()
        if preexec is not None:
            preexec()

    proc = subprocess.Popen([*CLI, *args], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=setup,
                            start_new_session=True)
    STARTED.append(proc)
    return proc


STARTED: list[subprocess.Popen] = []
"""Every command :func:`start` started (each in a session of its own), for :func:`ending`."""


@contextlib.contextmanager
def ending() -> Iterator[None]:
    """Every command started inside the block ends with it, with every process it started,
    however the block ends (a command hung past :data:`GUARD`, an assertion failed before the
    command was reaped): a hung run never outlives its test or fixture. One had: a design the
    two-designs test interrupts hung in its pool's shutdown and ran on, orphaned, 29 minutes
    after CI had ended."""
    first = len(STARTED)
    try:
        yield
    finally:
        while len(STARTED) > first:
            end_session(STARTED.pop())


@pytest.fixture(autouse=True)
def _ends_what_it_starts() -> Iterator[None]:
    """Each test's commands end with the test (:func:`ending`); the module fixtures' end with
    the fixture, which is made before this one."""
    with ending():
        yield


def run(args: list[str], cwd: Path, preexec: Callable[[], None] | None = None
        ) -> subprocess.CompletedProcess:
    proc = start(args, cwd, preexec)
    out, err = proc.communicate(timeout=GUARD)
    return subprocess.CompletedProcess(args, proc.returncode, out, err)


def wait_held(proc: subprocess.Popen, lock: Path) -> None:
    """Wait until ``proc`` holds ``lock``: until the file names its pid, which a run writes only
    once its ``flock`` is taken. The file itself appears a moment before (the run opens it,
    then locks it), and a second run started in that moment takes the lock first: under CI's
    load the refused run was then the first one, and the second designed on for 300 s."""
    deadline = time.monotonic() + GUARD
    while True:
        assert proc.poll() is None, f"ended before it held {lock}: {proc.communicate()}"
        with contextlib.suppress(FileNotFoundError, json.JSONDecodeError):
            if json.loads(lock.read_text() or "{}").get("pid") == proc.pid:
                return
        assert time.monotonic() < deadline, "hang"
        time.sleep(0.01)


def wait_for(proc: subprocess.Popen, moment: str | Path) -> str:
    """Wait until ``proc`` prints a stderr line holding ``moment``, or until the path
    ``moment`` exists; the stderr read so far."""
    seen: list[str] = []
    deadline = time.monotonic() + GUARD
    if isinstance(moment, Path):
        while not moment.exists():
            assert proc.poll() is None, f"ended before {moment}: {proc.communicate()}"
            assert time.monotonic() < deadline, "hang"
            time.sleep(0.01)
        return ""
    assert proc.stderr is not None
    for line in proc.stderr:
        seen.append(line)
        if moment in line:
            return "".join(seen)
    pytest.fail(f"no line with {moment!r} on stderr: {''.join(seen)}")


def interrupt(args: list[str], cwd: Path, moment: str | Path, signum: int
              ) -> tuple[int, str, set[int]]:
    """Run a command, send it ``signum`` at ``moment``; (status, stderr, its children then)."""
    proc = start(args, cwd)
    err = wait_for(proc, moment)
    workers = children(proc.pid)
    proc.send_signal(signum)
    _, rest = proc.communicate(timeout=GUARD)
    return proc.returncode, err + rest, workers


def snapshot(directory: Path) -> dict[str, bytes]:
    """Every entry of a folder, hidden ones too, by name → content (b"<dir>" for a folder)."""
    if not directory.exists():
        return {}
    return {str(p.relative_to(directory)): b"<dir>" if p.is_dir() else p.read_bytes()
            for p in sorted(directory.rglob("*"))}


def leftovers(directory: Path) -> list[str]:
    """A run's lock or staging folder in ``directory``."""
    return [k for k in snapshot(directory) if k == LOCK or k.startswith(STAGING)]


def visible(directory: Path) -> dict[str, bytes]:
    return {k: v for k, v in snapshot(directory).items() if not k.startswith(".")}


def whole_report(directory: Path) -> dict:
    """The report in ``directory``, checked to be one run's: the files report.json lists are the
    folder's, and every plot is the one report.html embeds."""
    data = json.loads((directory / "report.json").read_text())
    assert sorted(data["files"]) == sorted(visible(directory))
    html = (directory / "report.html").read_text()
    for png in directory.glob("*.png"):
        assert base64.b64encode(png.read_bytes()).decode() in html, png.name
    return data


def assert_one_line(err: str, command: str, expected: str) -> None:
    """``err`` is the command's progress lines and one more, ``expected``."""
    head = f"hexaleg {command}: "
    lines = [line for line in err.splitlines() if not line.startswith(head)
             or line.startswith((f"{head}error: ", f"{head}interrupted "))]
    assert "Traceback" not in err and lines == [f"{head}{expected}"], err


@contextlib.contextmanager
def small_disk(path: Path, size: int) -> Iterator[Callable[[], None] | None]:
    """A folder on a file system of ``size`` bytes (a tmpfs: yields None), or where it cannot be
    mounted a file-size limit of ``size // 4`` bytes to set in the child (yields the setter)."""
    path.mkdir()
    mounted = os.geteuid() == 0 and shutil.which("mount") is not None and subprocess.run(
        ["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)],
        capture_output=True).returncode == 0
    try:
        if mounted:
            yield None
        else:
            limit = size // 4
            yield lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    finally:
        if mounted:
            subprocess.run(["umount", "-l", str(path)], check=True)


POOL_SWEEP = ("[sweep]\nchunk_size = 1\n[gait]\nsamples = 60\n[springs.tibia]\n"
              "k = {start = 0.0, stop = 0.5, num = 4000}\ntheta_k = 0.02\n")
"""A sweep of 4000 one-point parts over a process pool: it runs for minutes, its workers
started within seconds."""


def start_pool_sweep(cwd: Path) -> tuple[subprocess.Popen, set[int]]:
    """:data:`POOL_SWEEP` started over two workers, once both run; (it, its workers)."""
    (cwd / "spec.toml").write_text(POOL_SWEEP)
    proc = start(["sweep", "spec.toml", "--out", "s", "--executor", "process", "--workers",
                  "2"], cwd)
    deadline = time.monotonic() + GUARD
    while len(children(proc.pid)) < 2:
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.01)
    return proc, children(proc.pid)


@pytest.mark.slow  # a pool sweep started: ~2 s the README's 5 minutes need
def test_a_command_running_at_the_end_of_its_test_ends_with_its_workers(tmp_path):
    """What :func:`ending` does for a command hung at the end of a test or fixture: killed
    with its workers (its process group), not left running. Fails where :func:`start` leaves
    the command in the test runner's process group (the group's kill finds nothing, and the
    command sweeps on) or where nothing ends it; a kill of the command alone would end its
    workers too (they die with their parent, prctl(2)), which this cannot tell apart."""
    with ending():
        proc, workers = start_pool_sweep(tmp_path)
    assert proc.returncode == -signal.SIGKILL
    assert wait_gone({proc.pid, *workers}) == set()


# --- report: the quickest command that writes a folder ---------------------------------------

@pytest.fixture(scope="module")
def old_report(tmp_path_factory) -> tuple[Path, Path, dict[str, bytes]]:
    """A complete report of another gait (the previous results) made while a second report into
    the same folder is refused (two runs at once); (its folder, its config, its snapshot)."""
    work = tmp_path_factory.mktemp("old")
    config = work / "other.toml"
    config.write_text(OTHER_GAIT)
    with ending():
        first = start(["report", "--config", str(config), "--out", "r"], work)
        wait_held(first, work / "r" / LOCK)
        second = run(["report", "--out", "r"], work)  # the default gait, into the same folder
        _, err = first.communicate(timeout=GUARD)
    assert first.returncode == 0, err
    assert second.returncode == 2 and "Traceback" not in second.stderr
    assert second.stderr.startswith(f"hexaleg report: error: another report (pid {first.pid} "
                                    f"on host {os.uname().nodename}, started ")
    assert second.stderr.count("\n") == 1
    assert "give this report another --out directory" in second.stderr
    assert whole_report(work / "r")["gait"]["period"]["value"] == 1.25
    assert not leftovers(work / "r")
    return work, config, snapshot(work / "r")


def _copy(old: tuple[Path, Path, dict[str, bytes]], to: Path) -> Path:
    shutil.copytree(old[0] / "r", to)
    return to


@pytest.mark.slow  # two reports at once and one more: ~25 s the README's 5 minutes cannot hold
@pytest.mark.parametrize(("signum", "moment"), [(signal.SIGINT, "hexaleg report: plot "),
                                                (signal.SIGTERM, LOCK)])
def test_an_interrupted_report_keeps_the_previous_one(old_report, tmp_path, signum, moment):
    out = _copy(old_report, tmp_path / "r")
    status, err, workers = interrupt(["report", "--out", "r"], tmp_path,
                                     out / LOCK if moment == LOCK else moment, signum)
    assert status == 128 + signum
    assert_one_line(err, "report", f"interrupted ({signal.Signals(signum).name}): r kept as "
                                   "it was, nothing of this run written")
    assert snapshot(out) == old_report[2]  # not a byte of this run, no lock, no staging
    assert wait_gone(workers) == set()


@pytest.mark.slow
def test_a_killed_report_keeps_the_previous_one_and_the_next_run_replaces_it(old_report,
                                                                             tmp_path):
    out = _copy(old_report, tmp_path / "r")
    status, _, workers = interrupt(["report", "--out", "r"], tmp_path, "hexaleg report: plot ",
                                   signal.SIGKILL)
    assert status == -signal.SIGKILL and wait_gone(workers) == set()
    assert visible(out) == visible(tmp_path / "r") == {
        k: v for k, v in old_report[2].items() if not k.startswith(".")}
    again = run(["report", "--out", "r"], tmp_path)  # the stale lock and staging taken over
    assert again.returncode == 0, again.stderr
    assert whole_report(out)["gait"]["period"]["value"] == 1.0  # the new run's, whole
    assert not leftovers(out)


@pytest.mark.slow
def test_a_report_on_a_full_disk_keeps_the_previous_one(old_report, tmp_path):
    """The old report (1.6 MB) fits, the new one does not: its page fails to be written."""
    with small_disk(tmp_path / "disk", 2_600_000) as limit:
        out = _copy(old_report, tmp_path / "disk" / "r")
        proc = run(["report", "--out", str(out)], tmp_path, limit)
        assert proc.returncode == 2, proc.stderr
        why = "No space left on device" if limit is None else "File too large"
        assert_one_line(proc.stderr, "report", f"error: cannot write the report {out}/report."
                        f"html: {why}; {out} kept as it was, nothing of this run written")
        assert snapshot(out) == old_report[2]


# --- simulate -------------------------------------------------------------------------------

def test_an_interrupted_simulation_writes_nothing(tmp_path):
    status, err, workers = interrupt(["simulate", "--out", "s"], tmp_path,
                                     tmp_path / "s" / LOCK, signal.SIGTERM)
    assert status == 143, err
    assert_one_line(err, "simulate", "interrupted (SIGTERM): nothing of this run written to s")
    assert not (tmp_path / "s").exists() and wait_gone(workers) == set()


# --- the viewer -----------------------------------------------------------------------------

def _catches_sigint(pid: int) -> bool:
    """Whether ``pid`` has a handler for SIGINT (SigCgt in /proc/PID/status, proc(5))."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("SigCgt:"):
            return bool(int(line.split()[1], 16) >> (signal.SIGINT - 1) & 1)
    return False


def test_the_viewer_takes_ctrl_c_while_it_builds_even_started_ignored(tmp_path):
    """Started with SIGINT ignored (a background job of a script), Ctrl-C during the build of
    the page had been lost and the view served until killed (#58)."""
    proc = start(["view", "--html", "v.html"], tmp_path,
                 lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    deadline = time.monotonic() + GUARD
    while not _catches_sigint(proc.pid):
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=GUARD)
    assert proc.returncode == 130
    assert_one_line(err, "view", "interrupted (SIGINT): nothing written")
    assert list(tmp_path.iterdir()) == []


# --- inputs without bound, through the command line -----------------------------------------

@pytest.mark.parametrize("nested", ["{a = " * 3000 + "1" + "}" * 3000,
                                    "[" * 3000 + "1" + "]" * 3000])
def test_deeply_nested_toml_is_named_in_report_and_sweep(tmp_path, capsys, nested):
    config = tmp_path / "deep.toml"
    config.write_text(f"[gait]\nx = {nested}\n")
    for argv, command in ((["report", "--config", str(config), "--out", str(tmp_path / "r")],
                           "report"), (["sweep", str(config), "--out", str(tmp_path / "s")],
                                       "sweep")):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err == (f"hexaleg {command}: error: config file {config} nests tables or arrays "
                       "deeper than Python's TOML parser can read; allowed: at most 32 levels "
                       "(hexaleg's own files nest 3 deep)\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["deep.toml"]


def test_a_urdf_of_ten_thousand_links_is_refused_not_a_crash(tmp_path):
    """10,000 links chained by fixed joints had killed `hexaleg robot` with signal 11."""
    n = 10_000
    links = "".join(f'<link name="l{i}"/>' for i in range(n))
    joints = "".join(f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child '
                     f'link="l{i}"/></joint>' for i in range(1, n))
    (tmp_path / "chain.urdf").write_text(f'<robot name="chain">{links}{joints}</robot>')
    proc = run(["robot", "--urdf", "chain.urdf"], tmp_path)
    assert proc.returncode == 2
    assert_one_line(proc.stderr, "robot", "error: URDF chain.urdf has 10000 links; allowed: at "
                    "most 1000 (Pinocchio's URDF parser recurses once a link and crashes near "
                    "3,700 chained links on an 8 MiB stack; a legged robot has tens): is it the "
                    "right file?")


# --- the long commands (slow) ---------------------------------------------------------------

SMALL_DESIGN = """[gait]
samples = 120
[design]
samples = 120
families = ["linear", "one_sided"]
map_period = [0.7, 1.0, 1.4]
map_stride = [0.75, 1.0]
map_payload = [0.0, 0.4]
map_mu = [0.3, 0.6]
map_slope = [0.0, 0.26]
robust_period = [0.8, 1.25]
robust_stride = [1.0, 1.0]
robust_payload = [0.0, 0.2]
robust_mu = [0.6, 0.6]
pareto_fractions = [0.5]
"""
"""A design of every stage at a fraction of the default's cost (tests/conftest.py's small one),
simulated under one servo: the old results and the interrupted runs of the design cases."""
DESIGN = ["design", "--config", "small.toml", "--controller", "feedforward", "--out", "d"]


@pytest.fixture(scope="module")
def old_design(tmp_path_factory) -> Path:
    """A complete small design, made once for the slow cases."""
    work = tmp_path_factory.mktemp("design")
    (work / "small.toml").write_text(SMALL_DESIGN)
    with ending():
        proc = run(DESIGN, work)
    assert proc.returncode == 0, proc.stderr
    return work / "d"


@pytest.mark.slow
@pytest.mark.parametrize(("signum", "moment"), [(signal.SIGINT, LOCK),
                                                (signal.SIGKILL, "hexaleg design: ")])
def test_an_interrupted_design_keeps_the_previous_one(old_design, tmp_path, signum, moment):
    out = tmp_path / "d"
    shutil.copytree(old_design, out)
    (tmp_path / "small.toml").write_text(SMALL_DESIGN)
    before = snapshot(out)
    status, err, workers = interrupt(DESIGN, tmp_path, out / LOCK if moment == LOCK else moment,
                                     signum)
    assert wait_gone(workers) == set()  # the forked candidates' workers too
    if signum == signal.SIGKILL:
        assert status == -signal.SIGKILL and visible(out) == visible(old_design)
        return
    assert status == 128 + signum, err
    assert_one_line(err, "design", f"interrupted ({signal.Signals(signum).name}): d kept "
                                   "as it was, nothing of this run written")
    assert snapshot(out) == before
    report = run(["report", "--design", "d/design.json", "--config", "small.toml", "--out", "r"],
                 tmp_path)
    assert report.returncode == 0, report.stderr  # the next command accepts it


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGKILL])
def test_an_interrupted_design_resumes_from_its_finished_stages(old_design, tmp_path, signum):
    """Interrupted as it simulates the designs (its candidates and Pareto front finished), the
    design leaves the previous one as it was and its finished stages hidden beside it (one line
    says so); the same command reads them back, and its design is the previous one but for the
    timings, the stages gone once it is whole. ~8 s killed, ~20 s interrupted and resumed."""
    from hexaleg.design.chain.chain import STAGES
    from hexaleg.design.chain.checkpoint import FOLDER

    out = tmp_path / "d"
    shutil.copytree(old_design, out)
    (tmp_path / "small.toml").write_text(SMALL_DESIGN)
    status, err, workers = interrupt(DESIGN, tmp_path, "designs simulated under", signum)
    assert wait_gone(workers) == set()
    assert visible(out) == visible(old_design)
    assert {p.name for p in (out / FOLDER).glob("*.pickle")} >= {"candidates.pickle",
                                                                   "pareto.pickle"}
    if signum == signal.SIGKILL:  # what it leaves is the same: the SIGINT case resumes
        assert status == -signal.SIGKILL
        return
    assert status == 130, err
    kept = ", ".join(sorted((p.stem for p in (out / FOLDER).glob("*.pickle")),
                            key=STAGES.index))  # the signal came as the ranking's line was
    # printed: before or after its file was written, or, on a fast run, after a later stage's
    assert_one_line(err, "design", "interrupted (SIGINT): d kept as it was, nothing of this "
                                   f"run written; but its finished stages ({kept}) are kept "
                                   "in d/.hexaleg-design-stages for the same command to "
                                   "resume from")
    again = run(DESIGN, tmp_path)
    assert again.returncode == 0, again.stderr
    assert [line for line in again.stderr.splitlines() if "family optimum" in line
            and line.endswith("(kept from the earlier run)")], again.stderr
    assert not (out / FOLDER).exists() and not leftovers(out)
    old, new = (json.loads((d / "design.json").read_text()) for d in (old_design, out))
    old.pop("timings"), new.pop("timings")
    assert new == old


@pytest.mark.slow
def test_two_designs_into_one_folder_one_runs_the_other_is_refused(tmp_path):
    (tmp_path / "small.toml").write_text(SMALL_DESIGN)
    first = start(DESIGN, tmp_path)
    wait_held(first, tmp_path / "d" / LOCK)
    second = run(DESIGN, tmp_path)
    assert second.returncode == 2 and f"another design (pid {first.pid} " in second.stderr
    first.send_signal(signal.SIGINT)  # the first need not finish: it leaves no result, at
    # most the stages it finished, for the same command to resume from
    from hexaleg.design.chain.checkpoint import FOLDER

    _, err = first.communicate(timeout=GUARD)
    assert first.returncode == 130 and "Traceback" not in err
    d = tmp_path / "d"
    assert not d.exists() or [p.name for p in d.iterdir()] == [FOLDER], err


@pytest.mark.slow
def test_an_interrupted_codesign_writes_nothing(tmp_path):
    status, err, workers = interrupt(["codesign", "--out", "c"], tmp_path, "hexaleg codesign: ",
                                     signal.SIGINT)
    assert wait_gone(workers) == set() and not (tmp_path / "c").exists()
    assert status == 130
    assert_one_line(err, "codesign", "interrupted (SIGINT): nothing of this run written to c")


@pytest.mark.slow
def test_an_interrupted_paper_keeps_the_previous_one(tmp_path):
    first = run(["paper", "--out", "p", "--no-simulation", "--samples", "512"], tmp_path)
    assert first.returncode == 0, first.stderr
    before = snapshot(tmp_path / "p")
    status, err, _ = interrupt(["paper", "--out", "p"], tmp_path, tmp_path / "p" / LOCK,
                               signal.SIGINT)
    assert status == 130 and snapshot(tmp_path / "p") == before
    assert_one_line(err, "paper", "interrupted (SIGINT): p kept as it was, nothing of this run "
                                  "written")


@pytest.mark.slow
def test_an_interrupted_pool_sweep_keeps_its_parts_and_leaves_no_worker(tmp_path):
    proc, workers = start_pool_sweep(tmp_path)
    deadline = time.monotonic() + GUARD
    while len(list((tmp_path / "s").glob("part-*"))) < 3:
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=GUARD)
    assert proc.returncode == 130 and "Traceback" not in err, err
    assert wait_gone(workers) == set()
    assert err.splitlines()[-1].startswith("hexaleg sweep: interrupted (SIGINT): the ")
    assert err.splitlines()[-1].endswith(" finished part(s) in s kept (the same command "
                                         "resumes the rest)")
    assert not (tmp_path / "s" / LOCK).exists()
    from hexaleg.sweep.store import read_table

    assert len(read_table(tmp_path / "s")) >= 3  # the next reader accepts it
