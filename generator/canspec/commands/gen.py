"""`canspec gen [SPEC] [-o DIR] [--target NAME...] [--node NAME] [--check] [--depfile FILE]`."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Iterable
from pathlib import Path

from canspec import depfile, gen_record
from canspec.commands.common import compile_or_report
from canspec.generation import GenerationError, generate
from canspec.ir.nodeview import for_node, node_names
from canspec.pipeline import Compiled
from canspec.render import writer
from canspec.render.formatters import version_notes
from canspec.targets import registry


def run(args: argparse.Namespace) -> int:
    known = registry()
    names = args.target or list(known)
    unknown = [n for n in names if n not in known]
    if unknown:
        print(f"canspec gen: unknown target {', '.join(unknown)} (known: {', '.join(known)})", file=sys.stderr)
        return 2
    out = Path(args.output)
    options = [f"targets={','.join(names)}", f"node={args.node}", f"strict={args.strict}"]
    if args.check and (count := gen_record.up_to_date(args.spec, out, options)) is not None:  # unchanged since the last gen: no compile
        print(f"canspec gen --check: {count} file(s) up to date", file=sys.stderr)
        return 0
    chosen = None if set(names) == set(known) else names  # only these targets' refusals (None: all, as `import` caches the spec)
    compiled = compile_or_report(args.spec, strict=args.strict, quiet_warnings=True, targets=chosen, cached=True)
    if compiled.spec is None:
        print("canspec gen: nothing written (fix the errors above)", file=sys.stderr)
        return 1
    spec = compiled.spec
    if args.node is not None:
        if args.node not in node_names(spec):
            print(
                f"canspec gen: --node {args.node}: no such node (nodes: {', '.join(node_names(spec)) or 'none: the spec has no CAN protocol'})", file=sys.stderr
            )
            return 2
        spec = for_node(spec, args.node)
    try:
        outputs = generate(spec, names)
    except GenerationError as exc:
        print(f"canspec gen: {exc}; nothing written", file=sys.stderr)
        return 1
    for note in version_notes(f for name in names for f in known[name].formatters):  # why output may differ from the committed files
        print(f"canspec gen: warning: {note}", file=sys.stderr)
    if out.exists() and not out.is_dir():
        print(f"canspec gen: {out} exists and is not a directory", file=sys.stderr)
        return 1
    plan = writer.plan(out, outputs)
    for note in plan.notes:
        print(f"canspec gen: warning: {note}", file=sys.stderr)
    if (clash := _spec_file_in(out, plan, compiled.files)) is not None:
        verb = "remove" if clash in plan.remove else "overwrite"
        print(f"canspec gen: {out / clash} is a file the spec reads, and this run would {verb} it; choose an output directory apart from the spec's "
              "files; nothing written", file=sys.stderr)
        return 1
    return _report_check(args, out, plan, compiled, options) if args.check else _write(args, out, plan, compiled, options)


def _report_check(args: argparse.Namespace, out: Path, plan: writer.Plan, compiled: Compiled, options: list[str]) -> int:
    """`--check`: list what a run would change; exit 1 if anything."""
    for rel in plan.write:
        print(f"{'stale' if (out / rel).exists() else 'missing'}: {out / rel}")
    for rel in plan.remove:
        print(f"extra: {out / rel}")
    if plan.stale:
        print(f"canspec gen --check: {len(plan.stale)} file(s) out of date; run `canspec gen`", file=sys.stderr)
        return 1
    gen_record.write(args.spec, out, options, compiled.files, plan.unchanged)
    print(f"canspec gen --check: {len(plan.unchanged)} file(s) up to date", file=sys.stderr)
    return 0


def _write(args: argparse.Namespace, out: Path, plan: writer.Plan, compiled: Compiled, options: list[str]) -> int:
    try:
        if args.depfile is not None:  # first: a depfile that cannot be written stops the run before any output changes
            depfile.write(Path(args.depfile), out / writer.MANIFEST, compiled.files)
        writer.clean_stale_temporaries(out)
        writer.apply(out, plan)
        if args.depfile is not None:
            depfile.touch(out / writer.MANIFEST)
        gen_record.write(args.spec, out, options, compiled.files, [*plan.unchanged, *plan.write])
    except OSError as exc:
        print(f"canspec gen: cannot write {exc.filename or out}: {exc.strerror}; previous files left unchanged", file=sys.stderr)
        return 1
    if not args.quiet:
        print(f"canspec gen: {len(plan.write)} written, {len(plan.unchanged)} unchanged, {len(plan.remove)} removed in {out}", file=sys.stderr)
    return 0


def _spec_file_in(out: Path, plan: writer.Plan, read: Iterable[Path]) -> str | None:
    """The output (relative to `out`) this run would write or remove that is one of the files the
    spec's compile read: generating must never replace its own input."""
    inputs = {os.path.realpath(p) for p in read}
    return next((rel for rel in [*plan.write, *plan.remove] if os.path.realpath(out / rel) in inputs), None)


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("gen", help="generate targets from a spec")
    p.add_argument("spec", nargs="?", default=None, help="spec bundle, directory or file (default: the shipped spec)")
    p.add_argument("-o", "--output", default="generated", help="output directory (default: ./generated)")
    p.add_argument("-t", "--target", action="append", help="target to generate (repeatable; default: all)")
    p.add_argument("--node", metavar="NAME", help="only the messages this node sends or receives (an ECU's headers: --target c --node NAME)")
    p.add_argument("--check", action="store_true", help="write nothing; list stale or missing files and exit 1 if any")
    p.add_argument(
        "--depfile", metavar="FILE", help="also write a Makefile rule: the output's manifest depends on every file the spec read (for CMake/Ninja/Make)"
    )
    p.add_argument("--strict", action="store_true", help="treat spec warnings as errors")
    p.add_argument("-q", "--quiet", action="store_true")
    p.set_defaults(func=run)
