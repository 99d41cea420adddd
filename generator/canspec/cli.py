"""The `canspec` command. Subcommands live in canspec/commands/, one module each with
`register(subparsers)`; a bad spec or bad input ends in a clear message and exit 1, never
a traceback."""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from canspec import __version__, commands


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="canspec", description="Generate DBC, C, Python, Rust, JSON Schema and docs from one protocol spec.")
    parser.add_argument("--version", action="version", version=f"canspec {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda i: i.name):
        module = importlib.import_module(f"{commands.__name__}.{info.name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        print("canspec: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # a bug in canspec: one clear line, never a traceback
        print(f"canspec: internal error: {type(exc).__name__}: {exc} (please report, with the command and the spec)", file=sys.stderr)
        return 3
