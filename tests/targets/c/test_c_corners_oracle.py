"""The C target's corner messages (corners/c_corners.yaml) against the independent oracle: cantools,
reading the corners' DBC, agrees with every vector case the C vector runner checks on both pack and
unpack paths (test_c_any_spec.py), so those expected bytes and values are not the generator's own
word. And the corners still take the strategy 3 forms they exist for: a CAN FD frame's unpack in
8-byte windows (a field over 9 bytes from its bytes, a window widened to the frame's end), a frame
word pack that zeroes the frame first, unpack words shifted to their least significant byte."""

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
    for m in re.finditer(r"c_corners_(\w+?)_(pack|unpack)\([^)]*\) \{\n#if C_CORNERS_STRATEGY >= 3[^\n]*\n(.*?)\n#(?:else|endif)", text, re.S):
        out[f"{m.group(1)}_{m.group(2)}"] = m.group(3)
    return out


def test_every_corner_case_agrees_with_cantools(spec, tmp_path):
    doc = vectors(spec)
    names = {c["message"] for c in doc["cases"]}
    assert {"fd_windows", "word_zeroed", "motorola_tail", "motorola_inner", "checksum_only"} <= names
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
