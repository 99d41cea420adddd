"""The `canspec` command. Subcommands live in canspec/commands/, one module each, named as the
command, with `register(subparsers)`; a bad spec or bad input ends in a clear message and exit 1,
never a traceback."""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from canspec import __version__, commands
from canspec.commands.extras import missing_module_hint


class _Version(argparse.Action):
    """`--version`: canspec's version and the spec schema versions it reads (the loader is
    imported only here: it costs 0.1 s at every start)."""

    def __call__(self, parser, namespace, values, option_string=None):  # type: ignore[no-untyped-def]
        from canspec.spec.loader import SUPPORTED_SCHEMA_VERSIONS

        print(f"canspec {__version__} (reads spec schema_version {', '.join(map(str, SUPPORTED_SCHEMA_VERSIONS))})")
        parser.exit()


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every command, or with `command` of that one only: the command modules'
    imports cost 0.2 s, paid at every start otherwise. Help and usage errors get every command."""
    parser = argparse.ArgumentParser(prog="canspec", description="Generate DBC, C, Python, Rust, JSON Schema and docs from one protocol spec.")
    parser.add_argument("--version", action=_Version, nargs=0, help="print the version and the spec schema versions it reads, then exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    names = sorted(info.name for info in pkgutil.iter_modules(commands.__path__))
    for name in [command] if command in names else names:
        register = getattr(importlib.import_module(f"{commands.__name__}.{name}"), "register", None)
        if register is not None:
            register(sub)
    if command is not None and command not in sub.choices:  # a helper module's name, or a typo
        return build_parser()
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    parser = build_parser(argv[0] if argv and not argv[0].startswith("-") else None)
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        print("canspec: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # a bug in canspec: one clear line, never a traceback
        if (hint := missing_module_hint(exc)) is not None:  # an optional extra not installed
            print(f"canspec {args.command}: {hint}", file=sys.stderr)
            return 2
        print(f"canspec: internal error: {type(exc).__name__}: {exc} (please report, with the command and the spec)", file=sys.stderr)
        return 3
