"""The external formatters generated code goes through, run on text in memory (stdin → stdout)
so output is deterministic. A missing or failing formatter is a generation error: generated
code is never written unformatted."""

from __future__ import annotations

import shutil
import subprocess

TIMEOUT_S = 300


def run(exe_name: str, args: list[str], text: str, what: str, install_hint: str, exe: str | None = None) -> str:
    exe = exe or shutil.which(exe_name)
    if exe is None:
        raise RuntimeError(f"{exe_name} not found on PATH; {what} is formatted with it ({install_hint})")
    proc = subprocess.run([exe, *args], input=text.encode("utf-8"), capture_output=True, check=False, timeout=TIMEOUT_S)
    if proc.returncode != 0:
        raise RuntimeError(f"{exe_name} failed on {what}: {proc.stderr.decode('utf-8', 'replace').strip()[:2000]}")
    return proc.stdout.decode("utf-8")


def rustfmt(text: str, what: str) -> str:
    return run("rustfmt", ["--edition", "2021", "--emit", "stdout"], text, what, "rustup component add rustfmt")
