"""Subcommands of `canspec`; each module defines `register(subparsers)`. Internal: the
command line is their interface."""
