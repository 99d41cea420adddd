"""The YAML fast path (yamlsource.fast_load: the data built from libyaml's events) gives exactly
what the loader gives (PyYAML's composer and constructor with canspec's resolvers): the same values
of the same types, and the same location for every mapping, key, value, sequence and item. It
runs on every YAML file the repository and its tests hold, on a document of every scalar form,
and on an imported spec; where it gives up (anchors, aliases, merge keys, repeated keys, other
tags, several documents, deep nesting), load_yaml still answers as the loader does."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from canspec.spec import yamlsource
from canspec.spec.problems import SpecError
from canspec.spec.yamlsource import LocDict, LocList, load_yaml
from canspec_cli import FIXTURES, ROOT


def slow_load(text: str, name: str) -> Any:
    loader = yamlsource._Loader(text)
    loader.display_name = name
    try:
        return loader.get_single_data()
    finally:
        loader.dispose()


def same(a: Any, b: Any, where: str = "$") -> None:
    """Equal values of equal types (1 == 1.0 == True in Python, not here), and equal locations."""
    assert type(a) is type(b), f"{where}: {type(a).__name__} vs {type(b).__name__}"
    if isinstance(a, LocDict):
        assert (a.loc, a.key_locs, a.value_locs) == (b.loc, b.key_locs, b.value_locs), where
        assert list(a) == list(b), where
        for key in a:
            same(key, next(k for k in b if k == key and type(k) is type(key)), f"{where}.{key!r} (key)")
            same(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, LocList):
        assert (a.loc, a.item_locs) == (b.loc, b.item_locs), where
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{where}[{i}]")
    elif a != a:  # NaN
        assert b != b, where
    else:
        assert a == b, f"{where}: {a!r} vs {b!r}"


def documents() -> list[Path]:
    found = [p for p in ROOT.rglob("*.yaml") if not {"build", "node_modules", ".git"} & set(p.relative_to(ROOT).parts)]
    assert len(found) > 200 and any(p.parent == FIXTURES / "valid" for p in found)
    return sorted(found)


def test_every_repository_file_loads_alike() -> None:
    fast = 0
    for path in documents():
        text = path.read_bytes().decode("utf-8", "replace").removeprefix("\ufeff")
        try:
            got = yamlsource.fast_load(text, str(path))
        except yamlsource._Unsupported:
            continue
        fast += 1
        same(got, slow_load(text, str(path)), str(path.relative_to(ROOT)))
    assert fast > 200  # the fast path takes the specs people write, not only the easy ones


SCALARS = """\
plain: text
quoted: "12"
single: 'x: y'
int: 42
negative: -7
hex: 0x1F
octal: 0o17
old_octal: 017
underscored: 1_000
sexagesimal: 1:30
float: 0.125
exponent: 1.5e3
inf: .inf
nan: .NaN
true_: true
True_: True
yes: yes
off: off
null_: null
tilde: ~
empty:
date: 2020-09-12
explicit_str: !!str 12
explicit_int: !!int "5"
explicit_float: !!float 1
bang: ! 12
block: |
  two
  lines
folded: >
  one
  line
unicode: 方向盘角度 °C
flow: {a: 1, b: [1, 2.5, x], c: {}}
list:
  - 1
  - - nested
    - {k: v}
  -
1: one
0x10: sixteen
-2: minus
1.5: half
"""


def test_every_scalar_form_loads_alike() -> None:
    same(yamlsource.fast_load(SCALARS, "s.yaml"), slow_load(SCALARS, "s.yaml"))


@pytest.mark.parametrize("text", [
    "a: &x 1\nb: *x\n",
    "base: &b {x: 1}\nthis:\n  <<: *b\n  y: 2\n",
    "a: 1\na: 2\n",
    "a: 1\n---\nb: 2\n",
    "a: !!binary aGVsbG8=\n",
    "a: !local 1\n",
    "? [1, 2]\n: x\n",
    "a: " + "[" * 60 + "]" * 60 + "\n",
    "a: 2020-09-12 10:00:00\nb: !!timestamp 2020-09-12\n",
    "a: [1, 2\n",
    "# only a comment\n",
])
def test_what_the_fast_path_leaves_to_the_loader_loads_as_before(text: str, tmp_path: Path) -> None:
    with pytest.raises(yamlsource._Unsupported):
        yamlsource.fast_load(text, "t.yaml")
    path = tmp_path / "t.yaml"
    path.write_text(text, encoding="utf-8")
    try:
        expected: Any = slow_load(text, str(path))
    except Exception as exc:  # noqa: BLE001 - what load_yaml turns into its SpecError
        expected = exc
    try:
        got: Any = load_yaml(path)
    except SpecError as exc:
        assert isinstance(expected, Exception) or expected is None, exc.problems
        return
    same(got, expected)


def test_an_imported_spec_takes_the_fast_path(tmp_path: Path) -> None:
    """The YAML `canspec import` writes (one flow mapping per signal) is the large case the path is for."""
    dbc = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
    done = subprocess.run([sys.executable, "-m", "canspec", "import", str(dbc), "-o", str(tmp_path / "spec")], capture_output=True, text=True,
                          check=False, cwd=ROOT, env={"PYTHONPATH": str(ROOT / "generator"), "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    path = tmp_path / "spec" / "kaiwo_gateway.yaml"
    text = path.read_text(encoding="utf-8")
    same(yamlsource.fast_load(text, str(path)), slow_load(text, str(path)))
