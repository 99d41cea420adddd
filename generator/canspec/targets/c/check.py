"""What the C target refuses (`canspec check` runs it):

- c-name-clash: distinct spec names that give the same C name (see names.py) — two declarations,
  or two struct fields, of one name do not compile. A name the C target escapes (a keyword gets
  a trailing `_`) can meet another that way too. Neither can be renamed silently without
  changing the other's API, so the report names both elements.
- c-name-length (a warning; `check --strict` refuses it): two C names that agree in their first
  63 characters. C99 (5.2.4.1) lets a compiler tell internal identifiers and macro names apart
  by those alone and MISRA C:2012 (rules 5.1-5.5) requires them distinct there, but every
  compiler in use reads more, so the header still builds. A signal or message can be given a
  shorter `c_name` for C alone.
- c-header-name: a protocol whose header would take the name of a C library header the
  headers include (`string.h`): found first on the include path, it would stand in for it.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from canspec import ir
from canspec.spec.problems import Problem, error, warning
from canspec.targets.c.names import Origin, declared, header_names, members

CLASH_HINT = "rename one of them: C names join the words of spec names with `_` after the protocol's prefix, and escape C and C++ keywords with a trailing `_`"
LENGTH_HINT = "give the signal or message a shorter `c_name:` (its name in the C target only), or shorten the name itself"
LIBRARY_HEADERS = ("stdbool.h", "stddef.h", "stdint.h", "string.h")
SIGNIFICANT = 63  # C99 5.2.4.1: significant initial characters of an internal identifier or macro name


def c_problems(spec: ir.Spec) -> Iterator[Problem]:
    if spec.can is None:
        return
    for header in sorted(set(header_names(spec.can)) & set(LIBRARY_HEADERS)):
        yield error(f"protocol {spec.can.name!r} gives the C header {header}, the name of the C library header it includes", spec.can.loc,
                    "rename the protocol: the C target names its headers after it", "c-header-name")
    pairs: set[tuple[str, str]] = set()  # two elements clash once, however many names they share
    yield from _clashes(declared(spec.can), "name", pairs)
    for msg in spec.can.messages:
        yield from _clashes(members(msg), f"field of `{msg.name}`", pairs)
    yield from _too_alike(declared(spec.can), "name", pairs)
    for msg in spec.can.messages:
        yield from _too_alike(members(msg), f"field of `{msg.name}`", pairs)


def _clashes(items: Iterable[tuple[str, Origin]], scope: str, pairs: set[tuple[str, str]]) -> Iterator[Problem]:
    """One problem per pair of elements whose names meet (at the first name they share)."""
    first: dict[str, Origin] = {}
    for name, origin in items:
        seen = first.setdefault(name, origin)
        if seen is origin or (origin[0], seen[0]) in pairs:
            continue
        pairs.add((origin[0], seen[0]))
        where = f" (at {seen[1]})" if seen[1] is not None else ""
        yield error(f"{origin[0]} gives the C {scope} `{name}`, which {seen[0]}{where} gives too", origin[1] or seen[1], CLASH_HINT, "c-name-clash")



def _too_alike(items: Iterable[tuple[str, Origin]], scope: str, pairs: set[tuple[str, str]]) -> Iterator[Problem]:
    """One problem per pair of elements (or per element) with distinct names that agree in their
    first SIGNIFICANT characters; names that clash outright are reported by `_clashes`."""
    first: dict[str, tuple[str, Origin]] = {}
    for name, origin in items:
        seen_name, seen = first.setdefault(name[:SIGNIFICANT], (name, origin))
        if seen_name == name or (origin[0], seen[0]) in pairs:
            continue
        pairs.add((origin[0], seen[0]))
        other = "" if seen is origin else f" of {seen[0]}" + (f" (at {seen[1]})" if seen[1] is not None else "")
        yield warning(f"{origin[0]} gives the C {scope} `{name}`, the same in its first {SIGNIFICANT} characters as `{seen_name}`{other}: "
                    f"C99 compilers need tell names apart only by those (MISRA C:2012 rules 5.1-5.5)", origin[1] or seen[1], LENGTH_HINT, "c-name-length")
