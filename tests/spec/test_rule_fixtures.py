"""One invalid spec per validation rule (tests/fixtures/invalid/<rule>.yaml), each stating its
expected problem in a header comment (`# expect: error [rule] at [FILE:]LINE:COL`). `canspec
check` must report exactly that, with the right exit code and no traceback; and every rule ID
the code can emit must have its fixture, so a new rule without one fails here."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from canspec_cli import FIXTURES, ROOT, assert_no_traceback, run_canspec

INVALID = FIXTURES / "invalid"
VALID = FIXTURES / "valid"
PACKAGE = ROOT / "generator" / "canspec"
# Every module that reports spec problems: the spec stage, the pipeline, and each target's refusals
# of what it cannot express (targets/<name>/*.py); diff/ reports on revisions, not on one spec.
RULE_MODULES = sorted(
    str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py") if not p.is_relative_to(PACKAGE / "diff") and "error(" in p.read_text(encoding="utf-8")
)
EXPECT = re.compile(r"^# expect: (?P<sev>error|warning) \[(?P<rule>[a-z0-9-]+)\] at (?:(?P<file>[^\s:]+):)?(?P<line>\d+):(?P<col>\d+)", re.MULTILINE)
PROBLEM = re.compile(r"^(?P<where>.+?): (?P<sev>error|warning): .* \[(?P<rule>[a-z0-9-]+)\]$", re.MULTILINE)


def fixtures() -> list[Path]:
    return sorted(INVALID.glob("*.yaml"))


def expectation(path: Path) -> re.Match[str]:
    m = EXPECT.search(path.read_text(encoding="utf-8"))
    assert m, f"{path.name}: no `# expect: error|warning [rule] at LINE:COL` header"
    return m


@pytest.mark.parametrize("path", fixtures(), ids=lambda p: p.stem)
def test_fixture_reports_its_rule(path: Path) -> None:
    exp = expectation(path)
    assert exp["rule"] == path.stem, "a fixture is named for the rule it breaks"
    proc = run_canspec("check", path.name, cwd=INVALID)
    assert_no_traceback(proc)
    where = f"{exp['file'] or path.name}:{exp['line']}:{exp['col']}"
    found = [(m["where"], m["sev"], m["rule"]) for m in PROBLEM.finditer(proc.stderr)]
    assert (where, exp["sev"], exp["rule"]) in found, proc.stderr
    # The fixture breaks one rule: nothing else may fire (it would hide a regression) but what its
    # `# also: [rule]` line names (a target refusal that cannot be isolated: rust-text-mux needs a
    # multiplexed message, which the targets without multiplexing refuse too).
    also = set(re.findall(r"^# also: \[([a-z0-9-]+)\]", path.read_text(encoding="utf-8"), re.MULTILINE))
    assert {r for _, _, r in found} - also == {exp["rule"]}, proc.stderr
    assert proc.returncode == (1 if exp["sev"] == "error" else 0), proc.stderr
    if exp["sev"] == "warning":
        strict = run_canspec("check", "--strict", path.name, cwd=INVALID)
        assert_no_traceback(strict)
        assert strict.returncode == 1 and f"{where}: warning:" in strict.stderr, strict.stderr


@pytest.mark.parametrize("path", sorted(VALID.glob("*.yaml")), ids=lambda p: p.stem)
def test_fixture_bases_are_clean(path: Path) -> None:
    """The bases the invalid fixtures break are themselves valid (so each fixture isolates one rule)."""
    proc = run_canspec("check", "--strict", path)
    assert proc.returncode == 0 and "error" not in proc.stderr and "warning" not in proc.stderr, proc.stderr


def _rule_ids() -> tuple[set[str], list[str], list[str]]:
    """Rule IDs (constants), f-string rule patterns, and rule-less error() calls in validation code."""
    ids: set[str] = set()
    patterns: list[str] = []
    unnamed: list[str] = []
    for name in RULE_MODULES:
        path = PACKAGE / name
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("error", "warning")):
                continue
            arg = node.args[3] if len(node.args) >= 4 else next((k.value for k in node.keywords if k.arg == "rule"), None)
            if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and arg.value:
                ids.add(arg.value)
            elif isinstance(arg, ast.JoinedStr):
                patterns.append("".join(re.escape(v.value) if isinstance(v, ast.Constant) else "[a-z0-9]+" for v in arg.values))
            elif name in ("spec/resolve.py", "spec/validate.py") or name.startswith("targets/"):
                unnamed.append(f"{name}:{node.lineno}")
    return ids, patterns, unnamed


def test_every_rule_has_a_fixture() -> None:
    ids, patterns, unnamed = _rule_ids()
    have = {p.stem for p in fixtures()}
    assert len(ids) >= 40, ids  # the parser still finds the rules
    assert not unnamed, f"validation problems without a rule ID: {unnamed}"
    assert not ids - have, f"rules without a fixture under tests/fixtures/invalid/: {sorted(ids - have)}"
    for pattern in patterns:
        assert any(re.fullmatch(pattern, h) for h in have), f"no fixture for rules matching {pattern}"
    known = ids | {h for h in have if any(re.fullmatch(p, h) for p in patterns)}
    assert not have - known, f"fixtures for rules the code no longer has: {sorted(have - known)}"
