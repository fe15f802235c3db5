"""The documentation site, checked without building it (the build is `mkdocs build --strict` in
CI): every public module gets an API page from docs/gen_api.py, every docs page is in the nav."""

from __future__ import annotations

import importlib.util
import itertools
import pkgutil
import sys
from collections.abc import Iterable
from pathlib import Path
from types import ModuleType

import yaml

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PACKAGE_DIR = ROOT / "src" / "hexaleg"


def _gen_api() -> ModuleType:
    """docs/gen_api.py imported as a module (it writes nothing unless run by mkdocs-gen-files)."""
    spec = importlib.util.spec_from_file_location("gen_api", DOCS / "gen_api.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[spec.name]
    return module


def _public_modules(path: Path, name: str) -> list[str]:
    """The package and its public modules as Python finds them (pkgutil, nothing imported)."""
    names = [name]
    for info in pkgutil.iter_modules([str(path)]):
        if info.name.startswith("_"):
            continue
        if info.ispkg:
            names += _public_modules(path / info.name, f"{name}.{info.name}")
        else:
            names.append(f"{name}.{info.name}")
    return names


def _nav_files(node: object) -> list[str]:
    """Every file or folder the nav of mkdocs.yml names, depth-first."""
    if isinstance(node, str):
        return [node]
    if isinstance(node, list):
        return [f for item in node for f in _nav_files(item)]
    if isinstance(node, dict):
        return [f for value in node.values() for f in _nav_files(value)]
    return []


def assert_quoted(page: str, log: str, pairs: Iterable[tuple[str, str]]) -> None:
    """Each pair's words on the page, and beside them in the log what it said: a figure the page
    quotes from a log a command wrote."""
    for words, said in pairs:
        assert words in page, words
        assert said in log, said


def _assert_run_row(part: str, log: str, run: str, covered: tuple[str, str],
                    tracking: tuple[str, str], saving: str) -> None:
    """A newcomer's table row on the page (stride covered and tracking RMS, springs / baseline,
    and the saving) and, in the log's per-run lines (``"<run> springs: walks, …"``), each run's
    figures beside it."""
    row = f"| {covered[0]} % / {covered[1]} % | {tracking[0]} / {tracking[1]} mrad | {saving} |"
    assert row in part, row
    for name, c, t in zip(("springs", "baseline"), covered, tracking, strict=True):
        line = log[log.index(f"{run} {name}: walks, "):].splitlines()[0]
        assert f"({c} %), tracking RMS {t} mrad" in line, line


def _mkdocs_config() -> dict:
    return yaml.safe_load((ROOT / "mkdocs.yml").read_text())


def test_every_public_module_gets_one_api_page():
    gen_api = _gen_api()
    pages = gen_api.api_pages()
    modules = [page.module for page in pages]
    expected = _public_modules(PACKAGE_DIR, "hexaleg")
    assert len(expected) > 10
    missing = sorted(set(expected) - set(modules))
    extra = sorted(set(modules) - set(expected))
    assert not missing, f"modules without an API page: {missing}"
    assert not extra, f"API pages for modules that are not in the package: {extra}"
    assert len(modules) == len(set(modules)), "a module has two pages"
    assert len({page.path for page in pages}) == len(pages), "two modules share a page"


def test_api_pages_start_with_the_public_surface_and_nest_by_package():
    gen_api = _gen_api()
    pages = gen_api.api_pages()
    assert pages[0].module == "hexaleg" and pages[0].path == "hexaleg.md"
    for page in pages:
        dotted_path = page.module.replace(".", "/")
        if page.is_package and page is not pages[0]:
            assert page.path == f"{dotted_path}/index.md"
            assert (ROOT / page.source).name == "__init__.py"
        else:
            assert page.path == f"{dotted_path}.md"
        assert (ROOT / page.source).is_file(), page.source
    # A package's modules follow it in the navigation (its section), never before it.
    seen: set[str] = set()
    for page in pages:
        parent = page.module.rpartition(".")[0]
        assert not parent or parent in seen, f"{page.module} comes before its package {parent}"
        seen.add(page.module)
    summary = gen_api.summary(pages)
    assert summary.splitlines()[0] == "* [hexaleg](hexaleg.md)"
    for page in pages:
        assert summary.count(f"]({page.path})") == 1, page.path


def test_private_modules_get_no_page(tmp_path: Path):
    gen_api = _gen_api()
    pkg = tmp_path / "pkg"
    for rel in ("__init__.py", "a.py", "_private.py", "__main__.py", "sub/__init__.py",
                "sub/b.py", "_hidden/__init__.py", "_hidden/c.py", "notapkg/d.py"):
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text('"""Doc."""\n')
    pages = gen_api.api_pages(tmp_path, "pkg")
    assert [p.module for p in pages] == ["pkg", "pkg.a", "pkg.sub", "pkg.sub.b"]
    assert [p.module for p in pages] == _public_modules(pkg, "pkg")


def test_every_docs_page_is_in_the_nav():
    config = _mkdocs_config()
    nav = _nav_files(config["nav"])
    pages = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
    assert "index.md" in pages
    missing = [p for p in pages if p not in nav]
    assert not missing, f"docs pages not in mkdocs.yml's nav: {missing}"
    for entry in nav:
        if entry == "reference/":  # generated at build time by gen_api.py
            continue
        assert (DOCS / entry).exists(), f"mkdocs.yml's nav names {entry}, which does not exist"
    assert "reference/" in nav, "the generated API reference is not in the nav"


def test_the_build_runs_the_walker_and_ci_builds_it_strict():
    config = _mkdocs_config()
    ci = (ROOT / ".ci" / "run").read_text()
    assert "mkdocs build --strict" in ci and '-e ".[docs]"' in ci
    plugins = {next(iter(p)) if isinstance(p, dict) else p: p for p in config["plugins"]}
    assert plugins["gen-files"]["gen-files"]["scripts"] == ["docs/gen_api.py"]
    assert "literate-nav" in plugins and "mkdocstrings" in plugins
    handler = plugins["mkdocstrings"]["mkdocstrings"]["handlers"]["python"]
    assert handler["paths"] == ["src"]
    assert handler["options"]["docstring_style"] == "google"
    assert config["theme"]["font"] is False  # no Google Fonts: the site works offline


def test_design_page_quotes_the_design_study_log():
    """docs/design.md's table is analysis/logs/design_hexaleg.log (itself diffed against the
    script by test_examples): every row of the log, energy, saving, magnitudes and geometry,
    stands in the page's table."""
    import re

    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "design_hexaleg.log").read_text()
    page = (root / "docs" / "design.md").read_text()
    cls = None
    rows = 0
    for line in log.splitlines():
        if line in ("coxa", "femur", "tibia"):
            cls = line
        m = re.match(r"  (.{26}) (\S+) J  saving\s+(\S+) %  (.*)$", line)
        if m and cls:
            label, energy, saving = (g.strip() for g in m.groups()[:3])
            assert f"| {cls} | {label} | {energy} | {saving} % | {m.group(4)} |" in page, line
            rows += 1
    assert rows == 21


def test_the_design_study_prints_no_angle_past_which_nothing_acts():
    """analysis/logs/design_hexaleg.log (and the page that quotes it): an angle whose stiffness and
    preload are 0 prints —, every other angle its value. The log printed the stiffening family's
    unused second stages at whatever angle the geometry search left (coxa above_2 +0.373, any
    angle giving the same 1.4851 J), and the dead zone's unused side likewise."""
    import re

    from hexaleg.design.families import family

    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "design_hexaleg.log").read_text()
    idle = 0
    for line in log.splitlines():
        m = re.match(r"  (\w+), searched .* %  (.*?)  \[(.*)\]$", line)
        if not m:
            continue
        fam = family(m.group(1))
        magnitudes = {k: float(v) for k, v in (e.split() for e in m.group(2).split(", "))}
        for entry in m.group(3).split(", "):
            name, value = entry.split()
            if name not in fam.angles:
                continue
            if all(magnitudes[k] == 0 for k in fam.stops[name]):
                assert value == "—", line
                idle += 1
            else:
                assert re.fullmatch(r"[+-]\d\.\d{3}", value), line
    assert idle == 9  # three stiffening designs' second stages (6), two dead zones, a preloaded


def test_design_page_quotes_the_placement_study_log():
    """docs/design.md's placement table is analysis/logs/placement_hexaleg.log, row by row."""
    import re

    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "placement_hexaleg.log").read_text()
    page = (root / "docs" / "design.md").read_text()
    family, rows = None, 0
    for line in log.splitlines():
        if m := re.match(r"(\w+): every set", line):
            family = m.group(1)
        if (m := re.match(r"  (\S+)\s+(\d\.\d{4})\s+(\S+)%\s+(\S+)%\s+(\S+)$", line)) and family:
            springs, energy, saving, old, gap = m.groups()
            assert f"| {family} | {springs} | {energy} | {saving} % | {old} % | {gap} |" in page, \
                line
            rows += 1
    assert rows == 14


def test_design_page_quotes_the_design_answer_log():
    """docs/design.md shows analysis/logs/answer_hexaleg.log (``hexaleg design``'s answer on the
    default robot, itself diffed against its script by test_examples) verbatim."""
    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "answer_hexaleg.log").read_text()
    page = (root / "docs" / "design.md").read_text()
    assert f"```text\n{log}```" in page


def test_bring_your_own_robot_quotes_the_test_robot():
    """docs/robots.md's five-line description is tests/data/spider.toml (which the tests load
    and run through every command)."""
    import tomllib

    root = Path(__file__).resolve().parents[1]
    page = (root / "docs" / "robots.md").read_text()
    block = page[page.index("## Bring your own robot"):].split("```toml\n")[1].split("```")[0]
    assert tomllib.loads(block) == tomllib.loads((root / "tests" / "data" / "spider.toml")
                                                 .read_text())


def test_robots_page_table_is_the_registry():
    """docs/robots.md's registry table: a row per registered robot, its mass and stand depth (the
    feet's mean depth below the base in the stand pose) as the loaded robot has them."""
    import re

    import numpy as np

    from hexaleg.robot.registry import DESCRIPTIONS, load

    page = (Path(__file__).resolve().parents[1] / "docs" / "robots.md").read_text()
    for name in DESCRIPTIONS:
        m = re.search(rf"^\| `{name}` \|.*\| ([\d.]+) kg \| ([\d.]+) m \|", page, re.MULTILINE)
        assert m, f"no row for {name} in docs/robots.md"
        robot = load(name)
        depth = -float(np.mean(robot.foot_positions(robot.pose("stand"))[:, 2]))
        mass, stand = m.groups()
        assert f"{robot.mass:.{len(mass.partition('.')[2])}f}" == mass, name
        assert f"{depth:.3g}" == stand, (name, depth)


def test_gaits_page_quotes_the_gait_study_logs():
    """docs/gaits.md's two tables are analysis/logs/gaits_hexaleg.log and gaits_solo12.log (each
    diffed against its script by test_examples), row by row."""
    import re

    root = Path(__file__).resolve().parents[1]
    page = (root / "docs" / "gaits.md").read_text()
    for name in ("gaits_hexaleg", "gaits_solo12"):
        log = (root / "analysis" / "logs" / f"{name}.log").read_text()
        rows = 0
        for line in log.splitlines():
            m = re.match(r"(\w+)\s+(\d\.\d{3})\s+([+-]\d+)°\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+"
                         r"(\S+)%$", line)
            if m:
                gait, v, slope, jm, cot, jm_s, cot_s, saving = m.groups()
                assert (f"| {gait} | {v} | {slope}° | {jm} | {cot} | {jm_s} | {cot_s} | "
                        f"{saving} % |") in page, line
                rows += 1
        assert rows == 27, name


def test_simulate_page_quotes_the_simulation_logs():
    """docs/simulate.md's tables are analysis/logs/simulate_hexaleg.log, row by row: the
    predicted/simulated energies, savings, distances and the sensitivity study (the single
    joint's tables are docs/paper.md's, below)."""
    import re

    logs = ROOT / "analysis" / "logs"
    page = (DOCS / "simulate.md").read_text()
    flat = page.replace("−", "-")
    rows = 0
    controller = None
    for line in (logs / "simulate_hexaleg.log").read_text().splitlines():
        if m := re.match(r"(feedforward|position) servo:", line):
            controller = m.group(1)
        m = re.match(r"  (predicted|\d\.\d+)\s+\| (\S+) / (\S+) \| (\S+) \| (\S+) \| (\S+) \|",
                     line)
        if m and not (m.group(1) == "predicted" and controller == "position"):
            _, with_, without, saving, joule, distance = m.groups()
            cells = [with_, without, saving, joule, f"{distance} mm"]
            assert re.search(r"\| " + r" \| ".join(re.escape(c) for c in cells).replace(
                re.escape(saving), r"\**" + re.escape(saving) + r"\**"), flat), line
            rows += 1
        m = re.match(r"    (.+?)\s+\| walks \((\w+)\) \| (\S+) \|", line)
        if m and m.group(1) not in ("other controller", "as set"):
            variant, _, saving = m.groups()
            table_row = next(r for r in flat.splitlines() if r.startswith("| ")
                             and variant.split(" (")[0] in r)
            column = 1 if controller == "feedforward" else 2
            assert table_row.split("|")[1 + column].strip().startswith(saving), (line, table_row)
            rows += 1
    assert rows == 9 + 15  # one variant does not walk (the position servo at gains ×0.25)


def test_paper_page_quotes_the_forward_study_log():
    """docs/paper.md's tables of the Adams experiment forward are analysis/logs/simulate_paper.log
    (diffed against its script by test_examples; ``hexaleg paper`` writes the same study): every
    required-torque row verbatim, the optima and savings of both metrics, their SI values and the
    paper's readings taken as the N·mm/deg they are labelled."""
    import re

    from hexaleg.units import nmm_per_deg_to_nm_per_rad

    log = (ROOT / "analysis" / "logs" / "simulate_paper.log").read_text()
    page = (DOCS / "paper.md").read_text()
    rows = re.findall(r"^  (rigid|Table 4, 400|k_M 713\.5|740)\s+peak (\S+) \| (\S+) \| (\S+); "
                      r"mean_abs (\S+) \| (\S+) \| (\S+); rms (\S+) \| (\S+) \| (\S+)$", log,
                      re.MULTILINE)
    assert len(rows) == 4
    for label, *values in rows:
        cells = [" \\| ".join(values[i:i + 3]) for i in (0, 3, 6)]
        assert f"| {label} | " + " | ".join(cells) + " |" in page, label
    optima = re.findall(r"optimum k: analytic closed form (\S+); simulated (\S+); with friction "
                        r"(\S+); the paper's Adams reading (\S+) \(k_M (\S+), k_E (\S+)\)", log)
    savings = re.findall(r"analytic (\S+) %, simulated (\S+) %, with friction (\S+) %", log)
    assert len(optima) == len(savings) == 2
    (m, ms), (e, es) = zip(optima, savings, strict=True)
    bold = r"\**"
    for label, i in (("analytic \\(closed form\\)", 0), ("forward simulation", 1),
                     ("forward simulation with Table 2 friction", 2)):
        assert re.search(rf"\| {label} \| {bold}{re.escape(m[i])}{bold} \({ms[i]} %\) \| "
                         rf"{bold}{re.escape(e[i])}{bold} \({es[i]} %\) \|", page), label
    assert re.search(rf"\| the paper's Adams reading \| {bold}{m[3]}{bold} \| {bold}{e[3]}"
                     rf"{bold} \|", page)
    assert f"| eq. 19 k_M, printed k_E | {m[4]} | {e[5]} |" in page
    si = [", ".join(f"{float(x) * 1e-6:.3e}" for x in (o[1], o[2], o[3])) for o in (m, e)]
    assert f"| in N·m/rad: forward, with friction, the paper's reading | {si[0]} | {si[1]} |" \
        in page
    labelled = [float(nmm_per_deg_to_nm_per_rad(float(o[3]))) for o in (m, e)]
    ratios = [f"{round(x / (float(o[1]) * 1e-6), -2):,.0f}".replace(",", " ")
              for x, o in zip(labelled, (m, e), strict=True)]
    assert (f"| {labelled[0]:.2f} N·m/rad ({ratios[0]} × the forward optimum) | "
            f"{labelled[1]:.2f} N·m/rad ({ratios[1]} ×) |") in page


def test_the_simulated_design_answer_in_the_prose_is_the_kept_log():
    """docs/design.md and docs/simulate.md quote the default design simulated forward (savings,
    the energies' gap to the prediction, the distance walked) at the precision they print, from
    analysis/logs/answer_hexaleg.log."""
    import re

    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "answer_hexaleg.log").read_text()
    rows = {}
    for label in ("feedforward + PD", "position only"):
        m = re.search(re.escape(label) + r"\s+(\S+) / (\S+) (\S+) / (\S+)\s+(\S+) % /\s+(\S+) %"
                      r"\s+(\S+) mm", log)
        assert m, log
        rows[label] = [float(x) for x in m.groups()]
    ew, sw, eb, sb, predicted, ff, distance = rows["feedforward + PD"]
    position = rows["position only"][5]
    gaps = sorted(100 * (1 - s / e) for s, e in ((sw, ew), (sb, eb)))
    design = " ".join((root / "docs" / "design.md").read_text().split())
    simulate = " ".join((root / "docs" / "simulate.md").read_text().split())
    assert (f"with feedforward + PD it saves {ff:.1f} % of the simulated electrical energy "
            f"against {predicted:.1f} % predicted (each energy {gaps[0]:.1f}–{gaps[1]:.1f} % "
            "below the prediction") in design
    assert f"walking {distance:.1f} of the planned 60 mm per cycle" in design
    assert f"position-only servo it saves {position:.1f} %, more than predicted" in design
    assert (f"save {ff:.1f} % under feedforward + PD and {position:.1f} % under the position "
            f"servo, against {predicted:.1f} % predicted") in simulate


def test_the_design_and_simulate_pages_lead_with_the_kept_answer():
    """docs/design.md and docs/simulate.md open with the recommendation (#29), its numbers those
    of analysis/logs/answer_hexaleg.log."""
    import re

    root = Path(__file__).resolve().parents[1]
    log = (root / "analysis" / "logs" / "answer_hexaleg.log").read_text()
    saving, net, grams = re.search(r"recommended: .*; electrical\s+(\S+) %, net\s+(\S+) % "
                                   r"\((\S+) g", log).groups()
    worst = re.search(r"tolerant\s+\S+ % /\s+(\S+) %", log).group(1)
    ff, pos = (re.search(re.escape(c) + r"\s+.* / +(\S+) % +\S+ mm", log).group(1)
               for c in ("feedforward + PD", "position only"))
    stop = re.search(r"hard stop at \+?(\S+)° from the centre", log).group(1)
    design = " ".join((root / "docs" / "design.md").read_text().split("## ")[0].split())
    simulate = " ".join((root / "docs" / "simulate.md").read_text().split("```")[0].split())
    assert (f"saving {saving} % of the energy the servos draw ({net} % net of their {grams} g), "
            f"{worst} % at worst with the stops ±1° off") in design
    assert f"they save {ff} % under feedforward + PD servos and {pos} % under" in design
    assert f"hard stop {stop}° from the centre" in design
    assert (f"saves {ff} % of the simulated electrical energy under feedforward + PD servos and "
            f"{pos} % under position-only servos, against {saving} % predicted") in simulate


def test_codesign_page_quotes_the_codesign_log():
    """docs/codesign.md's figures of the default robot are analysis/logs/codesign_hexaleg.log's
    (itself diffed against the example's output in CI): the chosen gait's J/m against the
    default gait, the simulated J/m under the worse servo, what the springs to buy keep under
    each servo and floor, and their predicted saving over the floors."""
    import re

    page = " ".join((ROOT / "docs" / "codesign.md").read_text().split())
    log = (ROOT / "analysis" / "logs" / "codesign_hexaleg.log").read_text()

    def logged(pattern: str) -> list[str]:
        found = re.search(pattern, log)
        assert found, pattern
        return list(found.groups())

    ratio, = logged(r"co-design / default gait without springs: ([\d.]+)")
    worse, best, predicted = logged(r"([\d.]+) J/m simulated under the worse \(the search's "
                                    r"best ([\d.]+) J/m\), predicted ([\d.]+) J/m")
    kept = {k: logged(rf"  {re.escape(k)}: keeps ([\d.]+) of")[0]
            for k in ("position only, mu 0.6", "position, mu 1", "feedforward + PD, mu 0.6",
                      "feedforward, mu 1")}
    floors = [float(x) for x in re.findall(r"mu [\d.]+ ([\d.]+) %", log)]
    assert f"{predicted} J/m predicted ({ratio} of the default gait" in page
    assert f"{worse} J/m simulated under the worse servo" in page
    assert f"and {best} J/m under position-only ones" in page
    assert (f"keep {kept['feedforward + PD, mu 0.6']} of that saving under feedforward servos "
            f"and {kept['position only, mu 0.6']} under position-only") in page
    assert f"{kept['feedforward, mu 1']} and {kept['position, mu 1']} on a grippier one" in page
    assert f"{min(floors):.1f}–{max(floors):.1f} %" in page


def test_simulate_page_quotes_the_sole_bipeds_design_log():
    """docs/simulate.md's line on the sole biped's design is
    analysis/bench_logs/design_biped6.log's answer (run by hand: 9 minutes)."""
    log = (ROOT / "analysis" / "bench_logs" / "design_biped6.log").read_text()
    page = " ".join((DOCS / "simulate.md").read_text().split())
    assert_quoted(page, log, (
            ('"fit dead_zone springs on hip_roll, hip_pitch, knee: electrical saving +32.42 %"',
             "fit dead_zone springs on hip_roll, hip_pitch, knee: electrical saving +32.42 %"),
            ("+31.92 % simulated under feedforward + PD and +33.44 % under position only",
             "simulated electrical saving feedforward + PD +31.92 %, position only +33.44 % "
             "(predicted +32.42 %)")))


def test_simulate_page_quotes_the_position_soles_log():
    """docs/simulate.md's account of why the bipeds on soles tipped under position servos (#54)
    is analysis/bench_logs/position_soles.log's: each figure it prints, beside the log's line
    (its runs about 3 minutes of CPU, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "position_soles.log").read_text()
    page = (DOCS / "simulate.md").read_text()
    part = page[page.index("### Position servos on soles: the sag"):
                page.index("## The built-in robot: predicted vs simulated")]
    biped = log[log.index("biped6, deflection off"):log.index("biped6, deflection on")]
    after = log[log.index("biped6, deflection on"):log.index("talos, deflection off")]
    talos = log[log.index("talos, deflection off"):log.index("talos, deflection on")]
    now = log[log.index("# ===== per step"):]  # the plan's torque at every step
    after = now[now.index("biped6, deflection on"):now.index("talos, deflection off")]
    talos_after = now[now.index("talos, deflection on"):]
    quoted = [  # (the page's words, the part of the log, its words)
        ("(7.24 N·m on its sole)", biped, "m g a = 7.24 N·m"),
        ("+11.18 N·m and the servo gives +0.40", biped,
         "  0.12    S.     -2.3 |   +11.18     +0.40"),
        ("(+15.28 of +16.12)", biped, "|   +16.12    +15.28"),
        ("+20.42 against +13.29 at 0.24 s", biped, "  0.24    S.    +20.2 |   +13.29    +20.42"),
        ("+1.90 against +4.47 at 0.36 s", biped, "  0.36    S.    +17.3 |    +4.47     +1.90"),
        ("from −2.3 to +25.4 mrad", biped, "  0.28    S.    +25.4 |"),
        ("+18.9 mm at 0.18 s", biped, "|   179.9   +18.9"),
        ("−45.0 mm (its edge) at 0.36 s", biped, "|    93.0   -45.0"),
        ("(48.71 N·m on its sole)", talos, "m g a = 48.71 N·m"),
        ("+70.46 N·m and the\n  servo gives −5.46", talos,
         "  0.30    S.     -2.2 |   +70.46     -5.46"),
        ("+18.25 N·m at most", talos, "    +18.25 |"),
        ("+49.2 mm of the 55 mm half-width at 0.36 s", talos, "|   534.7   +49.2"),
        ("+66.9 mrad at 1.30 s (the hip roll then 89 mrad off)", talos,
         "  1.30    S.    +66.9 |   +79.58    +89.77       -89"),
        ("falls at 2.96 s", talos, "fell the robot fell at t = 2.9610 s"),
        ("| asked for Δτ only (before) | 0.0 mm | 47.5 % of stance | 115.29 | 2.08° |", log,
         "single-support margin   0.0 mm (R1 right), soles off 47.5 % of stance, 132.3 mm,  "
         "115.29 J (plan 105.99), roll max 2.08°"),
        ("| same, open loop | 0.0 mm | 60.0 % | 132.61 | 2.36° |", log,
         "soles off 60.0 % of stance, 139.1 mm,  132.61 J (plan 105.99), roll max 2.36°"),
        ("| same, kp × 4 | 0.0 mm | 50.9 % | 118.98 | 1.00° |", log,
         "soles off 50.9 % of stance, 133.2 mm,  118.98 J (plan 105.99), roll max 1.00°"),
        ("| 0.0 mm | 77.1 % | 118.04 | 1.14° |", log,
         "soles off 77.1 % of stance, 131.2 mm,  118.04 J (plan 105.99), roll max 1.14°"),
        ("| asked for τ* + Δτ (now) | 26.3 mm | 0.0 % | 103.62 | 0.58° |", now,
         "single-support margin  26.3 mm (L1 right), soles off  0.0 % of stance, 131.2 mm,  "
         "103.62 J (plan 105.99), roll max 0.58°"),
        ("| same, kp × 4 | 38.9 mm | 0.0 % | 104.57 | 0.04° |", now,
         "single-support margin  38.9 mm (R1 left), soles off  0.0 % of stance, 129.9 mm,  "
         "104.57 J (plan 105.99), roll max 0.04°"),
        ("+10.81 and +67.91 N·m, 26.0 mm\nof single-support margin, 103.69 J", log,
         "single-support margin  26.0 mm (R1 left), soles off  0.0 % of stance, 131.1 mm,  "
         "103.69 J (plan 105.99)"),
        ("| feedforward + PD | 43.7 mm | 0.0 % | 105.71 | 0.02° |", log,
         "single-support margin  43.7 mm (R1 right), soles off  0.0 % of stance, 130.0 mm,  "
         "105.71 J (plan 105.99), roll max 0.02°"),
        ("+11.07 of +11.18 N·m", after, "  0.12    S.     -0.8 |   +11.18    +11.07"),
        ("+68.02 of +70.46", talos_after, "  0.30    S.     -0.4 |   +70.46    +68.02"),
        ("11.3 and 11.7 mrad at most", after, "  0.34    S.    +11.3 |"),
        ("11.3 and 11.7 mrad at most", talos_after, "  0.96    S.    +11.7 |"),
        ("28.0 and 11.4 mm of its centre", after, "|   163.9   -28.0"),
        ("28.0 and 11.4 mm of its centre", talos_after, "|   904.0   -11.4"),
        ("37 mrad RMS on the test biped", log, "| springs | walks | 37 / 158 |"),
        ("spends 12.04 J instead\nof 12.47 J (plan 12.29 J)", log,
         "feet off  0.0 % of stance, 119.9 mm,   12.04 J (plan 12.29)"),
        ("spends 12.04 J instead\nof 12.47 J (plan 12.29 J)", log,
         "feet off  0.0 % of stance, 120.5 mm,   12.47 J (plan 12.29)"),
        ("rolls 0.13°\ninstead of 1.52°", log, "12.04 J (plan 12.29), roll max 0.13°"),
        ("rolls 0.13°\ninstead of 1.52°", log, "12.47 J (plan 12.29), roll max 1.52°"),
    ]
    for words, where, said in quoted:
        assert words in part, words
        assert said in where, said
    # the simulate command's runs under the position servo, after (the page's biped table)
    assert_quoted(page, log, (
            ("| position | springs | 130.6 mm | 73.06 → 70.28 (−3.8 %) | walks |",
             "position springs (per step): walks, distance 130.6 mm per cycle, "
             "electrical per cycle [70.18158557366124, 70.37192786513137] J, mean "
             "70.28 J"),
            ("| position | baseline | 130.5 mm | 105.99 → 104.04 (−1.8 %) | walks |",
             "position baseline (per step): walks, distance 130.5 mm per cycle, "
             "electrical per cycle [103.93640397988032, 104.13538982312578] J, mean "
             "104.04 J"),
            ("simulated +30.72 % under feedforward and +32.45 % under the position\n"
             "servo", "simulated +32.45 % (70.28 J vs 104 J)"),
            ("27.4 mm (springs) and\n24.9 mm (baseline)",
             "in single support 27.4 mm from the R1 sole's left edge"),
            ("27.4 mm (springs) and\n24.9 mm (baseline)",
             "in single support 24.9 mm from the R1 sole's left edge"),
            ("off the ground in 3.4 % and\n0 % of their stance",
             "contact losses 3.38 %, normal force RMS error 16.0 N"),
            ("16.0 and 15.4 N RMS off the plan",
             "contact losses 0.00 %, normal force RMS error 15.4 N")))


def test_simulate_page_quotes_the_talos_log():
    """docs/simulate.md's Talos paragraph (its soles, issue #54) is
    analysis/bench_logs/simulate_talos.log's: each figure it prints, beside what the log says."""
    log = (ROOT / "analysis" / "bench_logs" / "simulate_talos.log").read_text()
    page = (DOCS / "simulate.md").read_text()
    talos = page[page.index("**Talos**"):page.index("simulate_talos.log`. They are not")]
    quoted = [  # (the page's words, the log's)
        ("planned stride 491.9 mm", "Distance per cycle: 491.9 mm (planned 491.9 mm)"),
        ("1003.9 → 1001.1", "springs 1003.89 -> 1001.14"),
        ("2121.1 → 2114.9", "baseline 2121.07 -> 2114.90"),
        ("| position | springs | 492.3 mm",
         "position springs (per step): walks, distance 492.3 mm"),
        ("| position | baseline | 492.4 mm",
         "position baseline (per step): walks, distance 492.4 mm"),
        ("1003.9 → 1038.7 (+3.5 %)", "mean 1038.66 J"),
        ("2121.1 → 2223.1 (+4.8 %)", "mean 2223.11 J"),
        ("the saving is +53.28 % simulated", "(electrical 1004 J vs 2121 J per cycle); "
                                               "simulated +53.28 % (1039 J vs 2223 J)"),
        ("to 16.0 mrad RMS", "| springs | walks | 16 / 101 |"),
        ("47.8 mm (springs) and 48.2 mm (baseline)",
         "in single support 47.8 mm from the R1 sole's left edge"),
        ("47.8 mm (springs) and 48.2 mm (baseline)",
         "in single support 48.2 mm from the L1 sole's right edge"),
        ("2.3 % and 1.8 % of their stance", "contact losses 2.34 %"),
        ("2.3 % and 1.8 % of their stance", "contact losses 1.79 %"),
        ("fell at 2.96 s (roll 45°)", "fell at t = 2.9610 s: base roll +45.0°"),
        ("+52.66 % simulated against +52.67 % predicted",
         "predicted saving +52.67 % (electrical 1004 J vs 2121 J per cycle); simulated +52.66 %"),
        ("0.11 mrad RMS", "| springs | walks | 0.107 /"),
        ("53.9 mm inside", "springs: 53.9 mm from the L1 sole's right edge"),
        ("66 N·m RMS on the hip roll", "leg_left_2_joint: plan's stance torque 65.6 N·m RMS"),
        ("97 N·m on the knee", "leg_left_4_joint: plan's stance torque 96.6 N·m RMS"),
        ("kp of 988 and 1852 N·m/rad: 66 and 52 mrad", "kp 988 N·m/rad: sag 66.4 mrad"),
        ("kp of 988 and 1852 N·m/rad: 66 and 52 mrad", "kp 1852 N·m/rad: sag 52.2 mrad"),
        ("up to 13.0 mrad (3.2 mrad RMS; 0.2 mrad under feedforward)",
         "position springs: soles within 5 mm of the ground tilt 13.0 mrad at most, 3.2 RMS"),
        ("0.2 mrad under feedforward", "feedforward springs: soles within 5 mm of the ground "
                                       "tilt 0.2 mrad at most"),
        ("sinks only 0.17 mm", "lowest sole centre -0.17 mm"),
        ("`cop_margin` 0.0 mm", "springs: -0.000239 mm from the L1 sole's heel edge"),
        ("17.6 % of stance samples", "| 17.6 |"),
        ("194 N RMS", "| 194 |"),
        ("at 5.24 s instead of 2.96 s", "fell at t = 5.2447 s"),
        ("leaned 2.8° outward over the\nright foot at 1.76 s", "t 1.761 roll  +2.80"),
        ("first\nright single support (1.87 s)", "t 1.872 roll  +2.60  L1 off | R1"),
        ("outer edge\nfor the whole stance (55 mm", "R1    905 N u  +44.7 v  -55.0 mm"),
        ("from 1.9° to 9° by 2.37 s",
         "t 2.368 roll  +8.84  L1 off | R1    516 N u   -7.4 v  -55.0"),
        ("left the ground at 2.48 s", "t 2.479 roll +12.98  L1 off | R1 off"),
        ("+26.97 % against +27.03 % predicted",
         "feedforward + PD +26.97 % (predicted +27.03 %)"),
        ('"fit one_sided … +27.03 %", simulated\n+26.97 %', "fit one_sided, spring torque ≤ "
         "21.15 N·m springs on hip_roll, knee: electrical saving +27.03 %"),
        ("simulated\n+26.97 %", "simulated electrical saving feedforward + PD +26.97 % "
                                 "(predicted +27.03 %); WARNING"),
        ('"unproven (under position only the runs did not walk',
         "unproven (under position only the runs did not walk (springs fell; baseline fell))"),
        ("Now it proves the same answer under both servos:\n\"fit one_sided, spring torque ≤ "
         "21.15 N·m springs on hip_roll, knee: electrical saving\n+27.03 %\", simulated +26.97 % "
         "under feedforward + PD and +26.99 % under position only",
         "fit one_sided, spring torque ≤ 21.15 N·m springs on hip_roll, knee: electrical saving "
         "+27.03 % (+24.37 % net of 1601.0 g of springs); worst case over the maps +14.72 % at "
         "period ×0.5, stride ×1.5; hard stops needed: hip_roll (below) at -17.3° from its "
         "centre of motion (S_y/σ 1.11 without), knee (above) at +47.5° from its centre of "
         "motion (S_y/σ 1.03 without); simulated electrical saving feedforward + PD +26.97 %, "
         "position only +26.99 % (predicted +27.03 %)"),
        ("+27.00 % while the position servo's τ* was held",
         "position only +27.00 % (predicted +27.03 %)"),
    ]
    assert_quoted(talos, log, quoted)


def test_robots_page_quotes_the_design_bench_log():
    """docs/robots.md's table of the design's time and memory per robot (issue #55) is
    analysis/bench_logs/bench_robots.log's design rows on a quiet machine: each robot's wall and
    CPU seconds and the larger of its main and worker peak MB as a row of the log prints them,
    and every figure within the issue's 60 s and 1 GB."""
    log = (ROOT / "analysis" / "bench_logs" / "bench_robots.log").read_text()
    page = (DOCS / "robots.md").read_text()
    table = page[page.index("### The design's time and memory per robot"):
                 page.index("### The co-design's time and memory per robot")]
    rows = [[c.strip() for c in line.split("|")[1:6]] for line in table.splitlines()
            if line.startswith("| ") and not line.startswith("| robot")]
    assert len(rows) == 15, rows  # the 6 registered robots and bench_robots' 9 test robots
    printed = {(w[0], w[2], w[4], str(max(int(w[6]), int(w[7]))))
               for w in (line.split() for line in log.splitlines() if not line.startswith("#"))
               if len(w) > 7 and w[1] == "design"}
    for robot, wall, cpu, peak, recommended in rows:
        assert (robot, wall, cpu, peak) in printed, (robot, wall, cpu, peak)
        assert float(wall) <= 60 and int(peak) <= 1024, robot
        assert recommended.startswith("refused") or any(
            f"{robot:12s} design" in line and f"recommended {recommended}" in line
            and f" {wall} " in line for line in log.splitlines()), (robot, recommended)
    prose = " ".join(table.split())
    assert_quoted(prose, log, (
            ("Solo-12's took 66.3 s the round before, recommending preloaded springs whose "
             "stop-tolerance search took 35 s", "solo12       design       66.3      4.65    "
             "95.7  1.44      818       305  ok, recommended preloaded (slowest stages: "
             "tolerance 35 s"),
            ("The brushless hexapod took 61.9 s two rounds ago and 27.1 s",
             "bldc_hexapod 61.9 -> 27.1 s quiet")))


def test_robots_page_quotes_the_codesign_bench_log():
    """docs/robots.md's table of the co-design's time and memory per robot (issue #55) is
    analysis/bench_logs/bench_robots.log's codesign rows: each robot's CPU seconds and the
    largest process's peak MB, and the quiet runs' wall and CPU seconds, as that log's row for
    it prints them."""
    log = (ROOT / "analysis" / "bench_logs" / "bench_robots.log").read_text()
    page = (DOCS / "robots.md").read_text()
    table = page[page.index("### The co-design's time and memory per robot"):]
    rows = [line.split("|")[1:5] for line in table.splitlines()
            if line.startswith("| ") and not line.startswith("| robot")]
    assert len(rows) == 15, rows  # the 6 registered robots and bench_robots' 9 test robots
    printed = {}
    for line in log.splitlines():  # robot, command, wall, x default, CPU s, share, peak, worker
        words = line.split()
        if len(words) > 7 and words[1] == "codesign" and not line.startswith("#"):
            printed.setdefault(words[0], []).append(
                (words[2], words[4], str(max(int(words[6]), int(words[7])))))
    for robot, cpu, peak, note in ((c.strip() for c in row) for row in rows):
        assert (cpu, peak) in [r[1:] for r in printed.get(robot, [])], (robot, cpu, peak)
        if note.startswith("quiet: "):
            wall, quiet_cpu = note.removeprefix("quiet: ").replace(" s CPU", "").split(
                " s wall, ")
            assert (wall, quiet_cpu) in [r[:2] for r in printed[robot]], (robot, note)
    prose = " ".join(table.split())
    log_words = " ".join(log.split())
    assert_quoted(prose, log_words, (  # (the page's words, the log's)
            ("31–40 iterations, 0.39–0.50 s of CPU", "the gait 0.39-0.50 s (its ZMP sway, 31-40 "
                                                    "iterations"),
            ("244 s of CPU for its 183 candidates", "co-design search 244.2 s (183 evaluations"),
            ("the gait-alone search's 200 took 97 s", "gait-alone search 97.4 s (200 evaluations"),
            ("about 0.8 s to each candidate", "about 0.8 s the inner spring program")))


def test_simulate_page_quotes_the_newcomers_round_hyq():
    """docs/simulate.md's four more example-robot-data quadrupeds (#54: HyQ, Solo-8,
    quadruped_description, anymal-kinova) are newcomers_simulate.log's block "round hyq": each
    table row beside the block's per-run line and summary, and the diagnosis' figures."""
    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    now = log[log.index("# ===== round hyq"):]
    page = (DOCS / "simulate.md").read_text()
    part = " ".join(page[page.index("Four more example-robot-data quadrupeds"):
                         page.index("The Adams model's printed-units")].split())
    part += " " + " ".join((DOCS / "robots.md").read_text().split())
    hyq, soft, odri = ("hyq.toml --config hyq_dt.toml", "hyq.toml --config hyq_soft.toml",
                       "solo8_odri.toml --config trot.toml")
    runs = {  # (label in the block, servo, command): (stride covered, tracking RMS, saving)
        ("hyqdt", "position", hyq): (("99.4", "99.5"), ("24", "24"), "+33.70 % (+33.68 %)"),
        ("hyqdt", "feedforward", hyq): (("100.0", "100.0"), ("0", "0"), "+33.75 %"),
        ("hyqsoft", "position", soft): (("99.2", "99.4"), ("23", "24"), "+34.03 % (+33.68 %)"),
        ("hyqsoft", "feedforward", soft): (("100.0", "100.0"), ("1", "1"), "+33.96 %"),
        ("solo8odri", "position", odri): (("100.1", "100.1"), ("7", "8"),
                                          "+31.91 % (+31.58 %)"),
        ("solo8odri", "feedforward", odri): (("100.0", "100.0"), ("1", "1"), "+31.69 %"),
        ("anymalk", "position", "anymalk.toml"): (("98.9", "98.7"), ("20", "21"),
                                                  "+22.29 % (+22.09 %)"),
        ("anymalk", "feedforward", "anymalk.toml"): (("99.3", "99.1"), ("2", "3"), "+22.34 %")}
    for (label, servo, toml), (covered, tracking, saving) in runs.items():
        _assert_run_row(part, now, f"{label} {servo}", covered, tracking, saving)
        command = now[now.index(f"--robot {toml} --controller {servo}"):]
        summary = next(line for line in command.splitlines() if "servo, balance feedback)" in line)
        simulated, _, predicted = saving.partition(" (")
        assert f"({servo} servo" in summary and f"simulated {simulated} (" in summary, summary
        assert not predicted or f"predicted saving {predicted.rstrip(')')} (" in summary
    for row, said in (
            ("| 110.0 % / 103.2 % | 86 / 101 mrad |", "hyq feedforward springs: walks, 433.3 mm "
                                                      "per cycle of 393.9 mm (110.0 %), tracking "
                                                      "RMS 86 mrad"),
            ("| 110.0 % / 103.2 % | 86 / 101 mrad |", "(103.2 %), tracking RMS 101 mrad"),
            ("fell at 3.28 s / stalled (−28.9 %) | — / 279 mrad",
             "hyq position springs: fell: the robot fell at t = 3.2844 s"),
            ("fell at 3.28 s / stalled (−28.9 %) | — / 279 mrad",
             "(-28.9 %), tracking RMS 279 mrad"),
            ("| 74.8 % / 59.9 % | 37 / 49 mrad |", "(74.8 %), tracking RMS 37 mrad"),
            ("| 74.8 % / 59.9 % | 37 / 49 mrad |", "(59.9 %), tracking RMS 49 mrad"),
            ("| 72.7 % / 70.8 % | 39 / 41 mrad |", "(72.7 %), tracking RMS 39 mrad"),
            ("| 72.7 % / 70.8 % | 39 / 41 mrad |", "(70.8 %), tracking RMS 41 mrad")):
        assert_quoted(part, now, ((row, said),))
    assert_quoted(part, now, (
        ("(−30.5 % and 23.2 % of its stride, feet slipping up to 446 mm)",
         "hyqcrawl feedforward springs: stalled, -120.0 mm per cycle of 393.9 mm (-30.5 %)"),
        ("(−30.5 % and 23.2 % of its stride, feet slipping up to 446 mm)", "slip max 446 mm"),
        ("(100.6 % and 100.2 %, 1215 J against the plan's 1199 J)",
         "hyq (feedforward servo): predicted saving +67.83 % (electrical 1199 J vs 3728 J per "
         "cycle); simulated +67.43 % (1215 J vs 3730 J)"),
        ("(100.6 % and 100.2 %, 1215 J against the plan's 1199 J)", "(100.6 %)"),
        ("the first 40 ms where the plan gives it 371 N",
         "0.040 sim tau rf_hfe  -168.8 plan   -13.8 | sim F_RF [0 0 0] plan [-86  33 379]"),
        ("the first 40 ms where the plan gives it 371 N", "plan RF force first [[-84.9  30.2 "
                                                          "371.5]"),
        ("its hip driven 185 mrad off", "0.040   -11    +0    -1   -13    -1    -0    +8  +185"),
        ("its body's mass (2 kg, MuJoCo's `body_invweight0`), but HyQ's foot at the end of its "
         "0.35-m shank moves with 0.34 kg", "LF body_invweight0 mass 2 kg foot effective mass: "
                                             "free 0.336 kg"),
        ("(ANYmal's from 0.4 to 0.09 ms)", "anymal: dt 0.4000 ms"),
        ("(ANYmal's from 0.4 to 0.09 ms)", "anymal: dt 0.0877 ms"),
        ("at the automatic 0.24 ms", "hyq.toml: dt 0.2421 ms"),
        ("(ω_n/ω_gait 7.8 at its least joint, ANYmal's 8.1)", "w_n/w_gait min 7.804"),
        ("(ω_n/ω_gait 7.8 at its least joint, ANYmal's 8.1)", "w_n/w_gait min 8.062"),
        ("at most 0.29 of μ 0.6", "friction use: median 0.233  p90 0.278  max 0.289"),
        ("its plan needs μ ≥ 1.14", "the least friction that admits forces here is μ = 1.14"),
        ("its bound needs μ 0.947", "its default bound needs μ 0.947"),
        ("the default bound is refused — its plan on the front pair needs μ ≥ 1.14 on a floor "
         "of 0.6", "the least friction that admits forces here is μ = 1.14"),
        ("(B1's position run", "b1 (position servo, balance feedback): predicted saving "
                               "+33.34 % (electrical 1313 J vs 1970 J per cycle); simulated "
                               "+30.22 % (1517 J vs 2174 J)")))


def test_simulate_page_quotes_the_newcomers_log():
    """docs/simulate.md's quadrupeds new to hexaleg (#54: Go1, B1, Laikago described as a
    newcomer would, their sized trots) are analysis/bench_logs/newcomers_simulate.log's block
    after the plan's torque went into a position servo's reference at every step: each table
    row and figure beside the log's line (its runs about 20 s of CPU each, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    now = log[log.index("# ===== per step"):]
    page = (DOCS / "simulate.md").read_text()
    part = " ".join(page[page.index("Quadrupeds new to hexaleg under position servos"):
                         page.index("The Adams model's printed-units")].split())
    runs = {  # (robot, servo): (stride covered, tracking RMS, saving) per the page's table
        ("go1", "position"): (("99.9", "98.4"), ("18", "18"), "+33.13 % (+36.75 %)"),
        ("go1", "feedforward"): (("102.0", "101.3"), ("18", "19"), "+32.04 %"),
        ("b1", "position"): (("99.1", "101.6"), ("25", "26"), "+30.18 % (+33.34 %)"),
        ("b1", "feedforward"): (("98.7", "98.1"), ("18", "21"), "+30.04 %"),
        ("laikago", "position"): (("90.6", "96.5"), ("47", "68"), "+23.67 % (+32.02 %)"),
        ("laikago", "feedforward"): (("96.3", "95.5"), ("9", "12"), "+32.99 %")}
    for (robot, servo), (covered, tracking, saving) in runs.items():
        _assert_run_row(part, now, f"{robot} {servo}", covered, tracking, saving)
        summary = next(line for line in now.splitlines()
                       if line.startswith(f"{robot} ({servo} servo, balance feedback)"))
        simulated, _, predicted = saving.partition(" (")
        assert f"simulated {simulated} (" in summary, summary
        assert not predicted or f"predicted saving {predicted.rstrip(')')} (" in summary
    assert_quoted(part, now, (
            ("1124 and 1473 J a cycle", "laikago (position servo, balance feedback): predicted "
                                         "saving +32.02 % (electrical 392.5 J vs 577.3 J per "
                                         "cycle); simulated +23.67 % (1124 J vs 1473 J)"),
            ("position 3.67 and 4.25 s", "laikago position springs: fell: the robot fell at "
                                         "t = 3.6695 s"),
            ("position 3.67 and 4.25 s", "laikago position baseline: fell: the robot fell at "
                                         "t = 4.2494 s"),
            ("B1's position baseline at 6.37 s", "b1 position baseline: fell: the robot fell at "
                                                 "t = 6.3684 s"),
            ("feedforward + PD 4.76 and 4.66 s", "springs  {'cycles': '8', 'controller': "
                                                 "'feedforward'}                 fell   t 4.76"),
            ("feedforward + PD 4.76 and 4.66 s", "baseline {'cycles': '8', 'controller': "
                                                 "'feedforward'}                 fell   t 4.66"),
            ("Laikago 96.8 % and 102.9 % of its stride at 19 and 31 mrad",
             "'SWING': '0.0001'}                           walks  t 6.41 roll 0.091 pitch 0.049 "
             "sat 0.000 cons 0.02 dist  96.8% track   19 mrad"),
            ("Laikago 96.8 % and 102.9 % of its stride at 19 and 31 mrad",
             "dist 102.9% track   31 mrad"),
            ("B1 99.8 % and 100.2 %", "dist  99.8% track   25 mrad"),
            ("B1 99.8 % and 100.2 %", "dist 100.2% track   27 mrad"),
            ("(151 and 197 J against 121 and 162 J)", "dist  99.0% track   20 mrad slip   33 mm "
                                                       "E 151.0"),
            ("(151 and 197 J against 121 and 162 J)", "dist  99.1% track   21 mrad slip   48 mm "
                                                       "E 197.0"),
            ("(151 and 197 J against 121 and 162 J)", "dist 100.0% track   14 mrad slip    3 mm "
                                                       "E 120.9"),
            ("(151 and 197 J against 121 and 162 J)", "dist  99.8% track   14 mrad slip    4 mm "
                                                       "E 162.4"),
            ("rolls 0.10 rad instead of 0.01", "roll 0.100 pitch 0.066"),
            ("Laikago's feedforward + PD, where", "'SWING': '0.0001'} walks  t 6.41 roll 0.071")))


def test_simulate_page_quotes_the_foot_placement_log():
    """docs/simulate.md's table of the trots under Raibert's foot placement (#54: 8 cycles under
    both servos) is newcomers_simulate.log's block "Raibert's foot placement": each row's
    rolls, slips and savings beside the log's lines (runs of 10–60 s of CPU each, by hand)."""
    import re

    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    block = log[log.index("# ===== Raibert's foot placement"):]
    eight = block[:block.index("## 16 cycles")]
    rerun = log[log.index("# --- the foot placement's 8-cycle table again"):]
    page = (DOCS / "simulate.md").read_text()
    part = page[page.index("**Raibert's foot placement**"):page.index("The Adams model's")]
    names = {"Laikago": "laikago", "B1": "b1", "Go1": "go1", "ANYmal with": "kinova",
             "Go2": "go2"}
    robot, rows = None, 0
    for line in part.splitlines():
        m = re.match(r"\|\s*(.*?)\s*\| (position|feedforward \+ PD) \| (\S+) / (\S+) rad \| "
                     r"(\d+) / (\d+) mm \| (\S+ %)", line)
        if not m:
            continue
        label, servo, *figures, saving = m.groups()
        robot = next((v for k, v in names.items() if label.startswith(k)), robot)
        servo = servo.split()[0]
        runs = eight if robot == "kinova" else rerun  # the others' timesteps moved: rerun
        for name, roll, slip in (("springs", figures[0], figures[2]),
                                 ("baseline", figures[1], figures[3])):
            assert re.search(rf"8_{robot}_{servo} +{name} +walks +roll max {roll} rad, "
                             rf"slip max +{slip} mm", runs), (robot, servo, name)
        command = (f"--robot {robot}.toml" if robot != "go2" else
                   "--robot go2 --config trot_go2.toml") + f" --controller {servo} --cycles 8"
        summary = runs[runs.index(command):]
        assert f"simulated {saving} (" in summary.splitlines()[1], (robot, servo)
        rows += 1
    assert rows == 10
    sixteen = block[block.index("## 16 cycles"):block.index("## the experiments")]
    assert_quoted(" ".join(part.split()), block, (
        ("walks 16 cycles under both (+32.35 % and +32.14 %)", "simulated +32.35 % (391.2 J"),
        ("walks 16 cycles under both (+32.35 % and +32.14 %)", "simulated +32.14 % (389.5 J"),
        ("(391 and 578 J a cycle against 392.5 and 577.3 J)", "(electrical 392.5 J vs 577.3 J "
                                                              "per cycle); simulated +32.34 % "
                                                              "(391 J vs 578 J)"),
        ("(1703 and 2579 J a cycle under position servos against 1313 and 1970 J)",
         "(electrical 1313 J vs 1970 J per cycle); simulated +33.97 % (1703 J vs 2579 J)"),
        ("(+31.23 % simulated against +25.20 %)", "predicted saving +25.20 % (electrical 172.1 "
                                                  "J vs 230.1 J per cycle); simulated +31.23 %"),
        ("rolling at most 0.037 rad", "8_anymal_c_position            baseline walks    roll "
                                      "max 0.037 rad"),
        ("anymal-kinova 15 (+22.73 % and +22.21 %", "simulated +22.73 % (301 J vs 389.6 J); "
                                                    "distance 320.9 mm"),
        ("anymal-kinova 15 (+22.73 % and +22.21 %", "simulated +22.21 % (309 J vs 397.2 J)")))
    whole = " ".join(page.split())
    placed = block[:block.index("## the test quadrupeds' trots of docs/simulate.md, 'Stands on "
                                "two point feet', again")]
    again = block[block.index("'Stands on two point feet', again"):]
    assert_quoted(whole, placed, (
        ("83 % and 84 % before", "(83%), outside ±10%"),
        ("83 % and 84 % before", "(84%), outside ±10%"),
        ("+14.06 % and +13.71 % at the old timesteps", "simulated +14.06 % (7.078 J vs 8.236 J)"),
        ("+14.06 % and +13.71 % at the old timesteps", "simulated +13.71 % (9.172 J vs 10.63 J)"),
        ("+16.94, +17.85 and +15.80 %", "simulated +16.94 % (209 J"),
        ("+16.94, +17.85 and +15.80 %", "simulated +17.85 % (208.4 J"),
        ("+16.94, +17.85 and +15.80 %", "simulated +15.80 % (204.5 J")))
    assert_quoted(whole, again, (  # the table and its prose at the foot points' timesteps
        ("| short / short (86 %, 86 %) | +16.48 % / — |", "(86%), outside ±10%"),
        ("| +16.71 % / +17.01 % |", "simulated +17.01 % (208.3 J vs 251 J)"),
        ("| +16.71 % / +17.49 % |", "simulated +17.49 % (211.8 J vs 256.7 J)"),
        ("| +15.65 % / +15.87 % |", "simulated +15.87 % (203.7 J vs 242.1 J)"),
        ("| +16.48 % / +14.39 % |", "simulated +14.39 % (6.868 J vs 8.022 J)"),
        ("| +17.88 % / +14.40 % |", "simulated +14.40 % (8.136 J vs 9.506 J)"),
        ("(+17.01, +17.49 and +15.87 %)", "simulated +15.87 %"),
        ("fell / fell (2.51 s, height)", "xquad_2.34_feedforward springs fell: the robot fell "
                                         "at t = 2.5089 s: base height"),
        ("fell / fell (2.51 s, height)", "xquad_2.34_feedforward baseline fell:"),
        ("fell / fell (2.19 s, roll)", "pryquad_1.44_feedforward springs fell: the robot fell "
                                       "at t = 2.1855 s: base roll"),
        ("fell / fell (2.19 s, roll)", "pryquad_1.44_feedforward baseline fell:")))
    assert sixteen.count("simulated +") == 8 and "fell" not in sixteen


def test_design_page_quotes_solo12s_answer_under_foot_placement():
    """docs/design.md's Solo-12 answer once the trot's swing feet are placed by Raibert's law is
    design_solo12.log's last block (a run of 2.5 minutes, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "design_solo12.log").read_text()
    block = log[log.index("## branch swing8"):]
    page = " ".join((DOCS / "design.md").read_text().split())
    assert_quoted(page, block, (
        ("the answer is the same", "fit one_sided, spring torque ≤ 0.4086 N·m springs on hfe "
                                   "LH/RH, hfe LF/RF, kfe LF/RF, kfe LH/RH: electrical saving "
                                   "+42.02 % (+39.60 % net of 42.4 g of springs)"),
        ("+42.09 % under feedforward + PD", "feedforward + PD  walks simulated +42.09 %"),
        ("+40.82 % position only, and", "position only     walks simulated +40.82 %"),
        ("the candidate +42.26 % position only", "one_sided, spring torque ≤ 0.4086 N·m    "
                                                 "position    walks  +43.21 % +42.26 %")))


def test_design_page_quotes_solo12s_answer_at_its_foot_points_timestep():
    """docs/design.md's Solo-12 answer once each contact's stability bound is at its foot
    point's mass is design_solo12.log's block "branch simstep" (a run of 4 minutes, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "design_solo12.log").read_text()
    block = log[log.index("## branch simstep"):]
    page = " ".join((DOCS / "design.md").read_text().split())
    assert_quoted(page, block, (
        ("the answer is the same again", "fit one_sided, spring torque ≤ 0.4086 N·m springs on "
                                         "hfe LH/RH, hfe LF/RF, kfe LF/RF, kfe LH/RH: electrical "
                                         "saving +42.02 % (+39.60 % net of 42.4 g of springs)"),
        ("its proof +41.92 % and +40.72 %", "feedforward + PD  walks simulated +41.92 %"),
        ("its proof +41.92 % and +40.72 %", "position only     walks simulated +40.72 %"),
        ("the candidate +42.60 % position only", "one_sided, spring torque ≤ 0.4086 N·m    "
                                                 "position    walks  +43.21 % +42.60 %"),
        ("simulates at 0.203 ms, was 0.325 ms", "now simulates at 0.2029 ms, was 0.3249 ms")))


def test_simulate_page_quotes_the_deadbeat_bound_block():
    """docs/simulate.md's paragraph on the lead bounded by the pendulum's deadbeat step, and
    docs/optimal.md's co-design row under it, are newcomers_simulate.log's block "placement"
    (scratch runs of 2–20 s of CPU each, by hand): each figure beside the log's line."""
    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    block = log[log.index("# ===== placement"):]
    page = (DOCS / "simulate.md").read_text()
    start = page.index("**The lead bounded by the pendulum's deadbeat step**")
    part = " ".join(page[start:page.index("The newcomers' servos are generic")].split())
    law = block[block.index("## (7)"):]
    assert_quoted(part, block, (
        ("feet landed 15.4 mm from the plan's on average (39.5 mm at most)",
         "raibert: verdict walks; touchdown shifts |dx| mean 15.4 mm, max 39.5 mm; |v - v*| "
         "there mean 47 mm/s, max 122 mm/s; electrical 14.5 J"),
        ("the feet land 5.6 mm off (8.1 mm at most) at 24 mm/s",
         "deadbeat: verdict walks; touchdown shifts |dx| mean 5.6 mm, max 8.1 mm; |v - v*| "
         "there mean 24 mm/s, max 34 mm/s"),
        ("spent 14.51 J a cycle against the plan's 8.418 J",
         "old        cd       feed | walks 14.51J"),
        ("ran short under both servos (86 % of its stride at most)",
         "T/2         feedforward springs  short     E  37.868 J  dist  237.2/276.6 mm"),
        ("with the co-design's springs 8.822 J and 8.388 J",
         "branch      feedforward springs  walks     E   8.822 J"),
        ("with the co-design's springs 8.822 J and 8.388 J",
         "branch      position    springs  walks     E   8.388 J"),
        ("(10.19 J a cycle with the pendulum's neutral point over them)",
         "lip_few    cd       feed | walks 10.19J"),
        ("ran short (33.39 J)", "HOLD 0.001  feedforward springs  short     E  33.388 J"),
        ("walked it too (9.739 J)", "neutral    cd       feed | walks 9.739J"),
        ("B1 spent 1839 J a cycle with springs under both servos",
         "neutral    b1       feed | walks 1839J"),
        ("B1 spent 1839 J a cycle with springs under both servos",
         "neutral    b1       posi | walks 1839J"),
        ("(+13.19 % simulated under feedforward + PD against +33.34 % predicted)",
         "predicted saving +33.34 % (electrical 1313 J vs 1970 J per cycle); simulated "
         "+13.19 % (1839 J vs 2118 J)"),
        ("Go2 rolled 0.022 rad (0.013 at `T_stance/2`)",
         "neutral    go2      posi | walks 122J 101% tr15 roll0.022"),
        ("Go2 rolled 0.022 rad (0.013 at `T_stance/2`)",
         "old        go2      posi | walks 121.5J 101% tr14 roll0.013")))
    assert_quoted(part, law, (
        ("9.672 and 13.11 J a cycle under feedforward + PD",
         "code       cd       feed | walks 9.672J 99% tr16 roll0.012 | walks 13.11J"),
        ("8.768 and 12.6 J under position servos (planned 8.418 and 12.85 J)",
         "code       cd       posi | walks 8.768J 100% tr10 roll0.008 | walks 12.6J 100% tr6 "
         "roll0.004 | pred 8.418/12.85"),
        ("covers 83 % and 84 % of its stride under position servos",
         "code       pry52    posi | short 12.78J 83% tr53 roll0.071 | short 13.54J 84%"),
        ("walks under feedforward + PD at 7.596 J a cycle",
         "code       pry60    feed | walks 7.596J"),
        ("covers 67 % of its stride under position servos (53 %)",
         "code       pry60    posi | short 13.99J 67%"),
        ("the same to the last digit", "code       go2      posi | walks 121.5J 101% tr14 "
                                       "roll0.013 | walks 163.3J 101% tr14 roll0.013")))
    assert_quoted(part, log, (("(9.172 J at `T_stance/2`)", "simulated +13.71 % (9.172 J"),))
    merged = log[log.index("# ===== integration, this stop"):]
    for run in ("simulated +25.60 % (9.836 J vs 13.22 J)",
                "simulated +30.17 % (8.817 J vs 12.63 J)"):
        assert run in merged, run
    assert ("9.836 and 13.22 J under feedforward + PD, 8.817 and 12.63 J under position servos, "
            "all four runs walking — the feedforward saving +25.60 % against +34.48 % "
            "predicted") in part
    assert ("feedforward springs walks, baseline walks; position springs walks, baseline walks"
            in merged)
    assert "old        pry60    posi | short 17.04J 53%" in block
    law_runs = law[:law.index("## (7) hexaleg")] if "## (7) hexaleg" in law else law
    assert law_runs.count("walks") >= 40 and "fell" not in law_runs
    optimal = " ".join((DOCS / "optimal.md").read_text().split())
    assert_quoted(optimal, block, (
        ("8.822 J a cycle over 274.7 mm under feedforward + PD",
         "branch      feedforward springs  walks     E   8.822 J  dist  274.7/276.6 mm"),
        ("8.388 J over 275.7 mm position only",
         "branch      position    springs  walks     E   8.388 J  dist  275.7/276.6 mm")))
    rows = (ROOT / "analysis" / "bench_logs" / "bench_optimal_rows_solo12_placement.log"
            ).read_text()
    check = rows[rows.index("# ===== branch placement"):]
    assert_quoted(optimal, check, (
        ("every one of its six finalists walking under both servos",
         "6 finalists simulated under both servos, by the worse: chose finalist 2"),
        ("duty factor 0.644, period 0.875 s, 30.77 J/m predicted, simulated feedforward 31.29, "
         "position 30.44", "→ 2. duty factor 0.644, period 0.875 s: predicted 30.77 J/m, "
                           "simulated feedforward 31.29, position 30.44")))
    assert check.count("simulated feedforward") == 6 and "—" not in check


def test_design_page_quotes_the_solo12_design_log():
    """docs/design.md's Solo-12 answer and how it followed the position servo's simulation are
    analysis/bench_logs/design_solo12.log's (two runs of 4 minutes, by hand): each figure
    beside the log's words."""
    log = (ROOT / "analysis" / "bench_logs" / "design_solo12.log").read_text()
    ranked = log.index("## ranking rows (solo12_design_main")
    before, now = log[:log.index("## branch posquad")], log[log.index("## branch posquad"):ranked]
    rows_before = log[ranked:log.index("## ranking rows (solo12_design/")]
    rows_now = log[log.index("## ranking rows (solo12_design/"):]
    page = " ".join((DOCS / "design.md").read_text().split())
    quoted = [
        ("one-sided springs (spring torque ≤ 0.4086 N·m) on hip and knee pitch, +42.02 % "
         "predicted (+39.60 % net of 42.4 g of springs), +42.74 % simulated under feedforward "
         "+ PD and +43.35 % position only", now,
         "fit one_sided, spring torque ≤ 0.4086 N·m springs on hfe LH/RH, hfe LF/RF, kfe LF/RF, "
         "kfe LH/RH: electrical saving +42.02 % (+39.60 % net of 42.4 g of springs)"),
        ("+43.35 % position only", now, "simulated electrical saving feedforward + PD +42.74 %, "
                                        "position only +43.35 % (predicted +42.02 %)"),
        ("preloaded springs (+43.65 % predicted, +37.62 % position only, +36.88 % net of "
         "117.0 g)", before, "fit preloaded springs on hfe LH/RH, hfe LF/RF, kfe LF/RF, "
                             "kfe LH/RH: electrical saving +43.65 % (+36.88 % net of 117.0 g"),
        ("+37.62 % position only", before, "simulated electrical saving position only "
                                           "+37.62 %, feedforward + PD +43.71 %"),
        ("simulated +36.25 % under position servos", rows_before,
         "one_sided, spring torque ≤ 0.4086 N·m    position    walks  +43.21 % +36.25 %"),
        ("that candidate simulates +43.60 %", rows_now,
         "one_sided, spring torque ≤ 0.4086 N·m    position    walks  +43.21 % +43.60 % "
         "+41.02 %"),
        ("(+40.92 % against the preloaded design's +40.15 %)", rows_now,
         "one_sided, spring torque ≤ 0.4086 N·m    feedforward walks  +43.21 % +43.51 % "
         "+40.92 %"),
        ("(+40.92 % against the preloaded design's +40.15 %)", rows_now,
         "preloaded                                feedforward walks  +45.56 % +45.93 % "
         "+40.15 %"),
    ]
    for words, where, said in quoted:
        assert words in page, words
        assert said in where, said


def test_codesign_page_quotes_the_codesign_bench_log():
    """docs/codesign.md's present time of the command, with and without the rules, is
    analysis/bench_logs/bench_codesign.log's (python analysis/bench_codesign.py, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "bench_codesign.log").read_text()
    page = " ".join((DOCS / "codesign.md").read_text().split())
    assert_quoted(page, log, (
            ("117.1 s wall (0.98 of the target) and 196.3 s CPU with the rules",
             "117.1 s wall, 0.98 of the 120 s target (met on this machine); 196.3 s CPU"),
            ("the co-design search 60.7 s", "search (codesign)              60.7 s"),
            ("84.5 s wall and 137.8 s CPU with `--no-rules`",
             "--no-rules (default robot, 0.06 m/s): 84.5 s wall, 0.70 of the 120 s target (met "
             "on this machine); 137.8 s CPU")))


def test_simulate_page_quotes_the_foot_points_mass():
    """docs/simulate.md's stability bound at the mass each foot point moves (#54): the masses
    and timesteps are analysis/bench_logs/bench_foot_masses.log's (python
    analysis/bench_foot_masses.py), HyQ's default trot at its new automatic timestep
    newcomers_simulate.log's block "the foot point's mass" (each row beside its run's summary
    line), what the retry it replaces printed the block "integration", and the registered
    trots' table bench_simulate_trots.log's last block."""
    masses = (ROOT / "analysis" / "bench_logs" / "bench_foot_masses.log").read_text()
    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    now = log[log.index("# ===== the foot point's mass"):]
    merged = log[log.index("# ===== integration"):log.index("# ===== the foot point's mass")]
    page = " ".join((DOCS / "simulate.md").read_text().split())
    part = page[page.index("**The foot point's mass.**"):page.index("The Adams model's printed")]
    model = page[page.index("**Integrator and timestep**"):page.index("## Balance feedback")]
    hexapod = masses[masses.index("hexaleg: "):masses.index("solo12: ")]
    hyq = masses[masses.index("hyq.toml: "):]
    anymal = masses[masses.index("anymal: "):masses.index("anymal:trot_anymal.toml: ")]
    assert_quoted(model, hexapod, (
        ("0.68 ms for the built-in robot, set by a hind foot's contact",
         "the ground contact of RH (K 2e+04 N/m, B 100 N·s/m, foot point's mass 0.0726 kg)"),
        ("0.073 kg for the built-in robot's hind feet against the tibia body's 0.085 kg",
         "RH  body 0.0852 kg  foot point sliding 0.0672 kg  held 0.0726 kg")))
    assert_quoted(model, hyq, (("HyQ's foot at the end of its 0.35-m shank 0.83 kg against its "
                                "shank's 2 kg", "LF  body 2 kg  foot point sliding 0.336 kg  "
                                                "held 0.832 kg"),
                               ("0.34 kg on HyQ", "foot point sliding 0.336 kg")))
    assert_quoted(model, anymal, (("0.25 kg on ANYmal", "LF  body 1.27 kg  foot point sliding "
                                                        "0.248 kg"),))
    assert_quoted(model, log, (("cut ANYmal's timestep 4.6×", "anymal: dt 0.4000 ms"),
                               ("cut ANYmal's timestep 4.6×", "anymal: dt 0.0877 ms")))
    assert_quoted(part, hyq, (
        ("front and hind left foot points move 0.832 kg, where the bound used its shank's 2 kg",
         "LH  body 1.99 kg  foot point sliding 0.336 kg  held 0.832 kg"),
        ("timestep is 0.1032 ms from the start (was 0.2421 ms)",
         "automatic timestep 0.2421 ms before, 0.1032 ms now")))
    quad2dof = masses[masses.index("tests/data/quad2dof.toml:q2b.toml: "):]
    retry = masses[masses.index("## main 3e7cc70"):]
    assert_quoted(part, masses, (("HyQ's down to 0.552 kg", "(held over the gait >= 0.552 kg)"),
                                 ("ANYmal's to 0.899 kg", "(held over the gait >= 0.899 kg)")))
    assert_quoted(part, quad2dof, (
        ("point moves 0.061 kg at its start and 0.027 kg at its lightest",
         "LF  body 0.164 kg  foot point sliding 0.0349 kg  held 0.0614 kg  (held over the gait "
         ">= 0.0269 kg)"),))
    assert_quoted(part, retry, (
        ("loses the ground in over half its stance samples at its 0.3-ms timestep and walks "
         "backwards", "q2b.toml:feedforward:auto: timestep 0.3000 ms, feedback True; springs "
                      "stalled lost 55.7 %; baseline stalled lost 58.0 %"),
        ("(at 0.15 ms, where the removed retry took it, a quarter, and its joints missed the "
         "plan", "q2b.toml:feedforward:auto: timestep 0.1500 ms, feedback True; springs "
                 "untracked lost 25.5 %")))
    assert_quoted(part, now, [
        ("| HyQ, default | position | +34.01 % (+33.68 %) | 1322 / 2004 (1349 / 2034) |",
         "hyq (position servo, balance feedback): predicted saving +33.68 % (electrical 1349 J "
         "vs 2034 J per cycle); simulated +34.01 % (1322 J vs 2004 J)"),
        ("| | feedforward + PD | +33.87 % | 1340 / 2027 |",
         "simulated +33.87 % (1340 J vs 2027 J)")])
    for run in ("position springs", "position baseline", "feedforward springs",
                "feedforward baseline"):
        line = now[now.index(f"hyq {run}: walks, "):].splitlines()[0]
        assert "contact lost 0.0 %" in line and "timestep 0.1032 ms" in line, line
    assert_quoted(part, merged, [
        ("they lost 14 % and 39 % at 0.24 ms", "the feet lost the ground in 14% of their stance "
                                               "samples at the automatic timestep 0.000242 s"),
        ("they lost 14 % and 39 % at 0.24 ms", "the feet lost the ground in 39% of their stance "
                                               "samples"),
        ("(HyQ walked at 0.121 ms: +34.09 % and +33.90 %", "simulated +34.09 % (1319 J"),
        ("(HyQ walked at 0.121 ms: +34.09 % and +33.90 %", "simulated +33.90 % (1340 J"),
        ("(HyQ walked at 0.121 ms:", "so the runs were simulated again at 0.000121 s")])
    for label, case, steps, held, body in (
            ("the built-in hexapod", "hexaleg", "0.5000 → 0.5000", "0.0726", "0.0852"),
            ("Solo-12", "solo12", "0.2500 → 0.2029", "0.0477", "0.0775"),
            ("Solo-12, trot 0.4 s", "solo12:trot_solo12.toml", "0.2000 → 0.1982", "0.0466",
             "0.0775"),
            ("A1", "a1", "0.3000 → 0.1694", "0.218", "0.465"),
            ("A1, trot 0.4 s", "a1:trot_a1.toml", "0.2000 → 0.1645", "0.212", "0.465"),
            ("ANYmal", "anymal", "0.4000 → 0.4000", "1.19", "1.27"),
            ("ANYmal, trot 0.6 s", "anymal:trot_anymal.toml", "0.3000 → 0.3000", "1.16", "1.27"),
            ("ANYmal C", "anymal_c", "0.4000 → 0.4000", "2.41", "2.25"),
            ("Go2", "go2", "0.2596 → 0.1581", "0.238", "0.395"),
            ("Go2, its trot", "go2:trot_own.toml", "0.2596 → 0.1608", "0.242", "0.395"),
            ("biped6 (a servo sets it)", "../tests/data/biped6.toml", "0.1238 → 0.1238", "", ""),
            ("Talos (a servo sets it)", "../tests/data/talos.toml", "0.2528 → 0.2528", "", ""),
            ("HyQ", "hyq.toml", "0.2421 → 0.1032", "0.832", "1.99")):
        cell = f"{held} / {body} |" if body else "|"
        assert f"| {label} | {steps} | {cell}" in part, label
        lines = masses[masses.index(f"\n{case}: ") + 1:].splitlines()
        legs = list(itertools.takewhile(lambda line: line.startswith(" "), lines[1:]))
        before, _, after = steps.partition(" → ")
        assert f"automatic timestep {before} ms before, {after} ms now" in lines[0], lines[0]
        assert not held or any(f"body {body} kg" in leg and f"held {held} kg" in leg
                               for leg in legs), (label, legs)
    trots = (ROOT / "analysis" / "bench_logs" / "bench_simulate_trots.log").read_text()
    last = trots[trots.rindex("per robot (4 cycles"):]
    table = page[page.index("**The registered quadrupeds' trots under position-only"):
                 page.index("Closed loop every run covers")]
    for label, cells in (("solo12 trot", ("25.0×", "13.5×", "+34.48 %")),
                         ("a1 trot", ("20.9×", "11.2×", "+31.13 %")),
                         ("anymal trot", ("35.7×", "14.2×", "+24.88 %")),
                         ("go2 trot", ("18.3×", "11.5×", "+25.48 %")),
                         ("hexaleg tripod", ("31.2×", "16.0×", "+15.09 %"))):
        rows = [r for r in last.splitlines() if r.strip().startswith(label)]
        open_cpu, closed_cpu, saving = cells
        assert f" {open_cpu} " in rows[0] and f" {closed_cpu} " in rows[1], rows
        assert saving.replace(" ", "") in rows[1], rows
        assert f"| {open_cpu} |" in table and f"| {saving} | {closed_cpu} |" in table, label


def test_simulate_page_quotes_g1s_log():
    """docs/simulate.md's Unitree G1 (#54: its ZMP gait on soles closed loop, the controller's
    rate and its toe corners) is analysis/bench_logs/newcomers_simulate.log's G1 block: each
    table row and figure beside the log's line (its runs about 30 s of CPU each, by hand)."""
    log = (ROOT / "analysis" / "bench_logs" / "newcomers_simulate.log").read_text()
    now = log[log.index("# ===== Unitree G1 on soles"):]
    page = (DOCS / "simulate.md").read_text()
    part = " ".join(page[page.index("### Unitree G1"):
                         page.index("### Position servos on soles")].split())
    robots = " ".join((DOCS / "robots.md").read_text().split())
    summary = ("g1 ({} servo, balance feedback): predicted saving +39.08 % (electrical 649.2 J "
               "vs 1066 J per cycle); simulated {}")
    assert_quoted(part, now, (
        ("| feedforward + PD | 200.0 / 200.0 mm | +39.08 % → +39.00 % |",
         summary.format("feedforward", "+39.00 %")),
        ("| position | 200.5 / 200.5 mm | +39.08 % → +38.65 % |",
         summary.format("position", "+38.65 %")),
        ("every 2.08 ms", "g1 position baseline: walks, 200.5 mm per cycle of 200.0 mm (100.3 %)"),
        ("every 2.08 ms", "controller period 2.08 ms"),
        ("r = 60.7", "g1 r 60.7"), ("is 15.6", "criterion 15.6"),
        ("0.000101 s of the ground contact of L1's sole corner 0 at its own effective mass "
         "0.124 kg", "0.000101 s of the ground contact of L1's sole corner 0 at its own "
                     "effective mass 0.124 kg")))
    for line in ("g1 feedforward springs: walks, 200.0 mm", "g1 feedforward baseline: walks, "
                 "200.0 mm", "g1 position springs: walks, 200.5 mm"):
        assert line in now, line
    assert "200.0 mm per cycle of the planned 200 mm, the saving +39.00 %" in robots
    assert "+39.08 % predicted; under position servos 200.5 mm, +38.65 %" in robots


def test_codesign_page_says_the_edges_the_kept_log_prints():
    """docs/codesign.md's edges of the default robot's co-design are those its kept command log
    prints (the tops of body height and duty factor, the step height's floor)."""
    import re

    page = " ".join((DOCS / "codesign.md").read_text().split())
    log = (ROOT / "analysis" / "bench_logs" / "codesign_motion_optimal_own_starts.log"
           ).read_text()
    line = re.search(r"on the search box's edge: (.*) — the co-design is this box's optimum", log)
    assert line
    said = set()
    for edge in line[1].split("; "):
        found = re.match(r"([a-z ]+?) [0-9.]+(?: m)? at the box's (top|floor)", edge)
        assert found, edge
        said.add(found.groups())
    assert said == {("body height", "top"), ("duty factor", "top"), ("step height", "floor")}
    assert ("The default robot's co-design lies on the tops of its body height and duty factor "
            "and on the step height's floor") in page
