"""docs/architecture.md against the code: its layers are the layer test's, its tables the run's,
its stages the design chain's, its public names hexaleg.__all__, the files a new spring family
or actuator model touches exist and hold what it says; its examples run."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from test_layers import LIBRARY, RANK

import hexaleg
from hexaleg.design.chain.chain import STAGES
from hexaleg.scenario.scenario import TABLES

ROOT = Path(__file__).resolve().parents[1]
PAGE = (ROOT / "docs" / "architecture.md").read_text()


def _table(heading: str) -> list[str]:
    """The first column of the first table under ``heading``, backticks stripped."""
    section = PAGE.split(f"## {heading}\n", 1)[1].split("\n## ", 1)[0]
    rows = [ln for ln in section.splitlines() if ln.startswith("| ")][1:]  # the header out
    return [re.sub(r"[`\[\]]", "", r.split("|")[1]).strip() for r in rows]


def test_the_layers_are_the_layer_tests():
    assert _table("Layers") == [*LIBRARY, "commands"]
    assert [*LIBRARY, "commands"] == sorted([*LIBRARY, "commands"], key=RANK.__getitem__)


def test_the_tables_are_the_runs():
    assert _table("The run: `Scenario`") == list(TABLES)


def test_the_stages_are_the_chains():
    assert tuple(_table("The design chain")) == STAGES


def test_the_public_names_are_hexalegs():
    section = PAGE.split("## The public surface\n", 1)[1]
    listed = section.split("The names of 0.1")[0]
    named = set(re.findall(r"`(\w+)`", listed))
    assert named == set(hexaleg.__all__)
    assert f"holds {len(hexaleg.__all__)} names" in section and len(hexaleg.__all__) <= 30
    for old in re.findall(r"`(\w+)`", section.split("The names of 0.1")[1]):
        with pytest.warns(DeprecationWarning, match=f"hexaleg.{old} is deprecated"):
            getattr(hexaleg, old)


def test_a_new_family_touches_the_files_named():
    """The files the page names exist; every family is one module of design/families/ and one
    entry of the registry, from which design.json's classes and the scan's stops come."""
    import importlib
    import inspect

    from hexaleg.design import families
    from hexaleg.design.springs import law_json as spring_json

    for path in re.findall(r"`(src/hexaleg/[\w/.]+)`", PAGE.split("## A new spring family")[1]
                           .split("## The public surface")[0]):
        assert (ROOT / path).exists(), path
    for name, fam in families._FAMILIES.items():
        module = importlib.import_module(f"hexaleg.design.families.{name}")
        assert inspect.getmodule(type(fam)) is module and isinstance(fam, families.Family)
        assert spring_json.CLASSES[name] is fam.law
        assert inspect.getmodule(fam.law).__name__ == f"hexaleg.robot.springs.{name}"


def _actuator_section() -> str:
    return PAGE.split("## A new actuator model\n", 1)[1].split("\n## ", 1)[0]


def _implementations() -> dict[str, str]:
    """Every class of src/ whose body defines each member of ``Actuator`` (a method, a property
    or a dataclass field), protocol itself aside: class → its file, read from the source."""
    import ast

    from hexaleg.robot.actuator import Actuator

    members = {m for m in vars(Actuator) if not m.startswith("_")}
    assert {"current", "electrical_power", "joule_coefficient", "models"} <= members
    found = {}
    for path in sorted((ROOT / "src" / "hexaleg").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.ClassDef) or node.name == "Actuator":
                continue
            defined = {n.name for n in node.body
                       if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
            defined |= {n.target.id for n in node.body
                        if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)}
            if members <= defined:
                found[node.name] = str(path.relative_to(ROOT))
    return found


def test_a_new_actuator_model_touches_the_files_named():
    """The files the section names exist, and its table lists every class of src/ that
    implements Actuator, with its module (a new model without its row fails here)."""
    import importlib

    section = _actuator_section()
    named = re.findall(r"`((?:src|tests)/[\w/.]+\.py)`", section)
    assert "src/hexaleg/robot/actuator.py" in named and "tests/test_docs_architecture.py" in named
    for path in named:
        assert (ROOT / path).exists(), path
    rows = [ln.split("|")[1:3] for ln in section.splitlines() if ln.startswith("| `")]
    table = {cls.strip(" `"): module.strip(" `") for cls, module in rows}
    implementations = _implementations()
    assert implementations, "no class of src/ implements Actuator: the scan is broken"
    assert table == implementations
    for cls, module in table.items():
        code = importlib.import_module(module.removeprefix("src/").removesuffix(".py")
                                       .replace("/", "."))
        assert isinstance(getattr(code, cls), type), (module, cls)


def test_the_examples_run():
    """The page's code blocks in turn, at their word (a small design: seconds)."""
    namespace: dict = {}
    for block in re.findall(r"```python\n(.*?)```", PAGE, re.S):
        exec(compile(block, "architecture.md", "exec"), namespace)
    result = namespace["result"]
    assert result.stages == ("candidates", "tolerance") and result.tolerance is not None
    assert hexaleg.load_design.__name__ and '"stages": [' in namespace["text"]
