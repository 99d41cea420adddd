"""`canspec diff OLD NEW [--format text|markdown|json|html] [--fail-on wire|source|compatible|any]`.

Every change is classed, strictest first:
  wire        an old receiver would decode different values (layout, factor/offset, signedness,
              unit, ID, DLC, enum meaning, checksum/counter role, removed message or signal)
  source      the wire is the same but generated identifiers change (renames)
  compatible  new message, new signal in formerly reserved bits, new enum value, widened range,
              cycle time, sender/receivers
  docs        names as printed, descriptions

--format html writes the revision report to publish with a release: one self-contained page with
the changes, the suggested bump and the new revision's declared change record beside them.

Exit status: 0 no failing change, 1 a change at or above --fail-on, 2 an input that cannot be
read (the message says which and why)."""

from __future__ import annotations

import argparse
import sys

from canspec.commands.common import add_encoding_argument
from canspec.diff.classes import FAIL_ON
from canspec.diff.compare import compare
from canspec.diff.inputs import InputError, is_database, load_model
from canspec.diff.report import FORMATS as TEXT_FORMATS
from canspec.diff.report_html import html

FORMATS = {**TEXT_FORMATS, "html": html}


def run(args: argparse.Namespace) -> int:
    try:
        comments = is_database(args.old) and is_database(args.new)  # a spec's descriptions are not its DBC's comments
        old = load_model(args.old, comments, args.encoding)
        new = load_model(args.new, comments, args.encoding)
    except InputError as exc:
        print(f"canspec diff: {exc}", file=sys.stderr)
        return 2
    changes = compare(old, new)
    sys.stdout.write(FORMATS[args.format](old, new, changes))
    if args.fail_on:
        failing = [ch for ch in changes if ch.cls in FAIL_ON[args.fail_on]]
        if failing:
            print(f"canspec diff: {len(failing)} change(s) at or above --fail-on {args.fail_on}", file=sys.stderr)
            return 1
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("diff", help="semantic diff of two protocol revisions (specs or DBC/ARXML/KCD/SYM files), classed wire/source/compatible/docs",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("old", help="old revision: spec bundle, directory or file, or a .dbc, .arxml, .kcd or .sym file")
    p.add_argument("new", help="new revision: spec bundle, directory or file, or a .dbc, .arxml, .kcd or .sym file")
    p.add_argument("--format", choices=sorted(FORMATS), default="text", help="output format (default: text)")
    p.add_argument("--fail-on", choices=list(FAIL_ON), help="exit 1 if any change is of this class or stricter (any: every change)")
    add_encoding_argument(p)  # of both revisions' DBC files
    p.set_defaults(func=run)
