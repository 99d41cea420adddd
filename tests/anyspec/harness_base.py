"""What every stage of the anyspec harness shares (harness.py): where it writes, the toolchains it
needs, a spec's result and failures, and running a command or canspec's CLI."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from anyspec import adapters, cross_stage

ROOT = adapters.ROOT
BUILD = ROOT / "build" / "anyspec"
FAILURES = BUILD / "failures"
TIMEOUT_S = 600
CANSPEC_TARGETS = ("dbc", "vectors", "json_vectors", "c", "python", "jsonschema", "rust", "json_bindings", "docs")
C_MODES = (
    ("gcc", ["-std=c99"], "c99"), ("clang", ["-std=c99"], "c99"), ("g++", ["-x", "c++", "-std=c++11"], "c++11"),
    ("clang++", ["-x", "c++", "-std=c++11"], "c++11"))
TOOLS = ("gcc", "clang", "g++", "clang++", "cargo", "node", "ruff")


# --- results -------------------------------------------------------------------------------


@dataclass
class Failure:
    sid: str
    seed: int | None
    target: str  # check | gen:<target> | c | python | cantools | canmatrix | json | typescript | rust
    stage: str  # what ran, e.g. "gcc c99 fixture_messages.h", "vector runner", "mypy --strict"
    message: str
    spec_dir: str
    features: list[str] = field(default_factory=list)
    refusal: list[str] | None = None  # check refusals: the NEW features that explain it ([] = none)

    @property
    def signature(self) -> str:
        return f"{self.target} | {signature_text(self.message)}"


@dataclass
class SpecRef:
    """One drawn spec of a batch: where it is written and what it uses (a job's input, its result's head)."""

    sid: str
    seed: int | None
    spec_dir: str
    entry: str
    out_dir: str
    features: list[str]
    facts: dict[str, Any]


@dataclass
class SpecResult(SpecRef):
    accepted: bool = False
    generated: list[str] = field(default_factory=list)
    checked: list[str] = field(default_factory=list)  # toolchains that ran on this spec
    failures: list[Failure] = field(default_factory=list)
    seconds: float = 0.0


SIGNATURE_LINES = (
    r"^[A-Z]+\d+ ",  # a ruff rule
    r"(?<![\w.])error(\[\w+\])?:",  # compilers, mypy, rustc, canspec
    r"\berror\b|Error\b|mismatch|failed|panicked|refused|disagree",
)


def signature_text(message: str) -> str:
    """A failure message without the details that differ between specs (names, numbers, paths)."""
    lines = [ln for ln in message.splitlines() if ln.strip() and not re.match(r"\s*(\d+\s*)?[|>]|\s*-->|\s*from \.|\s*In file included|\s+from ", ln)]
    line = next((ln for rx in SIGNATURE_LINES for ln in lines if re.search(rx, ln)), lines[0] if lines else "")
    runner = [ln for ln in lines if re.match(r"line \d+: ", ln)]  # the C runner's first mismatch
    exc = [ln for ln in lines if re.match(r"\w+(Error|Exception): ", ln)]  # a traceback's exception
    panic = [lines[i + 1] for i, ln in enumerate(lines[:-1]) if "panicked at" in ln]  # a Rust test's panic message
    mismatch = [ln for ln in lines if re.match(r"(case \d+|multiframe|MISMATCH) ", ln)]  # the Python runners
    line = (runner or panic or exc[-1:] or mismatch or [line])[0]
    line = re.sub(r"^line \d+: \S+ \(\w+\)", "line N: MSG (KIND)", line)
    line = re.sub(r"(mismatch: |^\w+Error: )\w+:", r"\1X:", line)
    line = re.sub(r"\b\w+?_(common|messages|enums|dispatch|monitor|text)\.h\b", r"P_\1.h", line)
    line = re.sub(r"\b[\w/.-]*?(\w+\.(py|rs|ts|h))\b", r"P/\1", line)
    m = re.match(r"(canspec gen: target \w+: )(.*)", line)
    if m:  # names from the spec in canspec's own messages
        line = m.group(1) + re.sub(
            r"(?<![/\w.])(?!error\b)(?:[a-z_][a-z0-9_]*\.)?[a-z_][a-z0-9_]*(?=:)(?!\d)|(?<=value table )\w+|(?<=JSON field )\S+", "X", m.group(2)
        )
    line = re.sub(r"/\S+/", "", line)
    line = re.sub(r"\bs\d{4}\b", "S", line)
    line = re.sub(r"'[^']*'|\"[^\"]*\"|`[^`]*`|‘[^’]*’", "X", line)
    line = re.sub(r"0x[0-9A-Fa-f]+|\b\d+(\.\d+)?\b", "N", line)
    return line.strip()[:160]


def clip(text: str, limit: int = 6000) -> str:
    """The first `limit` characters of a tool's output, cut at a line end."""
    text = text.strip()
    return text if len(text) <= limit else text[: text.rfind("\n", 0, limit)] + "\n[...]"


def sh(cmd: list[str], cwd: Path | None = None, env: dict[str, str] | None = None, timeout: float = TIMEOUT_S) -> tuple[int, str, str]:
    try:
        proc = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired as exc:
        return 124, str(exc.stdout or ""), f"timeout after {timeout} s: {' '.join(cmd)}"
    return proc.returncode, proc.stdout, proc.stderr


def canspec_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(adapters.GENERATOR) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def canspec(*args: str) -> tuple[int, str, str]:
    return sh([sys.executable, "-m", "canspec", *args], env=canspec_env())


def missing_tools() -> list[str]:
    """Toolchains the harness needs and cannot find (each one fails the run, never skips it)."""
    out = [f"{t} (not on PATH)" for t in TOOLS if shutil.which(t) is None] + cross_stage.missing_tools()
    if shutil.which("cargo") and sh(["cargo", "clippy", "--version"])[0] != 0:
        out.append("cargo clippy (rustup component add clippy)")
    for mod in ("cantools", "canmatrix", "jsonschema", "mypy", "hypothesis", "yaml"):
        try:
            __import__(mod)
        except ImportError:
            out.append(f"python module {mod}")
    if not (adapters.NODE_MODULES / "ajv").is_dir() or not adapters.TSC.is_file():
        out.append(f"ajv/typescript in {adapters.NODE_MODULES} (run `make setup`: .ci/setup.d/60-json.sh)")
    return out


class Ctx:
    def __init__(self, res: SpecResult) -> None:
        self.res = res
        self.spec = Path(res.spec_dir) / res.entry
        self.out = Path(res.out_dir)
        self.stage_filter: str | None = None
        self.bytewise = True
        self.work = Path(res.out_dir).parent / "work"
        self.work.mkdir(parents=True, exist_ok=True)

    def want(self, *labels: str) -> bool:
        """Whether to run a sub-stage (the shrinker re-runs only the one that failed)."""
        f = self.stage_filter
        return f is None or any(label.startswith(f) or f.startswith(label) for label in labels)

    def fail(self, target: str, stage: str, message: str) -> None:
        self.res.failures.append(Failure(self.res.sid, self.res.seed, target, stage, clip(message), self.res.spec_dir, self.res.features))
