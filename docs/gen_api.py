"""Generate the API reference: one page per public module of ``src/hexaleg/``.

Run by the ``gen-files`` plugin of ``mkdocs.yml`` at every build, so the reference follows the
package tree without edits. Each page is a single ``::: hexaleg.<dotted.path>`` directive that
mkdocstrings fills from the docstrings; a subpackage's ``__init__`` docstring is the page of its
section; modules and packages whose name starts with ``_`` are private and get no page.
``reference/SUMMARY.md`` is the section's navigation (read by the ``literate-nav`` plugin): the
public surface ``hexaleg`` first, then the top-level modules, then the layers in data-flow order.

The public surface's page (``hexaleg.md``) lists its functions first, then its classes, then its
data (``CATALOGUE``, ``DESCRIPTIONS``, …) by name, type and docstring without their values: a
mapping's source would otherwise open the reference with two screens of literals
(:func:`root_page`).

``api_pages`` is the walker; ``tests/test_docs.py`` checks it against the package tree without
building the site.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src"
PACKAGE = "hexaleg"
REFERENCE = "reference"

# A public name's kind by PEP 8 (a test checks it against the objects): data in capitals.
DATA_NAME = re.compile(r"^(?:[A-Z][A-Z0-9_]*|__version__)$")
CLASS_NAME = re.compile(r"^[A-Z]\w*[a-z]\w*$")

# The layers of docs/architecture.md in data-flow order; a subpackage not named here follows them.
LAYER_ORDER = ("robot", "parallel", "motion", "dynamics", "scenario", "simulation", "design",
               "outputs", "paper", "sweep", "report", "commands")


@dataclass(frozen=True)
class ApiPage:
    """One generated page of the API reference.

    Attributes:
        module: Dotted module name, e.g. ``hexaleg.robot.model``.
        path: Page path relative to the reference folder, e.g. ``hexaleg/robot/model.md``;
            a subpackage's page is its folder's ``index.md`` (the page of its section), the
            top-level package's is ``hexaleg.md`` (a page of its own, not the section's index).
        source: The module's file relative to the repository root.
        is_package: True for a package (its page heads the section of its modules).
    """

    module: str
    path: str
    source: str
    is_package: bool

    @property
    def depth(self) -> int:
        """Nesting level in the navigation: 0 for ``hexaleg`` and its top-level modules."""
        return max(self.module.count(".") - 1, 0)

    @property
    def title(self) -> str:
        """Navigation title: the last part of the dotted name."""
        return self.module.rsplit(".", 1)[-1]


def _is_private(parts: tuple[str, ...]) -> bool:
    return any(part.startswith("_") and part != "__init__" for part in parts)


def _sort_key(parts: tuple[str, ...]) -> tuple:
    """Order within the package: the package itself, its modules, then its subpackages."""
    key: list = []
    for depth, part in enumerate(parts):
        if part == "__init__":
            key.append((0, 0, ""))
            continue
        is_last = depth == len(parts) - 1
        if is_last:  # a module
            key.append((1, 0, part))
        else:  # a subpackage: layers in data-flow order at the top, by name elsewhere
            top = depth == 0 and part in LAYER_ORDER
            rank = LAYER_ORDER.index(part) if top else len(LAYER_ORDER)
            key.append((2, rank, part))
    return tuple(key)


def api_pages(src: Path = SRC, package: str = PACKAGE) -> list[ApiPage]:
    """The API pages of every public module of a package, in navigation order.

    A folder without ``__init__.py`` is not a package (Python does not import from it) and is not
    walked; private modules and packages (leading ``_``) are skipped, with everything under them.

    Args:
        src: The folder that holds the package (``src/`` of the src layout).
        package: The package's import name.

    Returns:
        The pages, ``package`` itself first, then depth-first: each package's modules, then its
        subpackages (at the top level in the order of ``LAYER_ORDER``).
    """
    root = src / package
    found: list[tuple[tuple[str, ...], Path]] = []
    for file in root.rglob("*.py"):
        rel = file.relative_to(src)
        parts = (*rel.parent.parts, rel.stem)
        if _is_private(parts):
            continue
        if not all((src.joinpath(*rel.parent.parts[: i + 1]) / "__init__.py").is_file()
                   for i in range(len(rel.parent.parts))):
            continue
        found.append((parts, file))
    found.sort(key=lambda item: _sort_key(item[0][1:]))

    pages = []
    for parts, file in found:
        is_package = parts[-1] == "__init__"
        dotted = parts[:-1] if is_package else parts
        if is_package and len(dotted) > 1:  # a section's own page (navigation.indexes)
            path = "/".join((*dotted, "index.md"))
        else:  # a module, or the public surface: a page of its own, first in the reference
            path = "/".join(dotted) + ".md"
        pages.append(ApiPage(module=".".join(dotted), path=path,
                             source=file.relative_to(src.parent).as_posix(),
                             is_package=is_package))
    return pages


def summary(pages: list[ApiPage]) -> str:
    """The literate-nav ``SUMMARY.md`` of the reference: a package's modules nest under it.

    Top-level entries carry the full dotted name, nested ones the last part.
    """
    lines = []
    for page in pages:
        title = page.module if page.depth == 0 else page.title
        lines.append(f"{'    ' * page.depth}* [{title}]({page.path})\n")
    return "".join(lines)


def public_names(src: Path = SRC, package: str = PACKAGE) -> dict[str, list[str]]:
    """The package's ``__all__`` split by kind, each in ``__all__``'s order.

    Read from ``__init__.py``'s source (nothing imported) and sorted by name: ``DATA_NAME``
    (constants and ``__version__``), ``CLASS_NAME`` (CamelCase), the rest functions.

    Returns:
        ``{"functions": [...], "classes": [...], "data": [...]}``.
    """
    tree = ast.parse((src / package / "__init__.py").read_text())
    names: list[str] = []
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            names = list(ast.literal_eval(node.value))
    kinds: dict[str, list[str]] = {"functions": [], "classes": [], "data": []}
    for name in names:
        kind = "data" if DATA_NAME.match(name) else "classes" if CLASS_NAME.match(name) \
            else "functions"
        kinds[kind].append(name)
    return kinds


def _directive(module: str, members: list[str], *, first: bool, values: bool = True) -> str:
    """One ``:::`` directive rendering ``members`` of ``module``; after the first, without the
    module's heading and docstring again, its members one heading level down."""
    lines = [f"::: {module}", "    options:",
             f"      members: [{', '.join(members)}]"]
    if not first:
        lines += ["      show_root_heading: false", "      show_root_toc_entry: false",
                  "      show_docstring_description: false", "      heading_level: 2"]
    if not values:
        lines += ["      show_attribute_values: false", "      show_source: false"]
    return "\n".join(lines) + "\n"


def page_text(page: ApiPage, src: Path = SRC) -> str:
    """The Markdown of one API page: a single directive, but for the top-level package
    (:func:`root_page`)."""
    if page.module == PACKAGE:
        return root_page(src)
    return f"::: {page.module}\n"


def root_page(src: Path = SRC, package: str = PACKAGE) -> str:
    """The public surface's page: its docstring and functions, then its classes, then its data by
    name, type and docstring (no values, no source)."""
    kinds = public_names(src, package)
    return "\n".join((_directive(package, kinds["functions"], first=True),
                      _directive(package, kinds["classes"], first=False),
                      _directive(package, kinds["data"], first=False, values=False)))


def write_pages() -> None:
    """Write the pages and the navigation into the build (called by mkdocs-gen-files)."""
    import mkdocs_gen_files

    pages = api_pages()
    for page in pages:
        full = f"{REFERENCE}/{page.path}"
        with mkdocs_gen_files.open(full, "w") as fd:
            fd.write(page_text(page))
    with mkdocs_gen_files.open(f"{REFERENCE}/SUMMARY.md", "w") as fd:
        fd.write(summary(pages))


# mkdocs-gen-files runs this file with runpy.run_path (``__name__ == "<run_path>"``); the test
# imports it for ``api_pages`` without writing anything.
if __name__ in {"__main__", "<run_path>"}:
    write_pages()
