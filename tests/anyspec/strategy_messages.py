"""A drawn message's identity and frame (strategy.py's Builder mixes these in): its frame ID,
standard or extended, J1939 or not; its name, sender and receivers; CAN FD lengths and bit-rate
switching; the byte order of its fields."""

from __future__ import annotations

from typing import Any

from anyspec.pools import BIG, CLASSIC_DLCS, FD_DLCS, LITTLE, MSG_SUFFIX, MSG_WORDS
from anyspec.yamltext import Hex


class MessageDraws:
    """Needs the Builder's choosers (`ch`, `p`, `pick`, `feature`, `ident`, `zh`) and its field
    draws (FieldDraws, LayoutDraws)."""

    def frame_id(self, sender: dict[str, Any] | None, extended: bool) -> tuple[int, dict[str, Any] | None]:
        if not extended:
            fid = self.ch.integer(0, 0x7FF)
            while fid in self.ids:
                fid = (fid + 1) & 0x7FF
            self.ids.add(fid)
            return fid, None
        if not self.j1939:
            fid = self.ch.integer(0, 0x7FF) if self.p(0.1) else self.ch.integer(0, 0x1FFFFFFF)
            while fid in self.ids:
                fid = (fid + 1) & 0x1FFFFFFF
            self.ids.add(fid)
            return fid, None
        prio = self.pick((6, 3, 7, 0, 1, 2, 4, 5))
        edp = 1 if self.p(0.1) else 0
        dp = 1 if self.p(0.2) else 0
        pf = self.ch.integer(0, 255)
        ps = self.ch.integer(0, 255)
        sa = int(sender["sa"]) if sender is not None else self.ch.integer(0, 255)

        def compose() -> int:
            return (prio << 26) | (edp << 25) | (dp << 24) | (pf << 16) | (ps << 8) | sa

        while compose() in self.ids:
            ps = (ps + 1) % 256
            if ps == 0:
                pf = (pf + 1) % 256
        fid = compose()
        self.ids.add(fid)
        decl: dict[str, Any] = {"priority": prio}
        if edp or self.p(0.2):
            decl["edp"] = edp
        if dp or self.p(0.2):
            decl["dp"] = dp
        decl.update({"pf": Hex(pf), "ps": Hex(ps), "sa": Hex(sa)})
        return fid, decl

    def message(self, nodes: list[dict[str, Any]], layout: tuple[str, list[dict[str, Any]], int] | None = None) -> dict[str, Any]:
        m: dict[str, Any] = {"name": self.ident(MSG_WORDS, self.msg_names, 0.08, MSG_SUFFIX)}
        if self.p(0.1):  # a C-only name, reserved like a message name so it meets no other
            m["c_name"] = self.msg_names.take(f"{m['name']}_c")
        if self.p(0.3):
            m["title"] = self.text()
        if self.p(0.4):
            m["zh"] = self.zh()
        if self.p(0.15):
            m["desc"] = self.text()
        self.identity(m, nodes)
        if layout is not None:
            return self.layout_user(m, *layout)
        fd = self.p(0.2)
        dlc = self.pick(FD_DLCS if fd else CLASSIC_DLCS)
        if dlc != 8 or self.p(0.2):
            m["dlc"] = dlc
        if fd:
            self.fd_frame(m)
        if dlc == 0 or self.p(0.03):
            if dlc > 0 or not self.feature("empty_signals", 0.6):
                m["layout_undefined"] = True
            m["signals"] = []
            return m
        mf = None
        if self.p(0.15):  # a multiplexed message (strategy_mux)
            from anyspec import strategy_mux

            sigs = strategy_mux.signals(self, dlc)
        elif 2 <= dlc <= 8 and self.multiframes < 2 and self.p(0.12):
            self.multiframes += 1
            sigs, mf = self.multiframe_signals(dlc)
        else:
            sigs = self.signals(dlc)
        if len(sigs) > 1 and self.p(0.2):
            k = self.ch.integer(1, len(sigs) - 1)
            sigs = sigs[k:] + sigs[:k]
        m["signals"] = sigs
        if mf is not None:
            m["multiframe"] = mf
        return m

    def identity(self, m: dict[str, Any], nodes: list[dict[str, Any]]) -> None:
        """The message's ID format, ID, sender, receivers and cycle."""
        extended = self.bus["id_format"] == "extended"
        if not self.j1939 and self.p(0.2):
            extended = self.p(0.5)
            m["extended"] = extended
        sender_all = self.p(0.05)
        sender = None if sender_all else nodes[self.ch.integer(0, len(nodes) - 1)]
        if self.j1939 and sender is not None and "sa" not in sender:
            sender = None
        fid, decl = self.frame_id(sender, extended)
        m["id"] = Hex(fid)
        if decl is not None and not self.feature("j1939_derived", 0.5):
            m["j1939"] = decl
        m["sender"] = "ALL" if sender is None else sender["name"]
        others = [n["name"] for n in nodes if sender is None or n["name"] != sender["name"]]
        if self.p(0.3):
            m["receivers"] = "ALL"
        elif not others or self.p(0.05):
            m["receivers"] = []
        else:
            m["receivers"] = others[: 1 + self.ch.integer(0, len(others) - 1)]
        if self.feature("event_driven", 0.2):
            if self.p(0.5):
                m["cycle_ms"] = 0
        else:
            m["cycle_ms"] = self.pick((20, 100, 10, 50, 1000, 1, 10000, 500)) if not self.p(0.2) else self.ch.integer(1, 10000)

    def fd_frame(self, m: dict[str, Any]) -> None:
        """`fd: true`, and `brs` where it is not the default (switching when the bus gives a data bit rate)."""
        m["fd"] = True
        if "data_bitrate" in self.bus:
            if self.p(0.3):
                m["brs"] = False
            elif self.p(0.1):
                m["brs"] = True
        elif self.p(0.2):
            m["brs"] = False

    # --- signals
    def field_order(self) -> str:
        """A field's byte order: mostly the bus default, else the other (both orders mixed in one frame)."""
        return (LITTLE if self.order == BIG else BIG) if self.p(0.25) else self.order

    def orient(self, s: dict[str, Any], order: str) -> None:
        """Write the field's `byte_order` where it differs from the bus default (now and then where it does not)."""
        if order != self.order or self.p(0.05):
            s["byte_order"] = order

    # --- shared layouts


# --- entry points --------------------------------------------------------------------------
