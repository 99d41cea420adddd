"""MISRA C:2012 findings of the generated C headers, by cppcheck 2.10's misra addon, in every
preprocessor configuration the headers have (the strategy macros of cross.py, each value).

cppcheck runs on a one-line translation unit that includes the umbrella header, once per
configuration (-D for each macro), as C99 on a 32-bit ARM platform with the standard headers of
misra_include/ (the typedefs the addon needs for essential types), with --enable=style so its
core checks that stand for MISRA rules run too (mapped to their rules below, as the addon's own
getCppcheckRules() lists them). No rule texts are needed or used: the addon reports rule numbers
(`misra-c2012-N.M`, "use --rule-texts to get proper output"), and RULE_CATEGORY below gives each
rule's category (Mandatory / Required / Advisory): numbers and categories only, MISRA's texts
are not distributable. Findings are (rule, file, line), kept only for files in the headers
directory, de-duplicated across configurations.

A deviation record is a Markdown file with a table | Rule | Where | Why |: one row per advisory
rule, Where a comma-separated list of file-name globs (`*` = every header). --deviations FILE
fails (exit 1) on any finding that no row covers, and on rows that name a Required or Mandatory
rule (those need a formal deviation or a fix, not a record entry).

    python3 tests/targets/c/cross/misra.py [--headers DIR] [--strategies 'M=0,1;...'] [--deviations FILE]
"""

from __future__ import annotations

import argparse
import fnmatch
import itertools
import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import cross  # noqa: E402

PLATFORM = "arm32-wchar_t4"
# <stdint.h> & co. as a 32-bit ARM target has them: the addon needs the typedefs to know
# essential types (rules 10.x); findings inside these stubs are not the headers' and are dropped.
STUB_INCLUDE = HERE / "misra_include"

# MISRA C:2012 (third edition, with Amendments 1 and 2: the rules cppcheck 2.10 checks):
# M = Mandatory, R = Required, A = Advisory. Directives are "D<n>.<m>".
_CATS = """
D1.1 R  D2.1 R  D3.1 R  D4.1 R  D4.2 A  D4.3 R  D4.4 A  D4.5 A  D4.6 A  D4.7 R  D4.8 A  D4.9 A
D4.10 R  D4.11 R  D4.12 R  D4.13 A  D4.14 R
1.1 R  1.2 A  1.3 R  1.4 R
2.1 R  2.2 R  2.3 A  2.4 A  2.5 A  2.6 A  2.7 A
3.1 R  3.2 R
4.1 R  4.2 A
5.1 R  5.2 R  5.3 R  5.4 R  5.5 R  5.6 R  5.7 R  5.8 R  5.9 A
6.1 R  6.2 R
7.1 R  7.2 R  7.3 R  7.4 R
8.1 R  8.2 R  8.3 R  8.4 R  8.5 R  8.6 R  8.7 A  8.8 R  8.9 A  8.10 R  8.11 A  8.12 R  8.13 A  8.14 R
9.1 M  9.2 R  9.3 R  9.4 R  9.5 R
10.1 R  10.2 R  10.3 R  10.4 R  10.5 A  10.6 R  10.7 R  10.8 R
11.1 R  11.2 R  11.3 R  11.4 A  11.5 A  11.6 R  11.7 R  11.8 R  11.9 R
12.1 A  12.2 R  12.3 A  12.4 A  12.5 M
13.1 R  13.2 R  13.3 A  13.4 A  13.5 R  13.6 M
14.1 R  14.2 R  14.3 R  14.4 R
15.1 A  15.2 R  15.3 R  15.4 A  15.5 A  15.6 R  15.7 R
16.1 R  16.2 R  16.3 R  16.4 R  16.5 R  16.6 R  16.7 R
17.1 R  17.2 R  17.3 M  17.4 M  17.5 A  17.6 M  17.7 R  17.8 A
18.1 R  18.2 R  18.3 R  18.4 A  18.5 A  18.6 R  18.7 R  18.8 R
19.1 M  19.2 A
20.1 A  20.2 R  20.3 R  20.4 R  20.5 A  20.6 R  20.7 R  20.8 R  20.9 R  20.10 A  20.11 R  20.12 R
20.13 R  20.14 R
21.1 R  21.2 R  21.3 R  21.4 R  21.5 R  21.6 R  21.7 R  21.8 R  21.9 R  21.10 R  21.11 R  21.12 A
21.13 M  21.14 R  21.15 R  21.16 R  21.17 M  21.18 M  21.19 M  21.20 M  21.21 R
22.1 R  22.2 M  22.3 R  22.4 M  22.5 M  22.6 M  22.7 R  22.8 R  22.9 R  22.10 R
"""
_NAMES = {"M": "Mandatory", "R": "Required", "A": "Advisory"}
RULE_CATEGORY = {r: _NAMES[c] for r, c in zip(_CATS.split()[::2], _CATS.split()[1::2])}

# cppcheck core checks that the misra addon leaves to cppcheck (its getCppcheckRules()).
CORE_RULE = {
    "alwaysFalse": "14.3", "alwaysTrue": "14.3", "knownConditionTrueFalse": "14.3", "compareValueOutOfTypeRangeError": "14.3",
    "duplicateBreak": "2.1", "unreachableCode": "2.1",
    "redundantCondition": "2.2", "redundantAssignment": "2.2", "redundantAssignInSwitch": "2.2", "unreadVariable": "2.2",
    "unusedLabel": "2.6", "shadowVariable": "5.3", "funcArgNamesDifferent": "8.3", "constPointer": "8.13",
    "constParameterPointer": "8.13", "constVariablePointer": "8.13", "uninitvar": "9.1", "unknownEvaluationOrder": "13.2",
    "sizeofCalculation": "13.6", "missingReturn": "17.4", "argumentSize": "17.5", "pointerOutOfBounds": "18.1",
    "comparePointers": "18.3", "danglingLifetime": "18.6", "overlappingWriteUnion": "19.1", "overlappingWriteFunction": "19.1",
    "preprocessorErrorDirective": "20.6", "invalidFunctionArg": "21.13", "bufferAccessOutOfBounds": "21.17",
    "memleak": "22.1", "resourceLeak": "22.1", "autovarInvalidDeallocation": "22.2", "incompatibleFileOpen": "22.3",
    "writeReadOnlyFile": "22.4", "useClosedFile": "22.6",
}
# cppcheck's remarks about its own run, not about the code.
NOT_FINDINGS = {"missingInclude", "missingIncludeSystem", "checkersReport", "toomanyconfigs", "unmatchedSuppression",
                "normalCheckLevelMaxBranches", "syntaxError", "internalAstError", "cppcheckError"}


@dataclass(frozen=True)
class Finding:
    rule: str  # "15.5"; "" for a cppcheck check with no MISRA rule
    file: str  # name inside the headers directory
    line: int
    col: int
    source: str  # "misra-c2012-15.5" or the cppcheck check id

    @property
    def category(self) -> str:
        return RULE_CATEGORY.get(self.rule, "unknown") if self.rule else "cppcheck"


_LINE = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+):(?P<col>\d+):(?P<sev>\w+):(?P<id>[\w.-]+):")


def parse(output: str, headers: Path) -> list[Finding]:
    """cppcheck --template='{file}:{line}:{column}:{severity}:{id}:{message}' lines → findings in `headers`."""
    out = []
    base = headers.resolve()
    for line in output.splitlines():
        m = _LINE.match(line)
        if not m or m.group("id") in NOT_FINDINGS:
            continue
        path = Path(m.group("file"))
        try:
            rel = path.resolve().relative_to(base)
        except ValueError:
            continue  # the probe translation unit or a system header
        cid = m.group("id")
        rule = cid[len("misra-c2012-"):] if cid.startswith("misra-c2012-") else CORE_RULE.get(cid, "")
        out.append(Finding(rule, str(rel), int(m.group("line")), int(m.group("col")), cid))
    return out


def configurations(strategies: str) -> list[tuple[tuple[str, str], ...]]:
    """Every combination of the strategy macros' values (the /le marker does not matter here)."""
    combos = [s.defines for s in cross.parse_strategies(strategies) if s.defines]
    return combos or [()]


def run_cppcheck(headers: Path, config: tuple[tuple[str, str], ...], work: Path, prefix: str) -> str:
    tu = work / "misra_probe.c"
    tu.write_text(f'#include "{prefix}.h"\n')
    defines = [f"-D{m}={v}" for m, v in config]
    # Without -D cppcheck would check (a few of) all #if configurations at once: one at a time instead.
    cmd = ["cppcheck", "--addon=misra", "--enable=style", "--std=c99", "--language=c", f"--platform={PLATFORM}",
           "--inline-suppr", "-q", f"-I{STUB_INCLUDE}", f"-I{headers}", *defines, *(["--max-configs=1"] if not config else []),
           "--template={file}:{line}:{column}:{severity}:{id}:{message}", str(tu)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=900, cwd=work)
    if proc.returncode != 0 or "Bailing out" in proc.stderr:
        raise RuntimeError(f"cppcheck failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr[-3000:]}")
    return proc.stderr + proc.stdout


def analyse(headers: Path, strategies: str, jobs: int | None = None) -> dict[str, list[Finding]]:
    """configuration name → findings."""
    headers = headers.resolve()  # cppcheck runs in a temporary directory: a relative -I found nothing, and 0 findings came back
    prefix = cross.header_prefix(headers)
    if not (headers / f"{prefix}.h").is_file():
        raise RuntimeError(f"no {prefix}.h in {headers}")
    configs = configurations(strategies)

    def one(config: tuple[tuple[str, str], ...]) -> tuple[str, list[Finding]]:
        with tempfile.TemporaryDirectory(prefix="misra-") as tmp:
            name = ",".join(f"{m}={v}" for m, v in config) or "default"
            return name, parse(run_cppcheck(headers, config, Path(tmp), prefix), headers)

    with ThreadPoolExecutor(max_workers=jobs or os.cpu_count() or 2) as pool:
        return dict(pool.map(one, configs))


# --- the deviation record -----------------------------------------------------------------


@dataclass(frozen=True)
class Deviation:
    rule: str
    where: tuple[str, ...]
    why: str
    line: int

    def covers(self, f: Finding) -> bool:
        return f.rule == self.rule and any(fnmatch.fnmatch(f.file, g) or fnmatch.fnmatch(Path(f.file).name, g) for g in self.where)


def load_record(path: Path) -> tuple[list[Deviation], list[str]]:
    """The rows of the record's tables whose first cell is a rule number; errors for bad rows."""
    devs, errors = [], []
    for no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.lstrip().startswith("|") else []
        if not cells:
            continue
        m = re.fullmatch(r"(?:Rule\s+)?(\d+\.\d+)", cells[0].strip("`* "))
        if not m:
            continue
        rule = m.group(1)
        where = tuple(g.strip().strip("`") for g in (cells[1] if len(cells) > 1 else "").split(",") if g.strip().strip("`"))
        why = cells[2] if len(cells) > 2 else ""
        cat = RULE_CATEGORY.get(rule)
        if cat is None:
            errors.append(f"{path.name}:{no}: {rule} is not a MISRA C:2012 rule number")
        elif cat != "Advisory":
            errors.append(f"{path.name}:{no}: rule {rule} is {cat}: only advisory rules can be recorded here")
        if not where or not why:
            errors.append(f"{path.name}:{no}: rule {rule} needs both where (file globs) and why")
        devs.append(Deviation(rule, where, why, no))
    return devs, errors


def check_record(findings: list[Finding], devs: list[Deviation]) -> tuple[list[Finding], list[Deviation]]:
    """(findings no row covers, rows that cover nothing)."""
    uncovered = [f for f in findings if not any(d.covers(f) for d in devs)]
    stale = [d for d in devs if not any(d.covers(f) for f in findings)]
    return uncovered, stale


# --- report -------------------------------------------------------------------------------


def unique(by_config: dict[str, list[Finding]]) -> list[Finding]:
    return sorted(set(itertools.chain.from_iterable(by_config.values())), key=lambda f: (f.file, f.line, f.col, f.source))


def _rule_key(rule: str) -> tuple[int, ...]:
    return tuple(int(x) for x in re.findall(r"\d+", rule)) or (999,)


def report(by_config: dict[str, list[Finding]]) -> str:
    configs = list(by_config)
    allf = unique(by_config)
    out = [(f"MISRA C:2012, cppcheck {cppcheck_version()} misra addon + core checks, platform {PLATFORM}; "
            f"configurations: {', '.join(configs)}; findings de-duplicated across configurations")]
    out.append(f"{'rule':<7} {'category':<10} {'findings':>8}  " + "  ".join(f"{c:>{max(8, len(c))}}" for c in configs) + "  checks")
    per_conf = {c: Counter(f.rule or f.source for f in fs) for c, fs in by_config.items()}
    groups: dict[str, list[Finding]] = defaultdict(list)
    for f in allf:
        groups[f.rule or f.source].append(f)
    for key in sorted(groups, key=lambda k: (_rule_key(k) if groups[k][0].rule else (1000,), k)):
        fs = groups[key]
        cat = fs[0].category
        sources = sorted({f.source for f in fs if not f.source.startswith("misra-")})
        out.append(f"{key:<7} {cat:<10} {len(fs):>8}  " + "  ".join(f"{per_conf[c].get(key, 0):>{max(8, len(c))}}" for c in configs)
                   + (f"  cppcheck: {', '.join(sources)}" if sources else ""))
    cats = Counter(f.category for f in allf)
    rules_by_cat: dict[str, set[str]] = defaultdict(set)
    for f in allf:
        rules_by_cat[f.category].add(f.rule or f.source)
    out.append("by category: " + "; ".join(f"{c} {cats[c]} findings in {len(rules_by_cat[c])} rules"
                                            for c in ("Mandatory", "Required", "Advisory", "unknown", "cppcheck") if cats[c]))
    out.append(f"Required+Mandatory: {cats['Required'] + cats['Mandatory']}; Advisory: {cats['Advisory']}")
    files = Counter(f.file for f in allf)
    out.append("by header: " + ", ".join(f"{k} {v}" for k, v in sorted(files.items())))
    return "\n".join(out)


def cppcheck_version() -> str:
    proc = subprocess.run(["cppcheck", "--version"], capture_output=True, text=True, check=False)
    return proc.stdout.strip().split()[-1] if proc.returncode == 0 and proc.stdout.strip() else "?"


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description="MISRA C:2012 findings of the generated C headers (cppcheck misra addon)")
    ap.add_argument("--headers", type=Path, default=cross.cbuild.HEADERS)
    ap.add_argument("--strategies", default=os.environ.get("CANSPEC_C_STRATEGIES", cross.DEFAULT_STRATEGIES))
    ap.add_argument("--deviations", type=Path, help="deviation record (Markdown); fail on any finding it does not cover")
    ap.add_argument("--no-fail", action="store_true", help="with --deviations: report, but exit 0 (a benchmark, not a gate)")
    ap.add_argument("--list", action="store_true", help="print every finding (file:line:col rule category)")
    ap.add_argument("-j", "--jobs", type=int, default=None)
    args = ap.parse_args(argv[1:])
    if shutil.which("cppcheck") is None:
        print("misra: cppcheck not installed (make setup)", file=sys.stderr)
        return 1
    try:
        by_config = analyse(args.headers, args.strategies, args.jobs)
    except (RuntimeError, ValueError, subprocess.TimeoutExpired) as exc:
        print(f"misra: {exc}", file=sys.stderr)
        return 1
    print(report(by_config))
    allf = unique(by_config)
    if args.list:
        for f in allf:
            print(f"{f.file}:{f.line}:{f.col}: {f.rule or '-'} {f.category} ({f.source})")
    if args.deviations is None:
        return 0
    devs, errors = load_record(args.deviations)
    uncovered, stale = check_record(allf, devs)
    for e in errors:
        print(f"misra: {e}", file=sys.stderr)
    for d in stale:
        print(f"misra: note: {args.deviations.name}:{d.line}: rule {d.rule} ({', '.join(d.where)}) has no finding any more")
    by_rule = Counter((f.rule or f.source, f.category) for f in uncovered)
    for (rule, cat), n in sorted(by_rule.items(), key=lambda x: (_rule_key(x[0][0]), x[0][0])):
        first = next(f for f in uncovered if (f.rule or f.source) == rule)
        print(f"misra: not in the record: {rule} ({cat}) x{n}, first at {first.file}:{first.line}:{first.col}", file=sys.stderr)
    print(f"misra: {len(allf) - len(uncovered)} findings covered by {args.deviations.name}, {len(uncovered)} not; {len(errors)} record errors")
    return 1 if (uncovered or errors) and not args.no_fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
