"""Where the shipped spec, the spec schema and the templates live.

An installed wheel carries them under `canspec/_data/`; a source checkout (or `pip -e`)
reads them from the repository's top-level `spec/` and `templates/`.
"""

from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent
_BUNDLED = _PACKAGE / "_data"
_REPO = _PACKAGE.parent.parent


def _root(name: str) -> Path:
    bundled = _BUNDLED / name
    return bundled if bundled.is_dir() else _REPO / name


def spec_dir() -> Path:
    return _root("spec")


def templates_dir() -> Path:
    return _root("templates")


def default_spec() -> Path:
    return spec_dir() / "canspec.yaml"


def spec_schema_path(version: int) -> Path:
    return spec_dir() / "schema" / f"canspec-spec.v{version}.schema.json"
