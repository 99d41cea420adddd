"""Every dependency of the anyspec harness on the rest of the repository, in one place.

The harness drives canspec through its CLI only (`python -m canspec check|gen`). It reuses
these existing test helpers; if one of them moves or changes its interface, fix it here:

- tests/targets/c/runner.c + tests/targets/c/gen_runner_tables.py (+ vectors_to_lines.py): the C vector runner
  (gen_runner_tables imports canspec's C model: that import happens in `c_runner_tables`);
- tests/targets/c/cbuild.py: the strict warning flags and the runner's summary line;
- tests/targets/c/c_sequences.py + tests/targets/c/seq_runner.c: the C sequence runner (vectors/sequences.json);
- tests/targets/python/sequence_runner.py: the Python sequence runner (`--package`);
- tests/targets/python/vector_runner.py: the Python vector runner (written for the shipped package
  `kaiwo_gateway`; `python_vector_runner` points that name at another package);
- tests/targets/json_bindings/py_runner.py: the Python JSON-bindings check of one vector case;
- tests/targets/json_bindings/node/ajv_check.cjs + build/json-node (ajv, typescript from `.ci/setup.d/60-json.sh`);
- tests/dbc_names.py: cantools reading a canspec DBC under the spec's signal names.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import re
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
TESTS = ROOT / "tests"
GENERATOR = ROOT / "generator"

C_RUNNER = TESTS / "targets" / "c" / "runner.c"
PY_VECTOR_RUNNER = TESTS / "targets" / "python" / "vector_runner.py"
JSON_PY_RUNNER = TESTS / "targets" / "json_bindings" / "py_runner.py"
AJV_CHECK = TESTS / "targets" / "json_bindings" / "node" / "ajv_check.cjs"
NODE_MODULES = ROOT / "build" / "json-node" / "node_modules"
TSC = NODE_MODULES / "typescript" / "bin" / "tsc"


def load_dbc_with_spec_names(dbc: Path, can: Any = None) -> Any:
    """cantools (strict) on a generated DBC, its DBC-unique signal names (and, given the spec's IR,
    its `dbc_name`s) read back as the spec's."""
    return _load(TESTS / "dbc_names.py", "anyspec_dbc_names").load_with_spec_names(dbc, strict=True, can=can)


def _load(path: Path, name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None, path
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


def _c_helpers() -> tuple[ModuleType, ModuleType, ModuleType]:
    cdir = str(TESTS / "targets" / "c")
    if cdir not in sys.path:
        sys.path.insert(0, cdir)
    if str(GENERATOR) not in sys.path:
        sys.path.insert(0, str(GENERATOR))
    return importlib.import_module("cbuild"), importlib.import_module("gen_runner_tables"), importlib.import_module("vectors_to_lines")


def c_strict_flags() -> list[str]:
    return list(_c_helpers()[0].STRICT)


def c_cases_re() -> Any:
    """The C runner's summary line: groups (cases, multi-frame texts, mismatches)."""
    return _c_helpers()[0].CASES_RE


def c_runner_tables(spec_path: Path) -> str:
    """runner_tables.h for `spec_path` (the per-message part of the C vector runner).

    runner.c's main() names the shipped spec's prefix (`kaiwo_gateway_lookup_id`, ...):
    the aliases below point those names at this spec's prefix."""
    text = _c_helpers()[1].tables(str(spec_path))
    prefix = text.splitlines()[0].split('"')[1].removesuffix(".h")
    if prefix != "kaiwo_gateway":
        text += "".join(f"#define kaiwo_gateway_{n} {prefix}_{n}\n" for n in ("msg_t", "lookup_id", "msg_info_t", "msg_info"))
    # A DLC-0 message has no shorter buffer to refuse (the tables would pass length -1u).
    text = re.sub(
        r"    st = \(int\)\w+_unpack\(&s, vc->data, -1u\);\n    if \(st != \(int\)\w+_ERR_LENGTH\) bad \+= fail\(vc, \"short buffer gave %d\", st\);\n",
        "    /* DLC 0: no shorter frame */\n", text)
    return text


def c_vectors_lines(doc: dict[str, Any], spec_path: Path) -> str:
    """The line form of a vectors file that runner.c reads (an empty frame written as `-`), each
    physical value with what its encodes and fixed-point decode must give (from the spec's IR)."""
    from canspec.pipeline import compile_spec

    spec = compile_spec(spec_path, _c_helpers()[1].C_TARGETS).spec  # the C runner's targets: another's refusal is not its concern
    if spec is None or spec.can is None:
        raise RuntimeError(f"{spec_path}: no CAN protocol to convert the vectors with")
    return str(_c_helpers()[2].convert(doc, spec.can))


def c_sequences(spec_path: Path, headers: Path, sequences: Path, build: Path) -> tuple[int, str]:
    """tests/targets/c/c_sequences.py: build the C sequence runner for the spec's headers and run it (no sanitizers)."""
    _c_helpers()
    return importlib.import_module("c_sequences").run_sequences(sequences, spec_path, headers, build, sanitize=False)


PY_SEQUENCE_RUNNER = TESTS / "targets" / "python" / "sequence_runner.py"


def python_vector_runner(package_dir: Path, package: str) -> ModuleType:
    """tests/targets/python/vector_runner.py bound to the generated package `package` in `package_dir`
    (call in a fresh interpreter: it imports the package under the shipped name)."""
    sys.path.insert(0, str(package_dir))
    mod = importlib.import_module(package)
    sys.modules["kaiwo_gateway"] = mod
    return _load(PY_VECTOR_RUNNER, "anyspec_vector_runner")


def json_case_check() -> Any:
    """py_runner.check(bindings_module, case) -> list of complaints (empty: agrees)."""
    return _load(JSON_PY_RUNNER, "anyspec_json_py_runner").check


def node_env() -> dict[str, str]:
    return {**os.environ, "NODE_PATH": str(NODE_MODULES)}
