"""`canspec targets`: list the output targets."""

from __future__ import annotations

import argparse

from canspec.targets import registry


def run(args: argparse.Namespace) -> int:
    for t in registry().values():
        print(f"{t.name:12} {t.directory:14} {t.description}")
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("targets", help="list the output targets")
    p.set_defaults(func=run)
