"""The package's shape: imports point down the layers, modules stay small, the import is light.

Layers, lowest first (docs/architecture.md): the top-level helpers (errors, units, config,
checks, quantities) → robot → parallel → motion → dynamics → scenario, optimal → simulation →
design → outputs → paper, sweep → report → commands → cli. A module may import its own layer and the
ones below it, at module level, inside functions or under TYPE_CHECKING alike; a command imports
no other command (only the shared modules at the top of ``commands/``).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import hexaleg

SRC = Path(hexaleg.__file__).resolve().parent
RANK = {"errors": 0, "units": 0, "config": 0, "checks": 0, "quantities": 0, "robot": 1,
        "parallel": 2, "motion": 3, "dynamics": 4, "scenario": 5, "optimal": 5, "simulation": 6,
        "design": 7, "outputs": 8, "paper": 9, "sweep": 9, "report": 10, "commands": 11, "cli": 12}
"""Each layer's rank: a module imports only from layers of its rank or lower."""
LIBRARY = ("robot", "parallel", "motion", "dynamics", "scenario", "optimal", "simulation",
           "design", "outputs", "paper", "sweep", "report")
"""The library's packages, in the order of :data:`RANK`; ``commands`` is the command layer."""
TOP_LEVEL = {"__init__.py", "errors.py", "units.py", "config.py", "checks.py", "quantities.py",
             "cli.py"}
WARN_LINES = 400
"""Code lines over which a module is worth a look for a seam (a warning)."""
MAX_LINES = 600
"""Code lines over which a module fails: split it at its seams, not at the count."""
DATA_TABLES: dict[str, str] = {}
"""Modules allowed over MAX_LINES because they are data tables (path → why)."""
MODULES = sorted(p for p in SRC.rglob("*.py") if "__pycache__" not in p.parts)


def _layer(dotted: str) -> str:
    return dotted.split(".")[1] if dotted.count(".") else ""


def _imports(path: Path) -> list[tuple[int, str]]:
    """(line, absolute dotted module) of every hexaleg import in ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = ".".join(("hexaleg", *path.relative_to(SRC).with_suffix("").parts[:-1]))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names if a.name.startswith("hexaleg")]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                module = f"{base}.{module}" if module else base
            if module == "hexaleg":  # `from hexaleg import x`: x is a module or a public name
                found += [(node.lineno, f"hexaleg.{a.name}") for a in node.names]
            elif module.startswith("hexaleg."):
                found.append((node.lineno, module))
    return found


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_imports_point_down_the_layers(path):
    rel = path.relative_to(SRC)
    if rel.name == "__init__.py" and len(rel.parts) == 1:
        return  # the public surface imports from every layer
    own = rel.parts[0].removesuffix(".py")
    bad = []
    for line, module in _imports(path):
        target = _layer(module)
        if target not in RANK:  # `hexaleg` itself: the public surface, for the CLI only
            target = "the public surface"
        if RANK.get(target, RANK["cli"]) > RANK[own]:
            bad.append(f"line {line}: {module} ({target} is above {own})")
    assert not bad, f"{rel} imports up the layers:\n" + "\n".join(bad)


def code_lines(path: Path) -> int:
    """Lines of ``path`` that hold code: not blank, not only a comment, not a docstring."""
    import io
    import tokenize

    text = path.read_text(encoding="utf-8")
    docs: set[int] = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                docs.update(range(body[0].lineno, (body[0].end_lineno or body[0].lineno) + 1))
        if isinstance(node, (ast.Module, ast.ClassDef)):  # attribute docstrings
            for a, b in zip(node.body, node.body[1:], strict=False):
                if isinstance(a, (ast.Assign, ast.AnnAssign)) and isinstance(b, ast.Expr) \
                        and isinstance(b.value, ast.Constant) and isinstance(b.value.value, str):
                    docs.update(range(b.lineno, (b.end_lineno or b.lineno) + 1))
    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
            tokenize.ENCODING, tokenize.ENDMARKER}
    code: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type not in skip:
            code.update(range(tok.start[0], tok.end[0] + 1))
    return len(code - docs)


def test_code_lines_leave_out_docstrings_comments_and_blanks(tmp_path):
    path = tmp_path / "m.py"
    path.write_text('"""Doc.\n\nMore."""\n\n# a comment\nX = 1\n"""X\'s doc."""\n\n\n'
                    'def f(a):\n    """Doc."""\n    return (a +\n            1)  # sum\n')
    assert code_lines(path) == 4  # X = 1, def, and the two lines of the return


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_modules_stay_under_the_line_limit(path):
    """The line rule counts code lines (docstrings, comments and blank lines left out): over
    :data:`WARN_LINES` is a warning to look for a seam, over :data:`MAX_LINES` a failure."""
    import warnings

    rel = str(path.relative_to(SRC))
    n = code_lines(path)
    assert n <= MAX_LINES or rel in DATA_TABLES, f"{rel}: {n} code lines; split it at its seams"
    if n > WARN_LINES:
        warnings.warn(f"{rel}: {n} code lines (over {WARN_LINES}): is there a seam?",
                      stacklevel=1)


def test_top_level_modules_and_layers_are_the_known_ones():
    top = {p.name for p in SRC.glob("*.py")}
    assert top <= TOP_LEVEL, sorted(top - TOP_LEVEL)
    layers = {p.name for p in SRC.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert layers == {*LIBRARY, "commands"}


@pytest.mark.parametrize("path", sorted(p for p in MODULES if "commands" in p.parts),
                         ids=lambda p: str(p.relative_to(SRC)))
def test_commands_do_not_import_each_other(path):
    """A command's modules import the library, their own command's modules and the shared
    modules at the top of ``commands/``; never another command."""
    rel = path.relative_to(SRC)
    own = rel.parts[1].removesuffix(".py") if len(rel.parts) > 2 else None
    shared = {p.stem for p in (SRC / "commands").glob("*.py")} - {"__init__"}
    bad = [f"line {line}: {module}" for line, module in _imports(path)
           if module.startswith("hexaleg.commands.")
           and module.split(".")[2] not in {own, *shared}]
    assert not bad, f"{rel} imports another command:\n" + "\n".join(bad)


def test_the_command_layer_is_thin():
    """The command layer (``commands/`` and ``cli.py``) is at most 15 % of the package's code
    lines: the library does the work."""
    lines = {p: code_lines(p) for p in MODULES}
    commands = sum(n for p, n in lines.items()
                   if "commands" in p.relative_to(SRC).parts or p.name == "cli.py")
    assert commands <= 0.15 * sum(lines.values()), (commands, sum(lines.values()))


def test_import_hexaleg_is_light():
    """`import hexaleg` loads no study (report, sweep, view, paper) and neither matplotlib,
    pandas nor meshcat: their public names are imported on first use."""
    code = ("import sys, hexaleg; print('\\n'.join(m for m in sys.modules if m.startswith("
            "('hexaleg.commands', 'hexaleg.report', 'hexaleg.sweep', 'hexaleg.paper', "
            "'hexaleg.outputs', 'matplotlib', 'pandas', 'meshcat', 'cvxpy'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == []


def test_every_command_starts_light():
    """`import hexaleg.cli` (every command's start) loads neither scipy.signal nor
    scipy.optimize: imported where a log is smoothed or a fit is made, they cost every command
    about a second (issue #54's profile of `hexaleg simulate`)."""
    code = ("import sys, hexaleg.cli; print('\\n'.join(m for m in sys.modules if m.startswith("
            "('scipy.signal', 'scipy.optimize'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == []


def test_every_public_name_resolves():
    for name in hexaleg.__all__:
        assert getattr(hexaleg, name) is not None, name


@pytest.mark.parametrize("path", [p for p in MODULES if p.name != "__init__.py"],
                         ids=lambda p: str(p.relative_to(SRC)))
def test_every_module_has_its_test_file(path):
    """Tests mirror modules: src/hexaleg/<layer>/<m>.py ↔ tests/<layer>/test_<m>.py."""
    rel = path.relative_to(SRC)
    test = Path(__file__).resolve().parent.joinpath(*rel.parts[:-1], f"test_{rel.name}")
    shown = test.relative_to(test.parents[len(rel.parts)])
    assert test.is_file(), f"{rel} has no test file {shown}"


def test_lazy_names_are_declared_for_type_checkers():
    """The `if TYPE_CHECKING:` imports of __init__ name exactly the lazily imported public names,
    from the modules __getattr__ imports them from (so the docs and mypy see what users get)."""
    tree = ast.parse((SRC / "__init__.py").read_text(encoding="utf-8"))
    block = next(n for n in tree.body if isinstance(n, ast.If)
                 and getattr(n.test, "id", None) == "TYPE_CHECKING")
    declared = {a.name: node.module for node in block.body if isinstance(node, ast.ImportFrom)
                for a in node.names}
    assert declared == hexaleg._LAZY
    assert set(declared) <= set(hexaleg.__all__)


DESIGN_FLAT = 12
"""Modules allowed directly in design/ (issue #53): the rest live in sub-packages that read as
the data flow (families/, search/, springs/, robust/, studies/, chain/, codesign/)."""


def test_design_reads_as_its_data_flow():
    flat = sorted(p.name for p in (SRC / "design").glob("*.py"))
    assert len(flat) <= DESIGN_FLAT, f"design/ holds {len(flat)} modules directly: {flat}"
    subs = sorted(p.parent.name for p in (SRC / "design").glob("*/__init__.py"))
    assert subs == ["chain", "codesign", "families", "robust", "search", "springs", "studies"]
