"""`canspec check [SPEC...]`: schema and semantic rules; exit 0 clean, 1 on errors."""

from __future__ import annotations

import argparse
import sys

from canspec.commands.common import compile_or_report, print_problems
from canspec.diff.history import changelog_problems
from canspec.targets import registry


def run(args: argparse.Namespace) -> int:
    known = registry()
    unknown = [n for n in args.target or [] if n not in known]
    if unknown:
        print(f"canspec check: unknown target {', '.join(unknown)} (known: {', '.join(known)})", file=sys.stderr)
        return 2
    specs = args.spec or [None]
    failed = False
    for spec in specs:
        compiled = compile_or_report(spec, strict=args.strict, targets=args.target)
        if compiled.spec is None:
            failed = True
            continue
        s = compiled.spec
        # The changelog's newest version must agree with the diff from its `previous` revision.
        history = changelog_problems(spec, s)
        print_problems(history)
        if any(p.severity == "error" or args.strict for p in history):
            failed = True
            continue
        if not args.quiet:
            counts = []
            if s.can is not None:
                counts.append(
                    f"{len(s.can.messages)} messages, {sum(len(m.data_signals) for m in s.can.messages)} signals, {len(s.can.value_tables)} value tables"
                )
            if s.json:
                counts.append(f"{sum(len(j.messages) for j in s.json)} JSON messages")
            warn = f", {len(compiled.warnings)} warning(s)" if compiled.warnings else ""
            print(f"{s.name} {s.version}: ok ({'; '.join(counts)}{warn})", file=sys.stderr)
    return 1 if failed else 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("check", help="validate a spec (schema + semantic rules)")
    p.add_argument("spec", nargs="*", help="spec bundles, directories or files (default: the shipped spec)")
    p.add_argument("--strict", action="store_true", help="treat warnings as errors")
    p.add_argument("-t", "--target", action="append", help="apply only this target's refusals (repeatable; default: every target's)")
    p.add_argument("-q", "--quiet", action="store_true", help="print problems only")
    p.set_defaults(func=run)
