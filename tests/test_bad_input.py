"""A catalogue of bad and careless inputs, across the command line and the API, as a hostile or
hurried user would give them (issue 18). Each must end in a hexaleg error of the stated class whose
message names the bad value — never a traceback, a silent result or a hang.

Command-line cases run the subcommand's handler (``args.func(args)``), so that the error's class
is seen; :func:`hexaleg.cli.main` turns any :class:`~hexaleg.errors.HexalegError` into one line on
stderr and exit status 2 (checked here for every command-line case too).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path

import pytest

import hexaleg
import hexaleg.dynamics.prepare
import hexaleg.robot.description
from hexaleg import errors
from hexaleg.cli import build_parser, main
from hexaleg.config import from_mapping, load_toml
from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF, load_robot

DATA = Path(__file__).parent / "data"
IPE, UNE, CE = errors.InvalidParameterError, errors.UnknownNameError, errors.ConfigError
RME = errors.RobotModelError


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The bad files of the catalogue, by name."""
    d = tmp_path_factory.mktemp("bad")
    out = {"dir": d}

    def put(name, text, encoding="utf-8"):
        (d / name).write_bytes(text.encode(encoding))
        out[name] = str(d / name)

    put("latin1.toml", "[gait]\nperiod = 1.0  # café\n", "latin-1")
    put("samples.toml", "[gait]\nsamples = 10000000\n")
    put("groups.toml", '[gait]\ngroups = "LF"\n')
    put("period_nan.toml", "[gait]\nperiod = nan\n")
    put("period_text.toml", '[gait]\nperiod = "1"\n')
    put("unknown_key.toml", "[gait]\nspeeed = 0.1\n")
    put("not_toml.toml", "[gait\nperiod = 1\n")
    put("paper_samples.toml", "[report]\npaper_samples = 1000000000\n")
    put("paper_samples_float.toml", "[report]\npaper_samples = 1e9\n")
    put("mu_bool.toml", "[contact]\nmu = true\n")
    put("fps.toml", "[view]\nfps = 1e9\n")
    put("wide.toml", "[springs.LF_femur]\nstiffness = 1.0\ntheta_k = 6.0\n")
    put("spec_latin1.toml", "[gait]\nsamples = 40  # é\n", "latin-1")
    put("spec_table.toml", "[sweeep]\nmetric = 'joule'\n")
    put("spec_scalar.toml", "sweep = 1\n")
    put("spec_grid.toml", "[gait]\nsamples = 40\nperiod = {start = 0.5, stop = 1.5, num = 100000}"
        "\n[springs.femur]\nk = {start = 0.0, stop = 1.0, num = 100000}\ntheta_k = 0.1\n")
    put("robot_nolegs.toml", '[robot]\nname = "x"\n')
    put("robot_key.toml", '[robot]\nname = "x"\nurdf = "x.urdf"\ncolour = "red"\n')
    srdf = DEFAULT_SRDF.read_text(encoding="utf-8")
    put("nan.srdf", srdf.replace('<joint name="LF_femur" value="0.3490658504"',
                                 '<joint name="LF_femur" value="nan"', 1))
    put("misspelt.srdf", srdf.replace('<joint name="LF_femur"', '<joint name="LF_femr"', 1))
    urdf = (DATA / "spider.urdf").read_text(encoding="utf-8")
    put("zero.urdf", re.sub(r'<mass value="[^"]*"', '<mass value="0"', urdf))
    put("mass_text.urdf", re.sub(r'<mass value="[^"]*"', '<mass value="abc"', urdf, count=1))
    put("origin_short.urdf", re.sub(r'<origin xyz="[^"]*"', '<origin xyz="0 0"', urdf, count=1))
    put("zero.toml", '[robot]\nname = "zero"\nurdf = "zero.urdf"\nheading = "+y"\n'
        "stand = {body_height = 0.08}\n")
    return out


def argv_of(argv: tuple[str, ...], f: dict) -> list[str]:
    """``@name`` is a catalogue file, ``{dir}`` its directory."""
    return [f[a[1:]] if a.startswith("@") else a.format(dir=f["dir"]) for a in argv]


def cli(*argv: str) -> Callable[[dict], None]:
    """A command line, run through its handler (``@name``: a catalogue file)."""
    def run(f: dict) -> None:
        args = build_parser().parse_args(argv_of(argv, f))
        args.func(args)
    run.argv = argv  # type: ignore[attr-defined]
    return run


def api(fn: Callable[..., object], *args: object, **kwargs: object) -> Callable[[dict], None]:
    return lambda f: fn(*args, **kwargs)


def walk(samples=40):
    robot = hexaleg.load()
    return robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=samples))


def spring(**kw):
    return hexaleg.DeadZoneSpring(**{"stiffness": 1.0, "theta_k": 0.1, **kw})


def analyze_with(springs):
    return lambda f: hexaleg.dynamics.prepare.analyze(*walk(), springs)


def sweep_spec(**kw):
    from hexaleg.sweep import SweepSpec

    return lambda f: SweepSpec(**kw)


def sweep_table(data):
    from hexaleg.sweep import SweepSpec

    return lambda f: SweepSpec.from_mapping(data)


def parse(name, text):
    from hexaleg.sweep import parse_range

    return lambda f: parse_range(name, text)


def axis(name, value):
    from hexaleg.sweep.ranges import axis_values

    return lambda f: axis_values(name, value)


def second_writer(f):
    from hexaleg.parallel.lock import DirectoryLock
    from hexaleg.sweep.store import ResultStore

    lock = DirectoryLock(f["dir"])
    try:
        ResultStore(f["dir"], {"spec": 1})
    finally:
        lock.release()


def view_params(**kw):
    from hexaleg.outputs.viewer.show import ViewParams

    return lambda f: ViewParams(**kw)


def report_params(**kw):
    from hexaleg.report.config import ReportParams

    return lambda f: ReportParams(**kw)


def executor(kind, **kw):
    from hexaleg.sweep.executors import open_executor

    def run(f):
        with open_executor(kind, **kw):
            pass
    return run


def paper(n):
    from hexaleg.paper.reproduce import reproduce

    return lambda f: reproduce(n=n)


G = hexaleg.GaitParams
C = hexaleg.ContactParams
NAN, INF = math.nan, math.inf
SWEEP = ("sweep", "--joints", "femur", "--executor", "serial", "--out", "{dir}/sweep")

# (id, input, error class, text the message must hold: the bad value as given)
CASES: list[tuple[str, Callable[[dict], None], type[Exception], str]] = [
    # gait parameters (API)
    ("gait period str", api(G, period="1"), IPE, "'1'"),
    ("gait period bool", api(G, period=True), IPE, "True"),
    ("gait period nan", api(G, period=NAN), IPE, "nan"),
    ("gait period negative", api(G, period=-1.0), IPE, "-1.0"),
    ("gait duty factor 1", api(G, duty_factor=1.0), IPE, "duty_factor = 1.0"),
    ("gait duty factor negative", api(G, duty_factor=-0.5), IPE, "-0.5"),
    ("gait stride negative", api(G, stride_length=-0.1), IPE, "-0.1"),
    ("gait step height 0", api(G, step_height=0.0), IPE, "step_height = 0.0"),
    ("gait samples 1e7", api(G, samples=10**7), IPE, "10000000"),
    ("gait samples float", api(G, samples=100.0), IPE, "100.0"),
    ("gait samples bool", api(G, samples=True), IPE, "True"),
    ("gait samples 5", api(G, samples=5), IPE, "samples = 5"),
    ("gait groups str", api(G, groups="LF"), IPE, "'LF'"),
    ("gait groups of str", api(G, groups=("LF", "RM")), IPE, "('LF', 'RM')"),
    ("gait groups repeated", api(G, groups=(("LF", "LF"),)), IPE, "'LF', 'LF'"),
    ("gait balance", api(G, balance="yes"), IPE, "'yes'"),
    ("gait yaw inf", api(G, yaw_rate=INF), IPE, "inf"),
    ("gait speed str", api(G, speed="fast"), IPE, "'fast'"),
    # contact (API)
    ("contact mu bool", api(C, mu=True), IPE, "True"),
    ("contact mu 0", api(C, mu=0), IPE, "mu = 0"),
    ("contact mu nan", api(C, mu=NAN), IPE, "nan"),
    ("contact cone", api(C, cone="cube"), IPE, "'cube'"),
    ("contact torque limits int", api(C, torque_limits=1), IPE, "torque_limits = 1"),
    ("contact min force", api(C, min_normal_force=-1.0), IPE, "-1.0"),
    ("contact regularization", api(C, regularization=0.0), IPE, "0.0"),
    # springs (API)
    ("spring k negative", lambda f: spring(stiffness=-1.0), IPE, "-1.0"),
    ("spring theta_k 0", lambda f: spring(theta_k=0), IPE, "theta_k = 0.0"),
    ("spring theta_k negative", lambda f: spring(theta_k=-0.1), IPE, "-0.1"),
    ("spring k str", lambda f: spring(stiffness="1"), IPE, "'1'"),
    ("spring k bool", lambda f: spring(stiffness=True), IPE, "True"),
    ("spring no dead zone", lambda f: hexaleg.DeadZoneSpring(stiffness=1.0), IPE, "None"),
    ("spring alpha 0", lambda f: spring(alpha=0.0), IPE, "alpha = 0.0"),
    ("spring convention", lambda f: spring(convention="eq9"), IPE, "'eq9'"),
    ("spring angles reversed", lambda f: spring(theta_k=None, theta_minus=0.2, theta_plus=0.1),
     IPE, "0.2"),
    ("linear spring k negative", api(hexaleg.LinearSpring, stiffness=-1.0), IPE, "-1.0"),
    ("linear spring k nan", api(hexaleg.LinearSpring, stiffness=NAN), IPE, "nan"),
    ("spring set key", lambda f: hexaleg.SpringSet({1: spring()}), IPE, "= 1"),
    ("analyze springs list", analyze_with([spring()]), IPE, "[DeadZoneSpring("),
    ("analyze misspelt joint", analyze_with({"LF_femr": spring()}), UNE, "'LF_femr'"),
    ("analyze spring not a law", analyze_with({"LF_femur": 1.0}), IPE, "1.0"),
    ("analyze dead zone holds the range", analyze_with({"LF_femur": spring(theta_k=6.0)}), IPE,
     "[-6, 6] rad"),
    # robot files (API)
    ("urdf missing", api(load_robot, "/nonexistent/robot.urdf"), RME, "/nonexistent/robot.urdf"),
    ("urdf device", api(load_robot, "/dev/zero"), RME, "/dev/zero"),
    ("srdf value nan", lambda f: load_robot(DEFAULT_URDF, f["nan.srdf"]), IPE, "'nan'"),
    ("srdf misspelt joint", lambda f: load_robot(DEFAULT_URDF, f["misspelt.srdf"]), UNE,
     "'LF_femr'"),
    ("urdf zero mass", lambda f: load_robot(f["zero.urdf"], legs="auto"), RME, "zero.urdf"),
    ("urdf mass not a number", lambda f: load_robot(f["mass_text.urdf"], legs="auto"), RME,
     '<mass value="abc">'),
    ("urdf origin of two numbers", lambda f: load_robot(f["origin_short.urdf"], legs="auto"),
     RME, '<origin xyz="0 0">'),
    ("robot toml without urdf", lambda f: hexaleg.robot.description.RobotDescription.from_toml(
        f["robot_nolegs.toml"]), CE, "urdf"),
    ("robot toml unknown key", lambda f: hexaleg.robot.description.RobotDescription.from_toml(
        f["robot_key.toml"]), UNE, "'colour'"),
    # TOML files and tables (API)
    ("toml latin-1", lambda f: load_toml(f["latin1.toml"]), CE, "0xe9"),
    ("toml device", api(load_toml, "/dev/zero"), CE, "/dev/zero"),
    ("toml directory", lambda f: load_toml(f["dir"]), CE, "is not a regular file"),
    ("toml missing", api(load_toml, "/nonexistent.toml"), CE, "/nonexistent.toml"),
    ("toml syntax", lambda f: load_toml(f["not_toml.toml"]), CE, "not_toml.toml"),
    ("table period str", api(from_mapping, G, {"period": "1"}), CE, "'1'"),
    ("table samples float", api(from_mapping, G, {"samples": 1e9}), CE, "1000000000.0"),
    ("table mu bool", api(from_mapping, C, {"mu": True}), CE, "True"),
    ("table unknown key", api(from_mapping, G, {"speeed": 1.0}), UNE, "'speeed'"),
    # sweeps (API)
    ("sweep grid 1e10", sweep_spec(springs={"femur": {"k": tuple(range(100000)),
                                                      "theta_k": tuple(0.01 + i * 1e-6
                                                                       for i in range(100000))}}),
     IPE, "10000000000"),
    ("sweep unknown gait key", sweep_spec(gait={"speeed": 1.0}), UNE, "'speeed'"),
    ("sweep no dead zone", sweep_spec(springs={"femur": {"k": 1.0}}), IPE, "['k']"),
    ("sweep k negative", sweep_spec(springs={"femur": {"k": -1.0, "theta_k": 0.1}}), IPE, "-1.0"),
    ("sweep chunk 0", sweep_spec(chunk_size=0), IPE, "chunk_size = 0"),
    ("sweep optimal not a table", sweep_table({"optimal": 1, "springs": {"femur": {}}}), CE,
     "optimal = 1"),
    ("range log from 0", parse("--k", "0:1:5:log"), IPE, "--k.start = 0.0"),
    ("range nan", parse("--period", "nan"), IPE, "--period = nan"),
    ("range text", parse("--k", "a:b"), IPE, "'a:b'"),
    ("range empty", parse("--k", "0:1:0"), IPE, "--k.num = 0"),
    ("range huge", parse("--k", "0:1:10000000000"), IPE, "10000000000"),
    ("axis empty list", axis("k", []), IPE, "[]"),
    ("axis without num", axis("k", {"start": 0, "stop": 1}), CE, "num"),
    ("axis num 1e10", axis("k", {"start": 0, "stop": 1, "num": 1e10}), IPE, "10000000000.0"),
    ("sweep second writer", second_writer, errors.DirectoryLockedError, "pid "),
    ("executor kind", executor("threads"), IPE, "'threads'"),
    ("executor workers 0", executor("process", workers=0), IPE, "workers = 0"),
    # view, report, paper (API)
    ("view fps 1e9", view_params(fps=1e9), IPE, "1000000000.0"),
    ("view fps 0", view_params(fps=0), IPE, "fps = 0"),
    ("view fps bool", view_params(fps=True), IPE, "True"),
    ("report paper samples", report_params(paper_samples=10**9), IPE, "1000000000"),
    ("report curve points", report_params(stiffness_points=1), IPE, "stiffness_points = 1"),
    ("report objective", report_params(objective="fast"), IPE, "'fast'"),
    ("paper samples", paper(10**9), IPE, "1000000000"),
    # the command line
    ("cli gait latin-1", cli("gait", "--config", "@latin1.toml"), CE, "0xe9"),
    ("cli gait /dev/zero", cli("gait", "--config", "/dev/zero"), CE, "/dev/zero"),
    ("cli gait samples", cli("gait", "--config", "@samples.toml"), IPE, "10000000"),
    ("cli gait groups", cli("gait", "--config", "@groups.toml"), CE, "'LF'"),
    ("cli gait period nan", cli("gait", "--config", "@period_nan.toml"), CE, "nan"),
    ("cli gait period text", cli("gait", "--config", "@period_text.toml"), CE, "'1'"),
    ("cli gait unknown key", cli("gait", "--config", "@unknown_key.toml"), UNE, "'speeed'"),
    ("cli gait robot", cli("gait", "--robot", "nosuch"), UNE, "'nosuch'"),
    ("cli robot zero mass", cli("robot", "--robot", "@zero.toml"), RME, "zero.urdf"),
    ("cli robot /dev/zero", cli("robot", "--urdf", "/dev/zero"), RME, "/dev/zero"),
    ("cli robot srdf nan", cli("robot", "--urdf", str(DEFAULT_URDF), "--srdf", "@nan.srdf"),
     IPE, "'nan'"),
    ("cli robot srdf misspelt", cli("robot", "--urdf", str(DEFAULT_URDF), "--srdf",
                                    "@misspelt.srdf"), UNE, "'LF_femr'"),
    ("cli report paper samples", cli("report", "--config", "@paper_samples.toml", "--out",
                                     "{dir}/r"), IPE, "1000000000"),
    ("cli report paper samples float", cli("report", "--config", "@paper_samples_float.toml",
                                           "--out", "{dir}/r"), CE, "1000000000.0"),
    ("cli report mu bool", cli("report", "--config", "@mu_bool.toml", "--out", "{dir}/r"), CE,
     "True"),
    ("cli report robot", cli("report", "--robot", "nosuch", "--out", "{dir}/r"), UNE,
     "'nosuch'"),
    ("cli view fps", cli("view", "--config", "@fps.toml", "--html", "{dir}/v.html"), IPE,
     "1000000000.0"),
    ("cli paper samples", cli("paper", "--samples", "1000000000", "--out", "{dir}/p"), IPE,
     "1000000000"),
    ("cli sweep period nan", cli(*SWEEP, "--k", "0.1", "--theta-k", "0.1", "--period", "nan"),
     IPE, "--period = nan"),
    ("cli sweep k log 0", cli(*SWEEP, "--k", "0:1:5:log", "--theta-k", "0.1"), IPE,
     "--k.start = 0.0"),
    ("cli sweep grid", cli(*SWEEP, "--k", "0.1:1:100000", "--theta-k", "0.01:0.1:100000"), IPE,
     "10000000000"),
    ("cli sweep wide dead zone", cli(*SWEEP, "--k", "0.1", "--theta-k", "6"), IPE,
     "[-6, 6] rad"),
    ("cli sweep samples", cli(*SWEEP, "--k", "0.1", "--theta-k", "0.1", "--samples",
                              "10000000"), IPE, "10000000"),
    ("cli sweep workers", cli(*SWEEP[:-1], "{dir}/sweep_w", "--k", "0.1", "--theta-k", "0.1",
                              "--samples", "40", "--executor", "process", "--workers", "0"),
     IPE, "workers = 0"),
    ("cli sweep max torque", cli(*SWEEP, "--k", "0.1", "--theta-k", "0.1", "--max-torque",
                                 "1"), IPE, "given without --family"),
    ("cli sweep spec latin-1", cli("sweep", "@spec_latin1.toml", "--out", "{dir}/s"), CE,
     "0xe9"),
    ("cli sweep spec table", cli("sweep", "@spec_table.toml", "--out", "{dir}/s"), UNE,
     "'sweeep'"),
    ("cli sweep spec section not a table", cli("sweep", "@spec_scalar.toml", "--out",
                                               "{dir}/s"), CE, "sweep = 1; expected a table"),
    ("cli sweep spec grid", cli("sweep", "@spec_grid.toml", "--out", "{dir}/s"), IPE,
     "10000000000"),
    ("cli sweep metric", cli(*SWEEP, "--k", "0.1", "--theta-k", "0.1", "--samples", "40",
                             "--metric", "speed"), UNE, "'speed'"),
]


def test_the_catalogue_is_large_and_spans_cli_and_api():
    n_cli = sum(hasattr(fn, "argv") for _, fn, _, _ in CASES)
    assert len(CASES) > 100 and n_cli >= 20 and len(CASES) - n_cli >= 40  # docs/limits.md
    assert len({case[0] for case in CASES}) == len(CASES)


@pytest.mark.parametrize(("kind", "run", "error", "text"), CASES, ids=[c[0] for c in CASES])
def test_bad_input_gets_a_named_error(files, kind, run, error, text, capsys):
    with pytest.raises(error) as e:
        run(files)
    assert isinstance(e.value, errors.HexalegError)
    message = str(e.value)
    assert text in message, message
    if hasattr(run, "argv"):  # the command line: one line on stderr, status 2, no traceback
        capsys.readouterr()
        assert main(argv_of(run.argv, files)) == 2
        err = capsys.readouterr().err
        assert err.startswith("hexaleg ") and ": error: " in err and "Traceback" not in err
        assert text in err


def test_a_truncated_sweep_part_is_a_warning_and_recomputed(files):
    from hexaleg.sweep import SweepSpec, run_sweep

    spec = SweepSpec(gait={"samples": 40}, springs={"coxa": {"k": (0.0, 0.1), "theta_k": 0.01}},
                     chunk_size=1)
    out = files["dir"] / "truncated"
    run_sweep(spec, out, executor="serial")
    part = out / "part-0000001-0000001.parquet"
    part.write_bytes(part.read_bytes()[:50])
    with pytest.warns(errors.HexalegWarning, match="part-0000001-0000001.parquet cannot be read"):
        again = run_sweep(spec, out, executor="serial")
    assert (again.reused, again.computed) == (1, 1)


def test_a_robot_toml_without_title_or_srdf_loads(files):
    """Once a raw TypeError (RobotDescription missing title/srdf): both are optional."""
    desc = hexaleg.robot.description.RobotDescription.from_toml(DATA / "spider.toml")
    assert desc.title == desc.name and desc.srdf is None


def test_the_limits_page_states_the_bounds_in_force():
    from hexaleg.checks import MEMORY_BUDGET
    from hexaleg.config import MAX_TEXT_BYTES
    from hexaleg.motion.limits import MAX_SAMPLES, MIN_SAMPLES, SAMPLE_BYTES
    from hexaleg.outputs.viewer.keyframes import KEYFRAME_BYTES, MAX_FPS
    from hexaleg.sweep.executors import CONNECT_TIMEOUT
    from hexaleg.sweep.ranges import POINT_BYTES

    docs = Path(__file__).parents[1] / "docs"
    page = " ".join(docs.joinpath("limits.md").read_text(encoding="utf-8").split())
    assert f"{MEMORY_BUDGET / 1024**3:g} GiB" in page and f"{MAX_TEXT_BYTES // 1024**2} MiB" in page
    assert f"| {MIN_SAMPLES} … {MAX_SAMPLES:,} | {SAMPLE_BYTES // 1024} kB (" in page
    with pytest.raises(errors.InvalidParameterError) as e:  # the paper's joint: its own low
        paper(0)(None)
    low = int(str(e.value).split("an integer in [")[1].split(",")[0])
    assert f"| {low} … {MAX_SAMPLES:,} | {SAMPLE_BYTES // 1024} kB (" in page
    assert f"| {MAX_FPS:,} per second, and {MAX_FPS:,} in all | {KEYFRAME_BYTES // 1024} kB (" \
        in page
    assert f"| {MEMORY_BUDGET // POINT_BYTES:,} points | {POINT_BYTES // 1024} kB (" in page
    for name in ("limits.md", "sweep.md"):
        text = " ".join(docs.joinpath(name).read_text(encoding="utf-8").split())
        assert f"within {CONNECT_TIMEOUT:g} s" in text, name


def test_a_refused_paper_run_writes_nothing(tmp_path, capsys):
    """The samples are checked before the output directory is created."""
    out = tmp_path / "paper-out"
    assert main(["paper", "--samples", str(10**9), "--out", str(out)]) == 2
    assert "1000000000" in capsys.readouterr().err
    assert not out.exists()


def test_public_functions_name_an_argument_of_the_wrong_type():
    """Every function of hexaleg.__all__, and of the names it deprecates, checks its arguments'
    types (#42): None, an object, a string or an array where its first parameter's annotation
    admits none of them is a hexaleg error naming the argument and the type — never an
    AttributeError from deep inside."""
    import inspect
    import warnings

    import numpy as np

    import hexaleg
    from hexaleg.checks import _admits, _hints
    from hexaleg.errors import HexalegError

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        names = [*hexaleg.__all__, *(n for n in hexaleg._DEPRECATED if n != "build_design")]
        functions = [getattr(hexaleg, n) for n in names
                     if inspect.isfunction(getattr(hexaleg, n))]
    assert len(functions) >= 30
    tried = 0
    for f in functions:
        first = next(iter(inspect.signature(f).parameters))
        classes = _hints(inspect.unwrap(f)).get(first)
        for bad in (None, object(), "hexaleg-no-such", np.zeros((2, 2, 2))):
            if classes is None or _admits(classes, bad):
                continue
            with pytest.raises(HexalegError, match=rf"{f.__name__}\({first}=…\)"):
                f(bad)
            tried += 1
    assert tried >= 60


@pytest.mark.parametrize("call", [
    lambda h, r, m: h.load_motion(None, "walk.csv"),
    lambda h, r, m: h.load_motion("hexaleg", "walk.csv"),
    lambda h, r, m: h.load_motion(r, None),
    lambda h, r, m: h.load_design(None),
    lambda h, r, m: h.prepare(r, None),
    lambda h, r, m: h.analyze("hexaleg", m),
    lambda h, r, m: h.gait(r, "tripod"),
    lambda h, r, m: h.design_torsion_spring(None),
    lambda h, r, m: h.load_motion(r, "walk.csv", max_gap=-1.0),
])
def test_the_third_catalogue_s_raw_tracebacks_are_named(call, robot, walk200):
    import hexaleg
    from hexaleg.errors import HexalegError

    with pytest.raises(HexalegError):
        call(hexaleg, robot, walk200)


# --------------------------------------------------------------------------------------------
# The fourth probe (#42): empty option values, a log's impossible values, design files read
# strictly by the report as by simulate.

@pytest.mark.parametrize("argv", [
    ["report", "--out", ""], ["view", "--html", ""], ["view", "--host", ""],
    ["simulate", "--springs", ""], ["report", "--config", ""], ["report", "--robot", ""],
    ["sweep", ""], ["design", "--motion", " "],
])
def test_an_empty_option_value_is_refused_not_the_default(argv, capsys):
    """``--out ""`` wrote into the working directory, ``--html ""`` served instead of writing,
    ``--host ""`` listened on every interface: each is named by the parser (status 2)."""
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    assert "an empty value; give a name or a path" in capsys.readouterr().err


@pytest.fixture(scope="module")
def log_csv(tmp_path_factory, robot, walk200):
    from hexaleg.motion.recorded.write import write_motion_log

    return write_motion_log(robot, walk200, tmp_path_factory.mktemp("log") / "walk.csv",
                            derivatives=False)


def _edited(path: Path, column: str, row: int, value: str, out: Path) -> Path:
    """The log at ``path`` with ``value`` at ``row`` of ``column``; a ``contact_<LEG>`` column
    is the writer's ``stance_<LEG>`` renamed (a switch's column, as a robot logs it)."""
    lines = path.read_text().splitlines()
    if column.startswith("contact_"):
        lines[0] = lines[0].replace("stance_", "contact_")
    col = lines[0].split(",").index(column)
    fields = lines[row].split(",")
    fields[col] = value
    lines[row] = ",".join(fields)
    out.write_text("\n".join(lines) + "\n")
    return out


@pytest.mark.parametrize(("column", "value", "says"), [
    ("LF_femur", "inf", "column 'LF_femur', row 3 = inf"),
    ("contact_LF", "2", "column 'contact_LF', row 3 = 2.0; allowed: 0 (swing) or 1"),
    ("contact_LF", "0.3", "row 3 = 0.3"),
    ("stance_LF", "2", "column 'stance_LF', row 3 = 2.0; allowed: 0 (swing) or 1"),
])
def test_a_log_value_that_cannot_be_is_named_with_its_row(robot, log_csv, tmp_path, column,
                                                          value, says):
    bad = _edited(log_csv, column, 3, value, tmp_path / "bad.csv")
    with pytest.raises(IPE, match=re.escape(says)):
        hexaleg.load_motion(robot, bad)


def test_a_complex_npz_column_and_a_string_ignore_are_named(robot, log_csv, tmp_path):
    import numpy as np

    table = np.loadtxt(log_csv, delimiter=",", skiprows=1)
    names = log_csv.read_text().split("\n", 1)[0].split(",")
    arrays = {n.split(" [")[0]: table[:, i] for i, n in enumerate(names)}
    arrays["LF_femur"] = arrays["LF_femur"] + 5j
    np.savez(tmp_path / "c.npz", **arrays)
    with pytest.raises(CE, match=r"array 'LF_femur' is complex128.*real numeric"):
        hexaleg.load_motion(robot, tmp_path / "c.npz")
    with pytest.raises(IPE, match=r"invalid ignore = 'LF_coxa'.*a list of column names"):
        hexaleg.load_motion(robot, log_csv, ignore="LF_coxa")


def _design(design_json: Path, tmp_path: Path, edit: Callable[[dict], None]) -> Path:
    import json

    data = json.loads(design_json.read_text())
    edit(data)
    out = tmp_path / "design.json"
    out.write_text(json.dumps(data))
    return out


def _set(path: tuple, value):
    def edit(data):
        node = data
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    return edit


@pytest.mark.parametrize(("edit", "error", "says"), [
    (_set(("recommended", "springs", 0, "parameters", "stiffness", "value"), -1.0), IPE,
     "springs.LF_femur.stiffness = -1.0"),
    (_set(("recommended", "springs"), []), CE, "no springs"),
    (_set(("recommended", "saving", "electrical", "value"), 9999.0), IPE, "at most 100 %"),
    (_set(("settings", "metric"), "happiness"), IPE, "settings.metric = 'happiness'"),
    (_set(("gait", "parameters", "period"), -1.0), IPE, "period = -1.0"),
    (_set(("gait", "parameters", "bogus"), 1), UNE, "'bogus'"),
])
def test_report_reads_a_design_json_as_simulate_does(design_json, tmp_path, edit, error, says,
                                                     capsys):
    """A design.json whose springs, gait, metric or savings cannot be is named by report
    --design (it used to analyse the paper's design under the file's headline) and by
    simulate --springs alike."""
    bad = _design(design_json, tmp_path, edit)
    assert main(["report", "--design", str(bad), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err
    assert not (tmp_path / "r").exists()
    if error is not UNE or "bogus" not in says:
        assert main(["simulate", "--springs", str(bad), "--cycles", "2", "--out",
                     str(tmp_path / "s")]) == 2
        assert says in capsys.readouterr().err


@pytest.mark.parametrize(("doc", "says"), [
    ({"robots": "hexaleg", "springs": []}, "unknown key in the design file"),
    ({"robot": "hexaleg", "springs": [{"family": "linear", "joint": "LF_femur", "note": "x",
                                       "parameters": {"stiffness": {"value": 0.01,
                                                                    "unit": "N·m/rad"}}}]},
     "unknown key in the spring entry of LF_femur"),
])
def test_a_hand_written_design_file_s_keys_are_checked(tmp_path, doc, says, capsys):
    """A misspelt ``robots`` skipped the robot check; an entry's extra key was ignored."""
    import json

    path = tmp_path / "d.json"
    path.write_text(json.dumps(doc))
    assert main(["simulate", "--springs", str(path), "--cycles", "2", "--out",
                 str(tmp_path / "s")]) == 2
    assert says in capsys.readouterr().err
