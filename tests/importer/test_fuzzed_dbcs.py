"""Dirty input beyond the corpus: real DBCs with a few lines mutated (a character dropped or added, a
line cut, doubled or removed, a number turned huge, negative, zero or non-finite). Each import ends
in a spec that `canspec check` judges, or in DbcError (one line with its place) — never in another
exception; a spec the check accepts generates the DBC, C, Python and vectors. The first run of this
fuzzer found a 10^10-bit signal that made cantools take 24 GB; the seeds are fixed, so a failure
here reproduces with its case number."""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from canspec.generation import generate
from canspec.importer.dbctext import DbcError
from canspec.importer.load import load
from canspec.importer.run import import_loaded

from importer.corpus import opendbc_files

CASES = 120
NUMBERS = ["9999999999", "-1", "18446744073709551616", "1e400", "0", "65", "nan", ".5"]


def _mutated(lines: list[str], rng: random.Random) -> list[str]:
    out = list(lines)
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(len(out))
        line, op = out[i], rng.randrange(6) if rng.random() < 0.5 else 5
        if op == 0 and line:
            j = rng.randrange(len(line))
            out[i] = line[:j] + line[j + 1 :]
        elif op == 1:
            out.insert(i, line)
        elif op == 2:
            out[i] = line[: rng.randrange(len(line) + 1)]
        elif op == 3 and line:
            j = rng.randrange(len(line))
            out[i] = line[:j] + rng.choice('"-0.9e:;|@+ ') + line[j:]
        elif op == 4:
            del out[i]
        else:
            out[i] = line.replace("1", rng.choice(NUMBERS), 1)
    return out


def _small_sources() -> list[Path]:
    return sorted(opendbc_files(), key=lambda p: p.stat().st_size)[10:60:5]


@pytest.mark.parametrize("case", range(CASES))
def test_a_mutated_dbc_imports_or_is_refused_in_one_line(case: int, tmp_path: Path) -> None:
    rng = random.Random(case)
    source = rng.choice(_small_sources())
    path = tmp_path / source.name
    path.write_text("\n".join(_mutated(source.read_text(encoding="utf-8", errors="replace").splitlines(), rng)) + "\n", encoding="utf-8")
    try:
        spec, _, compiled = import_loaded([load(path, str(path))])
    except DbcError as exc:
        text = str(exc)
        assert text.startswith(str(path)) and "\n" not in text, text
        return
    assert compiled.spec is not None or compiled.errors
    if compiled.spec is not None:
        outputs = generate(compiled.spec, ["dbc", "c", "python", "vectors"])
        assert all(outputs.values()) and len(spec["messages"]) == len(compiled.spec.can.messages)
