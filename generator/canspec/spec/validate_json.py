"""The rules of a JSON protocol document (its types, shared fields, messages and replies) and of
the change record; validate.py runs them after the CAN rules."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from typing import Any

from canspec.spec.finite import finite
from canspec.spec.problems import Problem, error
from canspec.spec.resolve import Resolved
from canspec.spec.yamlsource import LocDict


def version_key(text: str) -> tuple[int, ...]:
    return tuple(int(p) for p in str(text).split("."))


def json_rules(doc: Any) -> Iterator[Problem]:
    data = doc.data
    types = data["types"]
    shared = data.get("fields", LocDict())
    parties = {p["name"] for p in data["parties"]}
    for tname, tdef in types.items():
        for key in ("min", "max"):
            if key in tdef and not finite(tdef[key]):
                yield error(f"type {tname!r}: {key} must be a finite number within the range of a double", tdef.loc_of(key), None, "nonfinite")
    for fname, fdef in shared.items():
        if fdef["type"] not in types:
            yield error(f"field {fname!r} has unknown type {fdef['type']!r}", fdef.loc_of("type"), f"known types: {', '.join(types)}", "json-unknown-type")
    by_name: dict[str, Any] = {}
    for msg in data["messages"]:
        if msg["name"] in by_name:
            yield error(f"JSON message {msg['name']!r} is defined twice", msg.loc_of("name"), None, "json-duplicate-message")
        by_name[msg["name"]] = msg
        for key in ("from", "to"):
            if msg[key] not in parties:
                yield error(
                    f"message {msg['name']!r}: `{key}` {msg[key]!r} is not a party", msg.loc_of(key), f"parties: {', '.join(sorted(parties))}",
                    "json-unknown-party")
        keys: dict[str, Any] = {}
        fields = msg["fields"]
        for i, ref in enumerate(fields):
            if isinstance(ref, str):
                if ref not in shared:
                    yield error(
                        f"message {msg['name']!r} refers to unknown field {ref!r}", fields.loc_of(i), f"shared fields: {', '.join(shared)}",
                        "json-unknown-field")
                    continue
                fdef, default_key = shared[ref], ref
            else:
                fdef, default_key = ref, ref["name"]
                if fdef["type"] not in types:
                    yield error(
                        f"field {default_key!r} has unknown type {fdef['type']!r}", fdef.loc_of("type"), f"known types: {', '.join(types)}", "json-unknown-type"
                    )
            key = fdef.get("json_name", default_key)
            if key in keys:
                yield error(f"message {msg['name']!r} has JSON key {key!r} twice", fields.loc_of(i), None, "json-duplicate-field")
            keys[key] = fdef
        if ("cmd" in msg) != ("role" in msg):
            yield error(f"message {msg['name']!r}: a command message needs both `cmd` and `role`", msg.loc, None, "json-command")
    for msg in data["messages"]:
        if msg.get("role") == "reply":
            req = by_name.get(msg.get("reply_to", ""))
            if req is None or req.get("role") != "request":
                yield error(
                    f"reply {msg['name']!r} must name its request in `reply_to`", msg.loc_of("reply_to") if "reply_to" in msg else msg.loc,
                    "reply_to: <a message with role: request>", "json-reply-to")
            elif req.get("cmd") != msg.get("cmd"):
                yield error(
                    f"reply {msg['name']!r} (cmd {msg.get('cmd')}) answers {req['name']!r} (cmd {req.get('cmd')})", msg.loc_of("cmd"),
                    "a reply carries its request's cmd", "json-reply-to")


def check_changelog(res: Resolved) -> Iterator[Problem]:
    if res.changelog is None:
        return
    versions = res.changelog.data["versions"]
    for prev, cur in itertools.pairwise(versions):
        if version_key(cur["version"]) <= version_key(prev["version"]):
            yield error(
                f"changelog version {cur['version']} does not come after {prev['version']}", cur.loc_of("version"), "list versions oldest first",
                "changelog-order")
    if res.can is not None:
        protocol_version = str(res.can.doc.data["protocol"]["version"])
        newest = str(versions[-1]["version"])
        if newest != protocol_version:
            yield error(
                f"the changelog ends at {newest} but the protocol is version {protocol_version}", versions.loc_of(len(versions) - 1),
                "add the protocol's current version to the changelog", "changelog-current")
