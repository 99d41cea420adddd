"""Subcommands of `canspec`; each module defines `register(subparsers)`."""
