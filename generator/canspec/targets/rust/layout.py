"""Whether a classic message is held as the u64 frame word or as its 8 bytes.

A getter on the word copies it, shifts and masks (x86-64: mov, shr, and); one on the bytes
loads its byte (movzbl, which is the copy) and shifts or masks only where the field leaves bits
of the byte on that side, and a whole byte is the load alone. So the bytes win on fields that
end at byte edges and on whole bytes (one movzbl or movzwl), the word on 1-bit flags (a bit test)
and on other fields over several bytes (one load, no reassembly). The estimate counts instructions per field read; ties keep the word.

Flags held as bytes: a few cost a shift and a mask each, but a message of FLAG_RUN or more has LLVM's
SLP vectorizer read them from the loaded bytes together, about one instruction a flag, like the
word's bit test. Counted at 2 each regardless, vehicle_fault (21 flags) and vehicle_state_1 (12)
stayed on the word: decode 91.1 and 81.2 Ir where their bytes take 83.2 and 73.2 (encode 309 -> 295,
283 -> 278); the *_control_command_2 tie (2 flags) reads 30.2 Ir as the word, 31.2 as bytes.
"""

from __future__ import annotations

from canspec import ir
from canspec.targets.rust.bits import CLASSIC_BYTES, WORD_BITS
from canspec.targets.rust.naming import stored_signals

FLAG_RUN = 8  # flags from which the byte layout reads them at about one instruction each (module doc)


def _one_byte(sig: ir.Signal) -> bool:
    return len({s.byte for s in sig.segments}) == 1


def _whole_bytes(sig: ir.Signal) -> bool:
    """An Intel field of 2 or 4 whole bytes: read from the bytes as one integer, a single load."""
    return not sig.is_big_endian and sig.length in (16, 32) and sig.segments[0].byte_shift == 0


def _word_cost(sig: ir.Signal) -> int:
    if sig.length == 1:
        return 1  # bt
    shift = 8 * sig.segments[0].byte + sig.segments[0].byte_shift
    return 3 - (shift == 0) - (shift + sig.length == WORD_BITS)


def _byte_cost(sig: ir.Signal, flags: int) -> int:
    shift = sig.segments[0].byte_shift
    if sig.length % 8 == 0:  # whole bytes: the load alone
        return 0
    if sig.length == 1:  # `flags`: the message's 1-bit fields
        return 1 if flags >= FLAG_RUN else 2  # vectorized together, or a shift and a mask each
    return 3 - 2 * (shift + sig.length == 8) - (shift == 0)


def holds_bytes(msg: ir.Message) -> bool:
    """Held as its bytes: an FD frame, or a classic 8-byte one whose fields each lie in one byte or
    are 2 or 4 whole Intel bytes, and read for fewer instructions from the bytes (not multiplexed,
    no checksum: both read the word)."""
    if not msg.is_classic_length:
        return True
    sigs = stored_signals(msg)
    if msg.dlc != CLASSIC_BYTES or msg.is_multiplexed or msg.checksum is not None or not sigs:
        return False
    if not all(_one_byte(s) or _whole_bytes(s) for s in sigs):
        return False
    loads = len({(s.segments[0].byte, s.length if _whole_bytes(s) else 8) for s in sigs})
    flags = sum(1 for s in sigs if s.length == 1)
    return loads + sum(_byte_cost(s, flags) for s in sigs) < sum(_word_cost(s) for s in sigs)
