"""Several sources into one spec (files of one bus, or several buses' messages on one): messages,
nodes and value tables joined; a message ID or name twice, or a bus setting that differs, is an
error naming both places."""

from __future__ import annotations

from typing import Any

from canspec.importer.dbctext import DbcError

BUS_KEYS = ("bitrate", "data_bitrate")


def merge(specs: list[tuple[str, dict[str, Any]]]) -> dict[str, Any]:
    first_source, out = specs[0]
    out = {**out, "nodes": list(out["nodes"]), "messages": list(out["messages"]), "value_tables": dict(out.get("value_tables", {}))}
    where_id = {(m["id"], m.get("extended")): first_source for m in out["messages"]}
    where_name = {m["name"]: first_source for m in out["messages"]}
    for source, spec in specs[1:]:
        for key in BUS_KEYS:
            if spec["bus"].get(key) != out["bus"].get(key):
                raise DbcError(f"{source}: bus {key} {spec['bus'].get(key)} differs from {out['bus'].get(key)} in {first_source}: "
                               "one spec describes one bus (import the buses separately)")
        for msg in spec["messages"]:
            key = (msg["id"], msg.get("extended"))
            for seen, what in ((where_id.get(key), f"ID 0x{msg['id']:X}"), (where_name.get(msg["name"]), f"name {msg['name']}")):
                if seen is not None:
                    raise DbcError(f"{source}: message {msg.get('dbc_name', msg['name'])} has the {what} of a message in {seen}: "
                                   "rename or renumber one of them")
            where_id[key], where_name[msg["name"]] = source, source
            out["messages"].append(msg)
        known = {n["name"] for n in out["nodes"]}
        out["nodes"] += [n for n in spec["nodes"] if n["name"] not in known]
        kept = out.setdefault("dbc_attributes", {})
        for name, d in spec.get("dbc_attributes", {}).items():
            if name in kept and kept[name] != d:
                raise DbcError(f"{source}: attribute {name} is defined otherwise than in {first_source}: {d} against {kept[name]}")
            kept[name] = d
        for name, table in spec.get("value_tables", {}).items():
            if name in out["value_tables"] and out["value_tables"][name] != table:
                raise DbcError(f"{source}: value table {name} differs from the one in {first_source}")
            out["value_tables"][name] = table
    for key in ("value_tables", "dbc_attributes"):
        if not out.get(key, True):
            del out[key]
    out["messages"].sort(key=lambda m: (m["id"], m["name"]))
    return out
