"""The documentation site's landing page (docs/index.md), its stylesheet and the API reference's
root page, checked without building the site (the build is `mkdocs build --strict` in CI)."""

from __future__ import annotations

from test_docs import DOCS, ROOT, _gen_api, _mkdocs_config

INDEX = DOCS / "index.md"


def _bash_blocks(text: str) -> list[str]:
    import re

    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", text, re.S)]


def test_landing_page_has_the_readme_quick_start_verbatim():
    """docs/index.md's install steps are README.md's two quick-start commands (install + the
    report, install + the tests), which .ci/run runs (tests/test_readme.py)."""
    readme = _bash_blocks((ROOT / "README.md").read_text())
    quick = [b for b in readme if "pip install" in b and b.endswith(("hexaleg report", "pytest"))]
    assert len(quick) == 2, readme
    index = _bash_blocks(INDEX.read_text())
    assert index[:2] == quick


def test_landing_page_answer_is_the_kept_log():
    """docs/index.md's answer is analysis/logs/answer_hexaleg.log's (``hexaleg design``'s answer
    on the default robot, diffed against its script by test_examples): the family, the saving, net
    and mass, the worst case with the stops off and over the gait map, the simulated savings, and
    each spring to buy."""
    import re

    log = (ROOT / "analysis" / "logs" / "answer_hexaleg.log").read_text()
    page = INDEX.read_text()
    rec = re.search(r"recommended: (\w+); electrical\s+(\S+) %, net\s+(\S+) % \((\S+) g", log)
    assert rec, log
    family, saving, net, grams = rec.groups()
    assert f"| recommended family | **{family}** " in page
    assert f"**{saving} %** saved ({net} % net of the springs' {grams} g)" in page
    tol = re.search(r"stops mounted within ±(\S+)° .*\n  tolerant\s+\S+ % /\s+(\S+) %", log)
    assert tol, log
    assert f"| with the stops mounted up to ±{tol.group(1)}° off | {tol.group(2)} % at worst |" \
        in page
    worst = re.search(r"worst\s+(\S+) % at (period ×[^\n]+)", log)
    assert worst and f"| {worst.group(1)} % at worst, at {worst.group(2)} |" in page
    sim = {c: re.search(rf"{re.escape(c)}\s+.* / +(\S+) % +\S+ mm", log)
           for c in ("feedforward + PD", "position only")}
    ff, pos = (m.group(1) for m in sim.values() if m)
    assert f"| simulated in MuJoCo | {ff} % with feedforward + PD servos, {pos} % with " \
           "position-only servos |" in page
    buys = re.findall(r"^  (\w+)\s+(above|below) needs .* -> (\w+) d (\S+) mm, D \S+ mm, OD "
                      r"(\S+) \(.*?, (\S+) turns, .*?, (\S+) N·mm/deg, preload (\d+)°, .*, "
                      r"(\S+) g$", log, re.MULTILINE)
    assert len(buys) == 2, log
    for joint, side, wire, d, od, turns, rate, preload, mass in buys:
        assert (f"| {joint} | {side} | {wire} | {d} mm | {od} mm | {turns} | {rate} N·mm/deg | "
                f"{preload}° | {mass} g |") in page, joint
    groups = " and ".join(j for j, *_ in buys)
    assert f"on {groups} |" in page


def test_landing_page_lists_every_guide_page_and_the_nav_has_them():
    """Every docs/*.md guide page is linked in index.md's page table, with the title the nav
    gives it, and in mkdocs.yml's nav; the table has no page that does not exist."""
    import re

    guide = sorted(p.name for p in DOCS.glob("*.md") if p.name != "index.md")
    assert len(guide) >= 14
    nav = _mkdocs_config()["nav"]
    titles = {file: title for section in nav if isinstance(section, dict)
              for value in section.values() if isinstance(value, list)
              for entry in value for title, file in entry.items()}
    table = INDEX.read_text().split("## Pages", 1)[1]
    linked = dict((file, title) for title, file in re.findall(r"^\| \[([^]]+)\]\((\w+\.md)\) \|",
                                                              table, re.MULTILINE))
    assert sorted(linked) == guide, sorted(set(guide) ^ set(linked))
    assert sorted(titles) == guide, sorted(set(guide) ^ set(titles))
    for file, title in linked.items():
        assert titles[file] == title, (file, title, titles[file])


def test_wide_code_blocks_and_tables_scroll():
    """The site's stylesheet, named by mkdocs.yml, lets code blocks and tables scroll sideways."""
    import re

    sheets = _mkdocs_config()["extra_css"]
    css = "".join((DOCS / s).read_text() for s in sheets)
    rules = dict(re.findall(r"([^{}]+)\{([^}]*)\}", re.sub(r"/\*.*?\*/", "", css, flags=re.S)))
    scrolls = " ".join(sel for sel, body in rules.items() if "overflow-x: auto" in body)
    assert "pre > code" in scrolls and "table" in scrolls


def test_api_root_page_lists_functions_then_classes_then_data_without_values():
    """The public surface's page: functions first, then classes, then the data members by name
    (no values, no source); every name of ``hexaleg.__all__`` once, of the kind its object is."""
    import inspect

    import hexaleg

    gen_api = _gen_api()
    kinds = gen_api.public_names()
    assert sorted(n for names in kinds.values() for n in names) == sorted(hexaleg.__all__)
    for name in hexaleg.__all__:
        obj = getattr(hexaleg, name)
        kind = "classes" if inspect.isclass(obj) else "functions" if callable(obj) else "data"
        assert name in kinds[kind], (name, kind)
    text = gen_api.root_page()
    directives = text.split("::: hexaleg\n")[1:]
    assert len(directives) == 3
    for directive, kind in zip(directives, ("functions", "classes", "data"), strict=True):
        assert f"members: [{', '.join(kinds[kind])}]" in directive
    assert "show_root_heading: false" not in directives[0]
    assert "show_attribute_values: false" in directives[2]
    assert "show_source: false" in directives[2]
    root = gen_api.api_pages()[0]
    assert gen_api.page_text(root) == text
    assert gen_api.page_text(gen_api.api_pages()[1]) == f"::: {gen_api.api_pages()[1].module}\n"
