"""The C target's corner messages (corners/c_corners.yaml) against the independent oracle: cantools,
reading the corners' DBC, agrees with every vector case the C vector runner checks on both pack and
unpack paths (test_c_any_spec.py), so those expected bytes and values are not the generator's own
word. And the corners still take the strategy 3 forms they exist for: a CAN FD frame's unpack in
8-byte windows (a field over 9 bytes from its bytes, a window widened to the frame's end), its pack
in windows of 2, 4 and 8 bytes that carry fields in every byte (of one byte order, Motorola and
Intel), a frame word pack that zeroes the frame first, unpack words shifted to their least
significant byte, a classic frame's byte form unpack reading each field's bytes from src."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "dbc"))
from dbc_support import check_oracle, compiled, load_cantools, vectors, write_dbc  # noqa: E402

from canspec.targets import registry  # noqa: E402

SPEC = HERE / "corners" / "c_corners.yaml"


@pytest.fixture(scope="module")
def spec():
    return compiled(SPEC)


@pytest.fixture(scope="module")
def wide(spec) -> dict[str, str]:
    """`<message>_<pack|unpack>` -> the body of its <PREFIX>_STRATEGY >= 3 branch."""
    text = registry()["c"].render(spec)["c/c_corners_messages.h"]
    text = text.decode() if isinstance(text, bytes) else text
    out = {}
    for m in re.finditer(r"c_corners_(\w+?)_(pack|unpack)\([^)]*\) \{\n#if C_CORNERS_STRATEGY >= 3[^\n]*\n(.*?)\n#(?:elif|else|endif)", text, re.S):
        out[f"{m.group(1)}_{m.group(2)}"] = m.group(3)
    return out


def test_every_corner_case_agrees_with_cantools(spec, tmp_path):
    doc = vectors(spec)
    names = {c["message"] for c in doc["cases"]}
    assert {"fd_windows", "word_zeroed", "motorola_tail", "motorola_inner", "checksum_only", "fd_pack_windows", "fd_pack_sparse", "byte_fields"} <= names
    assert check_oracle(load_cantools(write_dbc(spec, tmp_path)), doc) == len(doc["cases"])


def test_fd_frame_unpacks_in_windows(wide):
    body = wide["fd_windows_unpack"]
    assert re.search(r"^\s*w = .*src\[1\]\) << 24u\) .*\(uint64_t\)src\[4\];", body, re.M | re.S)  # bytes 1-4 from bit 0
    for k, lo, hi in ((1, 8, 15), (2, 32, 39), (3, 41, 48), (4, 56, 63)):  # the last widened back from byte 61 to the frame's end
        assert re.search(rf"w{k} = \(\(\(uint64_t\)src\[{lo}\]\) << 56u\).*\(uint64_t\)src\[{hi}\];", body, re.S), k
    assert "w5" not in body and "b22 = src[22];" in body and "b30 = src[30];" in body  # 64 bits over 9 bytes: from its bytes
    assert "b46 = src[46];" in body  # the Intel field among Motorola ones


def test_word_pack_zeroes_first_and_unpack_words_start_at_bit_0(wide):
    assert "(void)memset(dst, 0, 5u);" in wide["word_zeroed_pack"] and "= 0u;" not in wide["word_zeroed_pack"]
    assert re.search(r"w = \(\(\(uint64_t\)src\[6\]\) << 8u\) \| \(uint64_t\)src\[7\];", wide["motorola_tail_unpack"])
    assert re.search(r"w = \(\(\(uint64_t\)src\[2\]\) << 8u\) \| \(uint64_t\)src\[3\];", wide["motorola_inner_unpack"])


def test_fd_frame_packs_in_windows(wide):
    body = wide["fd_pack_windows_pack"]
    assert "memset" not in body and "dst[14] = 0u;" in body and "dst[31] = 0u;" in body  # most bytes carry a field
    # Motorola, 4 bytes (two fields sharing byte 1), one signed, masked
    assert re.search(r"w = \(\(uint64_t\)src->pw_a << 20u\) \| \(\(uint64_t\)src->pw_b & UINT64_C\(0xFFFFF\)\);", body)
    assert "dst[0] = (uint8_t)(w >> 24u);" in body and "dst[3] = (uint8_t)w;" in body
    # Intel, 8 bytes, a signed 34-bit field masked to its bits
    assert re.search(r"w1 = \(uint64_t\)src->pw_i \| \(\(\(uint64_t\)src->pw_j & UINT64_C\(0x3FFFFFFFF\)\) << 30u\);", body)
    assert "dst[4] = (uint8_t)w1;" in body and "dst[11] = (uint8_t)(w1 >> 56u);" in body
    # bytes 12-15: byte 14 carries no field, so a 2-byte window (12-13) and byte 15 from its field
    assert "dst[12] = (uint8_t)(w2 >> 8u);" in body and "dst[13] = (uint8_t)w2;" in body
    assert "dst[15] = (uint8_t)src->pw_x;" in body and "w3" not in body
    # bytes 16-17 hold fields of both orders: bytes
    assert "dst[16] = (uint8_t)(src->pw_n | ((uint32_t)src->pw_m << 4u));" in body and "dst[17] = (uint8_t)src->pw_o;" in body
    sparse = wide["fd_pack_sparse_pack"]
    assert "(void)memset(dst, 0, 48u);" in sparse and "= 0u;" not in sparse and "dst[40] = (uint8_t)src->ps_c;" in sparse
    assert re.search(r"w = \(\(uint64_t\)src->ps_a & UINT64_C\(0x7FF\)\) \| \(\(uint64_t\)src->ps_b << 11u\);", sparse)
    assert "dst[20] = (uint8_t)w;" in sparse and "dst[23] = (uint8_t)(w >> 24u);" in sparse


def test_byte_form_unpack_reads_src_per_field(wide):
    body = wide["byte_fields_unpack"]  # strategy 3 has its own form: without it, the function has no #if
    assert "b0" not in body and "uint32_t b" not in body
    assert "dst->bf_b = (uint8_t)(((uint32_t)src[0] >> 1u) & 0x3u);" in body and "dst->bf_d = (uint8_t)((uint32_t)src[0] >> 7u);" in body
    assert "dst->bf_e = (uint8_t)src[1];" in body and "dst->bf_f = (uint8_t)src[7];" in body
