"""Load a spec (a bundle file, a directory holding `canspec.yaml`, or one spec file) into
schema-checked documents. Every problem carries file:line:col."""

from __future__ import annotations

import hashlib
import json
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from canspec import resources
from canspec.spec import fastschema
from canspec.spec.problems import Loc, Problem, SpecError, error
from canspec.spec.yamlsource import LocDict, LocList, load_yaml

if TYPE_CHECKING:  # jsonschema itself only for a document the fast check rejects (its import: 0.06 s of every compile)
    import jsonschema

SUPPORTED_SCHEMA_VERSIONS = (1,)
KINDS = ("bundle", "can_protocol", "value_tables", "json_protocol", "changelog")


@dataclass
class Document:
    path: Path
    name: str  # as shown in messages: relative to the working directory when possible
    kind: str
    data: LocDict


@dataclass
class LoadedSpec:
    root: Path
    documents: list[Document] = field(default_factory=list)
    sha256: str = ""
    bundle_name: str | None = None
    files: list[Path] = field(default_factory=list)  # every file a compile reads, or looks for: the spec files, schemas, ERRATA.md

    def of_kind(self, kind: str) -> list[Document]:
        return [d for d in self.documents if d.kind == kind]

    @property
    def errata_path(self) -> Path:
        return self.root / "ERRATA.md"


def display_name(path: Path) -> str:
    try:  # abspath, not resolve: a symlink is shown as the user named it
        return str(Path(os.path.abspath(path)).relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


_UNESCAPED_DOLLAR = re.compile(r"(?<!\\)\$")


def _ecma_pattern(validator: Any, pattern: str, instance: Any, schema: Any) -> Iterator[jsonschema.ValidationError]:
    """`pattern` as JSON Schema means it (ECMA-262): `$` is the end of the text. Python's `$` also matches
    before a final newline, so jsonschema would take the name "brake\\n" as an identifier."""
    if validator.is_type(instance, "string") and not re.search(_UNESCAPED_DOLLAR.sub(r"\\Z", pattern), instance):
        import jsonschema

        yield jsonschema.ValidationError(f"{instance!r} does not match {pattern!r}")


@cache
def _validator(version: int) -> jsonschema.protocols.Validator:
    import jsonschema

    schema = json.loads(resources.spec_schema_path(version).read_text(encoding="utf-8"))
    cls = jsonschema.validators.extend(jsonschema.validators.validator_for(schema), {"pattern": _ecma_pattern})
    return cls(schema)


def _walk(data: Any, path: Any) -> tuple[Any, Any]:
    """Container and key of the deepest element of `path` that exists."""
    container, key = data, None
    for step in path:
        try:
            nxt = container[step]
        except (KeyError, IndexError, TypeError):
            return container, None
        if not isinstance(nxt, (LocDict, LocList)):
            return container, step
        container, key = nxt, None
    return container, key


def _kind_of(value: Any) -> str:
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, bool):
        return f"boolean {value!r}"
    if isinstance(value, str):
        return f"text {value!r}"
    if value is None:
        return "nothing (null)"
    return f"number {value}"


def _describe(err: jsonschema.ValidationError) -> tuple[str, str | None]:
    """A one-line message and hint for a schema error, in the spec author's terms."""
    where = ".".join(str(p) for p in err.absolute_path) or "file"
    v = err.validator
    if v == "additionalProperties":
        extra = sorted(set(err.instance) - set(err.schema.get("properties", {})), key=str)
        allowed = ", ".join(sorted(err.schema.get("properties", {})))
        return f"unknown key {', '.join(repr(e) for e in extra)} in {where}", f"allowed keys: {allowed}"
    if v == "required":
        return f"{where}: {err.message.replace('is a required property', 'is required')}", "add the missing key"
    if v == "type":
        return f"{where}: expected {err.validator_value}, got {_kind_of(err.instance)}", None
    if v in ("enum", "const"):
        options = err.validator_value if v == "enum" else [err.validator_value]
        return f"{where}: {err.instance!r} is not one of {', '.join(map(repr, options))}", None
    if v == "pattern":
        return f"{where}: {err.instance!r} does not match {err.validator_value}", (
            "identifiers are lower_snake_case ASCII" if "a-z][a-z0-9_]" in str(err.validator_value) else None
        )
    if v in ("minItems", "maxItems"):
        bound = "at least" if v == "minItems" else "at most"
        return f"{where}: expected {bound} {err.validator_value} item{'s' if err.validator_value != 1 else ''}, got {len(err.instance)}", None
    if v in ("minimum", "maximum"):
        return f"{where}: {err.instance!r} is out of range ({v} {err.validator_value})", None
    return f"{where}: {err.message}", None


def _specific(err: jsonschema.ValidationError) -> jsonschema.ValidationError:
    """The most specific error inside a combinator. Of oneOf/anyOf alternatives, those of another
    type than the value are left out: a list given for "a string or a [name, 中文] list" is told
    what is wrong with it as a list, not that it is not a string."""
    import jsonschema

    context = list(err.context)
    if err.validator in ("oneOf", "anyOf"):
        context = [e for e in context if not (e.validator == "type" and len(e.relative_schema_path) == 2)] or context
    return jsonschema.exceptions.best_match(context) or err


def schema_problems(data: LocDict, name: str) -> list[Problem]:
    version = data.get("schema_version")
    top = Loc(name, 1, 1)
    if "schema_version" not in data:
        return [error("missing `schema_version`", data.loc, "start the file with `schema_version: 1` (see spec/schema/CHANGELOG.md)", "schema-version")]
    if not isinstance(version, int) or isinstance(version, bool):
        return [error(f"`schema_version` must be an integer, got {_kind_of(version)}", data.loc_of("schema_version"), None, "schema-version")]
    if version not in SUPPORTED_SCHEMA_VERSIONS:
        newest = max(SUPPORTED_SCHEMA_VERSIONS)
        hint = (
            "this file was written for a newer canspec; upgrade canspec"
            if version > newest
            else f"migrate the file to schema_version {newest} as described in spec/schema/CHANGELOG.md"
        )
        return [error(
            f"unsupported schema_version {version} (this canspec reads {', '.join(map(str, SUPPORTED_SCHEMA_VERSIONS))})", data.loc_of("schema_version"),
            hint, "schema-version")]
    fast = fastschema.checker(resources.spec_schema_path(version))
    if fast is not None and fast(data):
        return []
    problems = []
    errors = sorted(_validator(version).iter_errors(data), key=lambda e: (list(map(str, e.absolute_path)), str(e.validator)))
    seen = set()
    for err in errors:
        # Inside if/then and oneOf the most specific error is the useful one.
        if err.validator in ("if", "allOf", "oneOf", "anyOf") and err.context:
            err = _specific(err)
        message, hint = _describe(err)
        container, key = _walk(data, err.absolute_path)
        loc = (container.loc_of(key) if key is not None else container.loc) if isinstance(container, (LocDict, LocList)) else top
        if err.validator == "additionalProperties" and key is None and isinstance(container, LocDict):
            # Point at the unknown key itself, not at the mapping holding it.
            extra = [k for k in container if k not in err.schema.get("properties", {})]
            loc = container.key_locs.get(extra[0], loc) if extra else loc
        if (loc, message) in seen:
            continue
        seen.add((loc, message))
        problems.append(error(message, loc, hint, "schema"))
    return problems


def _load_document(path: Path) -> Document:
    name = display_name(path)
    data = load_yaml(path, name)
    if not isinstance(data, LocDict):
        raise SpecError([error(f"expected a mapping at the top of the file, got {_kind_of(data)}", getattr(data, "loc", Loc(name, 1, 1)),
                               "a spec file starts with `schema_version:` and `kind:`")])
    problems = schema_problems(data, name)
    if problems:
        raise SpecError(problems)
    return Document(path, name, data["kind"], data)


def load(spec: Path | str | None = None) -> LoadedSpec:
    """Load the spec at `spec` (default: the shipped one). Raises SpecError."""
    path = Path(spec) if spec is not None else resources.default_spec()
    try:
        return _load(path)
    except OSError as exc:  # e.g. a directory on the way that we may not search
        where = Path(exc.filename) if exc.filename else path
        raise SpecError([error(f"cannot access: {exc.strerror}", Loc(display_name(where)), "check the path and its permissions")]) from None


def _load(path: Path) -> LoadedSpec:
    if path.is_dir():
        manifest = path / "canspec.yaml"
        if not manifest.is_file():
            raise SpecError([error("directory has no canspec.yaml bundle file", Loc(display_name(path)),
                                   "pass a spec file, or add canspec.yaml listing the spec files")])
        path = manifest
    elif not path.exists():
        raise SpecError([error("no such file or directory", Loc(display_name(path)), "check the spec path")])
    first = _load_document(path)
    loaded = LoadedSpec(root=path.parent)
    if first.kind == "bundle":
        loaded.bundle_name = first.data.get("name")
        problems: list[Problem] = []
        files = first.data["files"]
        listed: dict[Path, int] = {}
        for i, rel in enumerate(files):
            entry = path.parent / rel
            if not entry.is_file():
                # Point at the bundle's entry: that is the line to fix.
                what = "is a directory" if entry.is_dir() else "is not a regular file" if entry.exists() else "does not exist"
                problems.append(error(f"bundle file {rel!r} {what}", files.loc_of(i), f"paths are relative to {display_name(path.parent) or '.'}/"))
                continue
            first_at = listed.setdefault(entry.resolve(), i)
            if first_at != i:
                problems.append(error(f"bundle file {rel!r} is listed twice (also as entry {first_at + 1})", files.loc_of(i), "list each file once"))
                continue
            try:
                doc = _load_document(path.parent / rel)
            except SpecError as exc:
                problems.extend(exc.problems)
                continue
            if doc.kind == "bundle":
                problems.append(error("a bundle cannot include another bundle", files.loc_of(i), "list the other bundle's files instead", "nested-bundle"))
            loaded.documents.append(doc)
        if problems:
            raise SpecError(problems)
        hashed = [path, *(d.path for d in loaded.documents)]
    else:
        loaded.documents.append(first)
        hashed = [path]
    digest = hashlib.sha256()
    for p in hashed:
        digest.update(p.relative_to(path.parent).as_posix().encode() if p.is_relative_to(path.parent) else p.name.encode())
        digest.update(b"\0")
        digest.update(p.read_bytes().replace(b"\r\n", b"\n"))
        digest.update(b"\0")
    loaded.sha256 = digest.hexdigest()
    loaded.files = [*hashed, *map(resources.spec_schema_path, SUPPORTED_SCHEMA_VERSIONS), loaded.errata_path]
    return loaded
