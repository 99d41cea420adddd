"""The fields of a drawn message (strategy.py): data fields with their scaling, ranges, value tables and
special values, IEEE floats, counters, checksums, reserved bits and multi-frame text, laid out in the
bits a frame has free. A mixin of strategy.Builder, which supplies the chooser (`p`, `pick`, `ch`, ...)."""

from __future__ import annotations

from decimal import Decimal
from typing import Any

from anyspec.pools import (
    BIG,
    DEC_FACTORS,
    DEC_OFFSETS,
    FLOAT_RANGES,
    INT_FACTORS,
    INT_OFFSETS,
    KEYWORDS,
    LENGTHS,
    LITTLE,
    SIG_WORDS,
    SPECIAL_IDENTS,
    TABLE_WORDS,
    UNITS,
    VALUE_IDENTS,
    _Names,
    frame_bits,
    occupied_all,
    raw_range,
    seq_bit,
)
from anyspec.yamltext import Hex


class FieldDraws:
    def signals(self, dlc: int, occupied: set[int] | None = None, names: _Names | None = None, counter: bool = True, checksum: bool = True,
                first_needed: bool = True) -> list[dict[str, Any]]:
        bits = 8 * dlc
        occ = set(occupied or ())
        names = names or _Names()
        out: list[dict[str, Any]] = []
        if checksum and dlc >= 2 and not set(range(bits - 8, bits)) & occ and self.p(0.25):
            out.append(self.checksum(dlc, names))
            occ |= set(range(bits - 8, bits))
        want_counter = counter and self.p(0.3)
        last = 0  # the previous field's length: rows of one width (wheel speeds, cell voltages), signed and unsigned mixed
        while (not out and first_needed) or self.p(0.8):
            order = self.field_order()
            # the field's first place (Intel: its LSB, Motorola: its MSB) and the free run from there, in its order's run of bits
            first = next((k for k in range(bits) if seq_bit(k, order) not in occ), None)
            if first is None:
                break
            run = 0
            while first + run < bits and seq_bit(first + run, order) not in occ:
                run += 1
            start = seq_bit(first, order)
            if self.p(0.2):  # a gap: free, or a reserved field
                gap = min(run, self.pick((1, 2, 3, 4, 8, 5, 7, 16)))
                if self.p(0.5):
                    out.append(self.reserved(start, gap, order))
                occ |= frame_bits(start, gap, order)
                continue
            if run >= 32 and self.p(0.2):  # an IEEE float
                length = 64 if run >= 64 and self.p(0.4) else 32
                out.append(self.float_field(start, length, names, order))
            else:
                length = min(run, last if last and self.p(0.3) else self.pick(LENGTHS))
                last = length
                if want_counter and length <= 8 and self.p(0.5):
                    want_counter = False
                    out.append(self.counter(start, length, names, order))
                else:
                    out.append(self.data(start, length, names, order=order))
            occ |= frame_bits(start, length, order)
        if first_needed and not out:  # every bit went to a free gap: one field after all
            start = min(b for b in range(bits) if b not in occupied_all(occupied))
            out.append(self.data(start, min(8, bits - start), names, order=LITTLE))
        return out

    def reserved(self, start: int, length: int, order: str) -> dict[str, Any]:
        s: dict[str, Any] = {"role": "reserved", "start": start, "len": length}
        self.orient(s, order)
        if self.p(0.2):
            s["desc_zh"] = "保留"
        return s

    def checksum(self, dlc: int, names: _Names) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take("checksum" if self.p(0.8) else self.pick(("xor", "crc_byte", "check")))}
        self.sig_zh(s, "校验")
        order = self.field_order()
        s.update({"start": 8 * (dlc - 1) + (7 if order == BIG else 0), "len": 8})  # the last byte: its MSB is bit 7 in Motorola order
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [0, 255]
        s["role"] = "checksum"
        return s

    def counter(self, start: int, length: int, names: _Names, order: str) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take("counter" if self.p(0.7) else self.pick(("alive", "rolling_counter", "heartbeat")))}
        self.sig_zh(s, "心跳")
        s.update({"start": start, "len": length})
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [0, (1 << length) - 1]
        s["role"] = "counter"
        return s

    def sig_zh(self, s: dict[str, Any], default: str | None = None) -> None:
        if not self.feature("optional_signal_zh", 0.3):
            s["zh"] = default if default and self.p(0.5) else self.zh()

    def scaling(self, length: int, signed: bool) -> dict[str, Any]:
        """factor / offset / range for a data field (range: None or reachable, within the field)."""
        out: dict[str, Any] = {}
        kind = self.pick(("identity", "integer", "decimal"))
        if kind == "integer":
            factor, offset = Decimal(self.pick(INT_FACTORS)), Decimal(self.pick(INT_OFFSETS))
        elif kind == "decimal":
            factor, offset = Decimal(self.pick(DEC_FACTORS)), Decimal(self.pick(DEC_OFFSETS))
        else:
            factor, offset = Decimal(1), Decimal(0)
        if factor != 1 or self.p(0.1):
            out["factor"] = factor
        if offset != 0 or self.p(0.1):
            out["offset"] = offset
        tmin, tmax = raw_range(length, signed)
        if self.p(0.6):
            lo_raw, hi_raw = tmin, tmax
            span = tmax - tmin
            if span >= 2 and self.p(0.5):
                lo_raw = tmin + self.ch.integer(0, min(span // 2, 1000))
                hi_raw = tmax - self.ch.integer(0, min(span // 2, 1000))
            a, b = sorted((lo_raw * factor + offset, hi_raw * factor + offset))
            if hi_raw - lo_raw >= 2 and self.p(0.1):  # bounds between two steps
                a, b = a + abs(factor) / 2, b - abs(factor) / 4
            out["range"] = [a, b]
            out["_raw"] = (lo_raw, hi_raw) if factor > 0 else (lo_raw, hi_raw)
        return out

    def data(self, start: int, length: int, names: _Names, name: str | None = None, order: str = LITTLE) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take(name) if name else self.ident(SIG_WORDS, names, 0.1)}
        self.sig_zh(s)
        s.update({"start": start, "len": length})
        self.orient(s, order)
        signed = self.p(0.25)
        if signed:
            s["signed"] = True
        elif self.p(0.05):
            s["signed"] = False
        tmin, tmax = raw_range(length, signed)
        with_values = length <= 16 and self.p(0.25)
        sc = self.scaling(length, signed) if not with_values else {}
        if with_values:  # a value table on an identity field, its raws inside the range
            lo, hi = tmin, tmax
            if self.p(0.5):
                hi = min(tmax, max(lo, self.ch.integer(lo, min(tmax, lo + 15))))
                s["range"] = [lo, hi]
            s["values"] = self.table_for(lo, hi)
        raw_lo, raw_hi = sc.pop("_raw", (tmin, tmax))
        s.update(sc)
        if self.p(0.4):
            s["unit"] = self.pick(UNITS)
        if self.p(0.15):
            self.specials(s, tmin, tmax, raw_lo, raw_hi)
        if self.p(0.1):
            s["desc"] = self.text()
        if self.p(0.1):
            s["desc_zh"] = self.zh()
        return s

    def float_field(self, start: int, length: int, names: _Names, order: str) -> dict[str, Any]:
        """An IEEE 754 float32/float64 field: no scaling, sign flag or tables; a range or none (NaN, ±Inf pass)."""
        s: dict[str, Any] = {"name": self.ident(SIG_WORDS, names, 0.1)}
        self.sig_zh(s)
        s.update({"start": start, "len": length, "float": True})
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [Decimal(v) for v in self.pick(FLOAT_RANGES)]
        if self.p(0.4):
            s["unit"] = self.pick(UNITS)
        return s

    def specials(self, s: dict[str, Any], tmin: int, tmax: int, raw_lo: int, raw_hi: int) -> None:
        taken = set(self.tables[s["values"]]) if "values" in s else set()
        idents = _Names([ident for ident, _ in self.tables[s["values"]].values()] if "values" in s else ())
        candidates = [tmax, tmin, 0, raw_hi + 1 if raw_hi < tmax else tmax, raw_lo - 1 if raw_lo > tmin else tmin]
        special: dict[Any, Any] = {}
        for _ in range(1 + (1 if self.p(0.3) else 0)):
            raw = self.pick(candidates)
            if raw in taken or raw in special:
                continue
            ident = self.pick(SPECIAL_IDENTS) if not self.p(0.1) else self.pick(KEYWORDS)
            if not idents.free(ident):
                continue
            idents.take(ident)
            special[Hex(raw) if raw >= 0 and self.p(0.5) else raw] = [ident, self.zh()]
        if special:
            s["special"] = special

    # --- value tables
    def new_table(self, lo: int, hi: int) -> str:
        name = self.table_names.take(self.pick(TABLE_WORDS) if not self.p(0.08) else self.pick(KEYWORDS))
        k = 1 + self.ch.integer(0, min(4, hi - lo))
        base = 0 if lo <= 0 <= hi - k else lo
        raws: list[int] = []
        for i in range(k):
            r = base + i if self.p(0.7) else self.ch.integer(lo, hi)
            if r not in raws:
                raws.append(r)
        idents = _Names()
        entries: dict[int, tuple[str, str | None]] = {}
        for r in sorted(raws):
            ident = self.ident(VALUE_IDENTS, idents, 0.1)
            zh = None if self.feature("bare_value_ident", 0.3) else self.zh()
            entries[r] = (ident, zh)
        self.tables[name] = entries
        return name

    def table_for(self, lo: int, hi: int) -> str:
        fitting = [t for t, e in self.tables.items() if all(lo <= r <= hi for r in e)]
        if fitting and self.p(0.5):
            return self.pick(fitting)
        return self.new_table(lo, hi)

    # --- multiframe text
    def multiframe_signals(self, dlc: int) -> tuple[list[dict[str, Any]], dict[str, Any]]:
        names = _Names()
        index_len = self.pick((2, 8, 1, 3, 4))
        index: dict[str, Any] = {"name": names.take(self.pick(("frame_index", "index", "seq")))}
        self.sig_zh(index, "序号")
        index.update({"start": 0, "len": index_len})
        self.orient(index, LITTLE)  # whole bytes from bit 0 of a byte: Intel fields
        if self.p(0.5):
            index["range"] = [0, (1 << index_len) - 1]
        first_byte = (index_len + 7) // 8
        if first_byte >= dlc:
            first_byte = dlc - 1
        max_bytes = dlc - first_byte
        nbytes = 1 + self.ch.integer(0, max_bytes - 1)
        payload: dict[str, Any] = {"name": names.take(self.pick(("text_chars", "chars", "payload")))}
        self.sig_zh(payload, "字符")
        payload.update({"start": 8 * first_byte, "len": 8 * nbytes})
        self.orient(payload, LITTLE)
        frames = 1 + self.ch.integer(0, min((1 << index_len), 8) - 1)
        text_length = 1 + self.ch.integer(0, frames * nbytes - 1)
        mf = {"index": index["name"], "payload": payload["name"], "encoding": "ascii", "text_length": text_length, "frames": frames,
              "padding": Hex(self.pick((0x00, 0x20, 0xFF, 0x2A)))}
        occ = set(range(index_len)) | set(range(8 * first_byte, 8 * (first_byte + nbytes)))
        rest = self.signals(dlc, occ, names, counter=True, checksum=True, first_needed=False) if self.p(0.5) else []
        return [index, payload, *rest], mf
