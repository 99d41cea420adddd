"""Property tests (hypothesis): random in-range physical values survive encode → decode within
the factor's precision and agree with cantools on the generated DBC; decode of arbitrary IDs
and bytes raises nothing but the documented errors (issue 9)."""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import pytest
from canspec.pipeline import compile_spec
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from repo_paths import SPEC as SPEC_DIR

CAN = compile_spec(SPEC_DIR).spec.can  # type: ignore[union-attr]
MESSAGES = [m for m in CAN.messages if any(s.role != "checksum" for s in m.data_signals)]
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


def physical_strategy(sig):
    """Physical values a physical encode must accept: the documented range ∩ what the bits carry, plus specials."""
    lo, hi = sig.phys_min, sig.phys_max
    if sig.is_integer:
        values = st.integers(math.ceil(max(lo, sig.check_min)), math.floor(min(hi, sig.check_max)))
        if sig.factor != 1:  # only multiples of the factor are exact
            values = st.integers(sig.raw_min, sig.raw_max).map(lambda r: int(r * sig.factor + sig.offset))
    else:
        values = st.floats(float(max(lo, sig.check_min)), float(min(hi, sig.check_max)), allow_nan=False)
    specials = [s.physical for s in sig.specials]
    if specials:
        values = st.one_of(values, st.sampled_from([int(p) if sig.is_integer else float(p) for p in specials]))
    return values


def message_strategy(msg):
    return st.fixed_dictionaries({s.name: physical_strategy(s) for s in msg.data_signals if s.role != "checksum"})


def attrs(cls):
    return dict(zip(cls.SIGNALS, (f.name for f in dataclasses.fields(cls))))


@pytest.mark.parametrize("msg", MESSAGES, ids=lambda m: m.name)
def test_physical_values_survive_and_agree_with_cantools(gw, db, msg):
    cls = gw.BY_ID[msg.frame_id]
    names = attrs(cls)
    cmsg = db.get_message_by_frame_id(msg.frame_id)

    @SETTINGS
    @given(message_strategy(msg))
    def check(values):
        data = gw.encode(cls(**{names[k]: v for k, v in values.items()}))
        back = gw.decode(msg.frame_id, data)
        theirs = cmsg.decode(data, decode_choices=False)
        for sig in msg.data_signals:
            if sig.role == "checksum":
                assert getattr(back, names[sig.name]) == data[msg.checksum.byte]
                continue
            got = getattr(back, names[sig.name])
            # precision: within half a raw step (plus double rounding noise)
            assert abs(got - values[sig.name]) <= float(sig.factor) / 2 * (1 + 1e-9) + 1e-9, (sig.name, values[sig.name], got)
            # the oracle reads the same bytes to the same value
            assert math.isclose(got, theirs[sig.name], rel_tol=1e-12, abs_tol=1e-9), (sig.name, got, theirs[sig.name])
        # and cantools encodes our decoded raw values to the same bytes
        assert cmsg.encode(gw.decode_raw(msg.frame_id, data), scaling=False, strict=False) == data

    check()


@SETTINGS
@given(frame_id=st.one_of(st.sampled_from([m.frame_id for m in CAN.messages]), st.integers(0, 0x1FFFFFFF), st.integers(-(2**40), 2**40)),
       data=st.binary(min_size=0, max_size=72), verify=st.booleans())
def test_decode_of_anything_raises_only_documented_errors(gw, frame_id, data, verify):
    try:
        message = gw.decode(frame_id, data, verify_checksum=verify)
    except (gw.UnknownFrameError, gw.FrameLengthError, gw.ChecksumError):
        return
    # whatever decodes re-encodes at raw level to the same bits in every data signal (reserved
    # bits, the checksum byte and the bits of a message whose layout is undefined aside)
    again = gw.encode_raw(frame_id, gw.decode_raw(frame_id, data, verify_checksum=False))
    msg = CAN.by_id(frame_id)
    checksum_bits = 0xFF << (8 * msg.checksum.byte) if msg.checksum else 0
    carried = 0
    for s in msg.data_signals:
        carried |= s.word_mask
    carried &= ~checksum_bits
    as_int = int.from_bytes(data, "little")
    assert int.from_bytes(again, "little") & carried == as_int & carried
    assert type(message).FRAME_ID == frame_id


@SETTINGS
@given(data=st.binary(min_size=8, max_size=8))
def test_checksum_check_never_raises_and_matches_decode(gw, data):
    for msg in CAN.messages:
        ok = gw.checksum_ok(msg.frame_id, data)
        if msg.checksum is None:
            assert ok
        else:
            x = 0
            for b in msg.checksum.covers:
                x ^= data[b]
            assert ok == (x == data[msg.checksum.byte])


def test_exact_rule_at_every_tie(gw):
    """The generated double-precision rounding equals the exact (Fraction) rule on every decimal tie of every signal."""
    from canspec.ir.encoding import to_raw_exact

    checked = 0
    for msg in MESSAGES:
        cls = gw.BY_ID[msg.frame_id]
        names = attrs(cls)
        for sig in msg.data_signals:
            if sig.is_identity or sig.role in ("checksum", "counter") or sig.raw_max - sig.raw_min > 50000:
                continue
            for lower in range(sig.raw_min, sig.raw_max):
                tie = Fraction(2 * lower + 1, 2) * sig.factor + sig.offset
                if not sig.check_min <= tie <= sig.check_max:
                    continue
                value = float(tie) if not sig.is_integer or tie.denominator != 1 else int(tie)
                expected = to_raw_exact(Fraction(repr(float(tie))) if isinstance(value, float) else tie, sig.factor, sig.offset)
                if not sig.raw_min <= expected <= sig.raw_max:
                    continue
                m = cls(**{names[sig.name]: value})
                assert m.to_raw()[sig.name] == expected, (msg.name, sig.name, value)
                checked += 1
    assert checked > 10000
