"""Shared layouts and the change record of a drawn spec (strategy.py): a layout's fields, a message
that uses it with fields removed, overridden or added, and a changelog file. A mixin of
strategy.Builder, which supplies the chooser (`p`, `pick`, `ch`, ...) and the field draws."""

from __future__ import annotations

from decimal import Decimal
from typing import Any

from anyspec.pools import SIG_WORDS, UNITS, _Names, frame_bits, raw_range
from anyspec.yamltext import Hex, block


class LayoutDraws:
    def layout(self) -> tuple[str, list[dict[str, Any]], int, int]:
        name = self.pick(("command", "sensor_block", "status_block", "common"))
        dlc = self.pick((8, 4, 6, 2))
        sigs = self.signals(dlc)
        users = 2 + self.ch.integer(0, 1)
        return name, sigs, dlc, users

    def layout_user(self, m: dict[str, Any], lname: str, lay: list[dict[str, Any]], dlc: int) -> dict[str, Any]:
        if dlc != 8 or self.p(0.2):
            m["dlc"] = dlc
        m["layout"] = lname
        by_name = {s.get("name", f"reserved_{s['start']}"): s for s in lay}
        final_names = _Names(list(by_name))
        removed: list[str] = []
        if len(lay) > 1 and self.p(0.3):
            victim = self.pick(list(by_name))
            removed.append(victim)
        overrides = self.layout_overrides(by_name, final_names, removed)
        occ: set[int] = set()
        has_counter = has_checksum = False
        for s in lay:
            key = s.get("name", f"reserved_{s['start']}")
            if key in removed:
                continue
            occ |= frame_bits(s["start"], s["len"], s.get("byte_order", self.order))
            has_counter |= s.get("role") == "counter"
            has_checksum |= s.get("role") == "checksum"
        adds: list[dict[str, Any]] = []
        if self.p(0.4):
            names = _Names([*by_name, *(o["name"] for o in overrides.values() if "name" in o)])
            adds = self.signals(dlc, occ, names, counter=not has_counter, checksum=not has_checksum, first_needed=False)
        if overrides:
            m["override"] = overrides
        if removed:
            m["remove"] = removed
        if adds:
            m["add"] = adds
        return m

    def layout_overrides(self, by_name: dict[str, dict[str, Any]], final_names: _Names, removed: list[str]) -> dict[str, Any]:
        """Up to two of the layout's fields changed for this message: a Chinese name, a description, a
        unit, a new name or new scaling."""
        overrides: dict[str, Any] = {}
        for _ in range(self.ch.integer(0, 2)):
            target = self.pick(list(by_name))
            sig = by_name[target]
            if target in removed or target in overrides or sig.get("role") == "reserved":
                continue
            what = self.pick(("zh", "desc", "unit", "name", "scaling"))
            if what == "zh":
                overrides[target] = {"zh": self.zh()}
            elif what == "desc":
                overrides[target] = {"desc": self.text()}
            elif what == "unit" and sig.get("role", "data") == "data":
                overrides[target] = {"unit": self.pick(UNITS)}
            elif what == "name":
                new = self.ident(SIG_WORDS, final_names, 0.1)
                overrides[target] = {"name": new}
            elif what == "scaling" and sig.get("role", "data") == "data" and "values" not in sig and "special" not in sig and not sig.get("float"):
                sc = self.scaling(sig["len"], bool(sig.get("signed")))
                sc.pop("_raw", None)
                sc.setdefault("factor", Decimal(1))
                sc.setdefault("offset", Decimal(0))
                if "range" in sig and "range" not in sc:
                    lo, hi = raw_range(sig["len"], bool(sig.get("signed")))
                    a, b = sorted((lo * sc["factor"] + sc["offset"], hi * sc["factor"] + sc["offset"]))
                    sc["range"] = [a, b]
                overrides[target] = sc
        return overrides

    # --- change record
    def changelog(self, protocol: str, version: str, ids: list[int]) -> str:
        major, minor, patch = (int(x) for x in version.split("."))
        versions = []
        older = []
        if patch > 0 and self.p(0.6):
            older.append(f"{major}.{minor}.{patch - 1}")
        if (minor > 0 or major > 0) and self.p(0.4):
            older.insert(0, f"{major}.{minor - 1}.0" if minor > 0 else f"{major - 1}.9.0")
        for v in [*older, version]:
            entry: dict[str, Any] = {"version": v}
            if self.p(0.5):
                entry["date"] = f"20{self.ch.integer(10, 29)}-0{self.ch.integer(1, 9)}-1{self.ch.integer(0, 9)}"
            if self.p(0.3):
                entry["authors"] = [self.zh()]
            items = []
            for _ in range(1 + self.ch.integer(0, 1)):
                item: dict[str, Any] = {"zh": self.zh()}
                if self.p(0.6):
                    item["en"] = self.text()
                if ids and self.p(0.3):
                    item["ids"] = [Hex(self.pick(ids))]
                items.append(item)
            entry["items"] = items
            versions.append(entry)
        doc = {"schema_version": 1, "kind": "changelog", "protocol": protocol, "versions": versions}
        return block(doc, 0, 2)
