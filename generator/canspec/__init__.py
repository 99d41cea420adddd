"""canspec: one machine-readable CAN/JSON protocol spec, generated into every target.

The Python API is what this module exports (`__all__`), and the IR's model classes under
`canspec.ir` (`ir.Spec`, `ir.Message`, `ir.Signal`, ...: what a compiled spec is made of). Never
import anything from canspec that is not available here: every other module is internal and may
change without notice. The names are loaded on first use, so `import canspec` stays cheap and the
log decoder's optional dependencies (`pip install canspec[logs]`) are needed only by its names.

    import canspec

    compiled = canspec.compile_spec("spec")                 # never raises for a bad spec
    for problem in compiled.problems:
        print(problem.format())                             # file:line:col, rule, hint
    files = canspec.generate(compiled.spec, ["dbc", "c"])  # {target: {relative path: bytes}}, in memory

    decoder = canspec.Decoder(compiled.spec.can.messages)   # bus logs → one Arrow table per message
    for chunk in canspec.read_log("drive.blf"):
        tables = decoder.decode(chunk.batch).tables
    tables = canspec.decode_file(compiled.spec.can.messages, "drive.blf").tables   # a whole file (Dask)
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

# public name → the internal module that defines it
_EXPORTS = {
    "compile_spec": "canspec.pipeline",
    "Compiled": "canspec.pipeline",
    "Problem": "canspec.spec.problems",
    "generate": "canspec.generation",
    "GenerationError": "canspec.generation",
    "target_names": "canspec.targets",
    "Decoder": "canspec.logs.bulk",
    "Batch": "canspec.logs.frames",
    "read_log": "canspec.logs.logread",
    "InputError": "canspec.logs.logread",
    "decode_file": "canspec.logs.fleet",
    "RestBus": "canspec.runtime.simulate",
    "SimFault": "canspec.runtime.simulate",
    "SimulationError": "canspec.runtime.simulate",
}

__all__ = ["__version__", "ir", *_EXPORTS]

if TYPE_CHECKING:
    from canspec import ir
    from canspec.generation import GenerationError, generate
    from canspec.logs.bulk import Decoder
    from canspec.logs.fleet import decode_file
    from canspec.logs.frames import Batch
    from canspec.logs.logread import InputError, read_log
    from canspec.pipeline import Compiled, compile_spec
    from canspec.runtime.simulate import RestBus, SimFault, SimulationError
    from canspec.spec.problems import Problem
    from canspec.targets import target_names


def __getattr__(name: str) -> Any:
    if name == "ir":
        return importlib.import_module("canspec.ir")
    if name not in _EXPORTS:
        raise AttributeError(f"module 'canspec' has no attribute {name!r}")
    value = getattr(importlib.import_module(_EXPORTS[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
