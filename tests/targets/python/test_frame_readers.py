"""How the generated Python reads a frame: all bytes unpacked as a tuple, a few of them indexed after a length check,
or a struct that reads bytes and whole 16-bit words (a field spanning exactly two bytes). Each layout of
tests/fixtures/valid/py_frame_readers.yaml takes the reader it is there for, and every one decodes random frames
(raw and physical) as cantools does reading the generated DBC, and refuses every wrong length."""

from __future__ import annotations

import math
import random
import re

import cantools
import pytest
from canspec.generation import generate
from canspec.pipeline import compile_spec
from repo_paths import ROOT

from targets.python.vector_runner import attr_names, load_package

FIXTURE = ROOT / "tests" / "fixtures" / "valid" / "py_frame_readers.yaml"
# message → what its decode unpacks: the 16-bit words `hN` it reads, or the indexed bytes `data[N]`
READERS = {
    "be_pairs": "h0, h2, d4, d5, h6 = _BE_PAIRS_BYTES.unpack(data)",  # the Intel pair is the minority order: two bytes
    "overlapping": "d0, d1, d2, d3, d4, _ = data",  # no byte pair is a field's alone
    "sparse": "d2 = data[2]",
    "fd_pair": "d3, h4, d15 = _FD_PAIR_BYTES.unpack(data)",
    "fd_sparse": "d20 = data[20]",
    "paged": "d0, h1, h4, d6, d7 = _PAGED_BYTES.unpack(data)",  # both pages read the word h1
    "whole_checksum": "d0, d1, d2, d3, d4, d5, d6, d7 = data",  # the XOR of every byte needs each one
}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    root = tmp_path_factory.mktemp("frame-readers")
    for files in generate(compile_spec(FIXTURE).spec, ["python", "dbc"]).values():
        for rel, data in files.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_bytes(data)
    return load_package(root / "python" / "frame_readers"), cantools.database.load_file(str(root / "dbc" / "frame_readers.dbc"))


def _decode_source(pkg, name: str) -> str:
    text = (ROOT / pkg.__file__).parent.joinpath("messages.py").read_text(encoding="utf-8")
    match = re.search(rf"^def _decode_{name}\(.*?(?=^def )", text, re.MULTILINE | re.DOTALL)
    assert match, name
    return match.group(0)


@pytest.mark.parametrize("name", sorted(READERS))
def test_each_layout_takes_its_reader(built, name):
    assert READERS[name] in _decode_source(built[0], name)


@pytest.mark.parametrize("name", sorted(READERS))
def test_random_frames_decode_as_cantools(built, name):
    pkg, db = built
    msg = db.get_message_by_name(name)
    cls = pkg.BY_ID[msg.frame_id]
    attrs = attr_names(cls)
    rng = random.Random(name)
    paged = {s.name for s in msg.signals if s.multiplexer_ids}
    for _ in range(2000):
        data = bytes(rng.getrandbits(8) if i or not paged else rng.choice((0, 1, 2)) for i in range(msg.length))
        try:
            want_raw = db.decode_message(msg.frame_id, data, decode_choices=False, scaling=False)
        except cantools.database.DecodeError:  # a multiplexer value of no page: cantools refuses, the package has no page
            assert paged and not set(pkg.decode_raw(msg.frame_id, data)) & paged, data.hex()
            continue
        assert pkg.decode_raw(msg.frame_id, data, verify_checksum=False) == want_raw, data.hex()
        got = pkg.decode(msg.frame_id, data, verify_checksum=False)
        for signal, want in db.decode_message(msg.frame_id, data, decode_choices=False).items():
            assert math.isclose(getattr(got, attrs[signal]), want, rel_tol=1e-12, abs_tol=1e-12), (signal, data.hex())
        absent = set(attrs) - set(want_raw)  # another page's fields
        assert all(getattr(got, attrs[s]) is None for s in absent), data.hex()


@pytest.mark.parametrize("name", sorted(READERS))
def test_every_wrong_length_is_refused(built, name):
    pkg, db = built
    msg = db.get_message_by_name(name)
    for n in [*range(msg.length), msg.length + 1, 64]:
        for call in (pkg.decode, pkg.decode_raw):
            with pytest.raises(pkg.FrameLengthError):
                call(msg.frame_id, bytes(n))
