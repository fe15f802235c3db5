"""Griffe extension: Sphinx cross-reference roles in docstrings become mkdocstrings links.

The docstrings name other objects with Sphinx roles (``:func:`prepare```, ``:class:`~a.B```,
``:mod:`hexaleg.units```). Markdown has no roles and would show them as raw text, so before the
docstrings are rendered each role is rewritten into an autorefs cross-reference:

- the target is resolved the way Sphinx does: an absolute ``hexaleg.…`` path, or a name looked up
  in the scope of the documented object and its parents (members and imports);
- a target found in the package links to the page of its definition (its canonical path); a
  target outside the package (``os.replace``, numpy) or not found stays plain code;
- the reference is *optional*: an object that has no rendered entry (private, or undocumented)
  shows as code instead of failing ``mkdocs build --strict``;
- ``~a.b.c`` shows ``c``, ``title <target>`` shows ``title``, ``!target`` does not link, and
  ``:func:``/``:meth:`` add ``()`` as Sphinx does.

Only the text handed to mkdocstrings changes (line numbers of griffe's warnings stay valid); the
sources are not touched. Loaded from ``mkdocs.yml`` (``handlers.python.options.extensions``).
"""

from __future__ import annotations

import html
import re
from typing import Any

import griffe

ROLE = re.compile(
    r":(?:py:)?(?P<role>func|meth|class|mod|data|attr|obj|exc|const)"
    r":`(?P<body>[^`]+)`"
)
CALLABLE_ROLES = {"func", "meth"}


def _parse(body: str) -> tuple[str, str, bool]:
    """``(target, shown text, link?)`` of a role's body, following Sphinx's conventions."""
    body = body.strip()
    link = not body.startswith("!")
    body = body.lstrip("!")
    explicit = re.fullmatch(r"(?P<title>.+?)\s*<(?P<target>[^<>]+)>", body, flags=re.DOTALL)
    if explicit:
        return explicit["target"].strip(), explicit["title"].strip(), link
    if body.startswith("~"):
        target = body[1:]
        return target, target.rsplit(".", 1)[-1], link
    return body, body, link


def _lookup(obj: griffe.Object, target: str) -> griffe.Object | griffe.Alias | None:
    """The object a role's target names, seen from ``obj``'s scope; None when not in the tree."""
    collection = obj.modules_collection
    target = target.lstrip(".")
    candidates = [target]
    head, _, rest = target.partition(".")
    try:
        base = obj.resolve(head)
    except (griffe.NameResolutionError, griffe.AliasResolutionError, griffe.CyclicAliasError):
        base = None
    if base is not None:
        candidates.insert(0, f"{base}.{rest}" if rest else base)
    for candidate in candidates:
        try:
            return collection[candidate]
        except (KeyError, ValueError, griffe.AliasResolutionError, griffe.CyclicAliasError):
            continue
    return None


def rewrite(obj: griffe.Object, text: str) -> str:
    """``text`` with each Sphinx role replaced by an (optional) autorefs cross-reference."""

    def replace(match: re.Match[str]) -> str:
        target, shown, link = _parse(match["body"])
        if match["role"] in CALLABLE_ROLES and not shown.endswith(")"):
            shown += "()"
        code = f"<code>{html.escape(shown)}</code>"
        found = _lookup(obj, target) if link else None
        if found is None:
            return code
        try:
            identifier = found.canonical_path
        except (griffe.AliasResolutionError, griffe.CyclicAliasError):
            return code
        return f'<autoref identifier="{html.escape(identifier)}" optional>{code}</autoref>'

    return ROLE.sub(replace, text)


def _walk(obj: griffe.Object) -> Any:
    yield obj
    for member in obj.members.values():
        if member.is_alias:  # documented where it is defined
            continue
        yield from _walk(member)


class SphinxRoles(griffe.Extension):
    """Rewrite the Sphinx roles of every docstring of a package once it is loaded."""

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        for obj in _walk(pkg):
            if obj.docstring is not None and ":`" in obj.docstring.value:
                obj.docstring.value = rewrite(obj, obj.docstring.value)
