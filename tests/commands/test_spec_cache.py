"""The compiled-spec cache of the read-only commands (canspec/spec_cache.py): a second decode
loads the compiled spec instead of compiling it; an edited spec file, a corrupt or unwritable
cache and CANSPEC_NO_CACHE all fall back to compiling; results are the same either way."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from functools import reduce
from operator import xor

import pytest
from canspec import spec_cache
from canspec.pipeline import compile_spec
from repo_paths import CANSPEC_ENV, SPEC

PAYLOAD = [0, 0, 10, 0x2A, 0x2A, 0, 0]  # autocar_eps_command: max_angular_speed raw 10
FRAME = f"(1.000000) can0 1801B0A0#{bytes([*PAYLOAD, reduce(xor, PAYLOAD)]).hex().upper()}\n"


def decode(cache, *args, no_cache=False):
    env = {**CANSPEC_ENV, "CANSPEC_CACHE_DIR": str(cache)}
    if no_cache:
        env["CANSPEC_NO_CACHE"] = "1"
    proc = subprocess.run([sys.executable, "-m", "canspec", "decode", "--format", "json", *args, "-"], input=FRAME, capture_output=True,
                          text=True, env=env, timeout=120, check=False)
    assert proc.returncode == 0, proc.stderr
    return proc


def compiled_in(*args, cache) -> bool:
    """Whether `canspec decode` compiled the spec (imported the loader) rather than loading it."""
    env = {**CANSPEC_ENV, "CANSPEC_CACHE_DIR": str(cache)}
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "canspec", "decode", *args, "-"], input=FRAME, capture_output=True, text=True,
                          env=env, timeout=120, check=False)
    assert proc.returncode == 0, proc.stderr
    return "canspec.spec.loader" in proc.stderr


def signal(proc, name="max_angular_speed"):
    return json.loads(proc.stdout)["signals"][name]


def entries(cache):
    return sorted(cache.glob("*.pickle"))


def test_second_decode_loads_the_cached_spec(tmp_path):
    cache = tmp_path / "cache"
    assert compiled_in(cache=cache)
    assert len(entries(cache)) == 1
    assert not compiled_in(cache=cache)


def test_an_edited_spec_file_is_compiled_again(tmp_path):
    spec, cache = tmp_path / "spec", tmp_path / "cache"
    shutil.copytree(SPEC, spec)
    assert signal(decode(cache, "--spec", str(spec))) == 20
    assert signal(decode(cache, "--spec", str(spec))) == 20  # from the cache
    gateway = spec / "can" / "gateway.yaml"
    gateway.write_text(gateway.read_text(encoding="utf-8").replace("start: 16, len: 8, factor: 2,", "start: 16, len: 8, factor: 4,"), encoding="utf-8")
    assert signal(decode(cache, "--spec", str(spec))) == 40
    (spec / "ERRATA.md").unlink()  # a file the compile read, now absent
    assert compiled_in("--spec", str(spec), cache=cache)


def test_corrupt_or_unwritable_cache_is_ignored(tmp_path):
    cache = tmp_path / "cache"
    expected = decode(cache).stdout
    for entry in entries(cache):
        entry.write_bytes(b"not a pickle")
    assert decode(cache).stdout == expected
    assert not compiled_in(cache=cache)  # the corrupt entry was replaced
    blocked = tmp_path / "file"
    blocked.write_text("a file where the cache directory would be")
    assert decode(blocked).stdout == expected


def test_no_cache_writes_nothing_and_decodes_the_same(tmp_path):
    cache = tmp_path / "cache"
    uncached = decode(cache, no_cache=True)
    assert not cache.exists()
    decode(cache)
    cached = decode(cache)
    assert cached.stdout == uncached.stdout
    assert untimed(cached.stderr) == untimed(uncached.stderr)


def untimed(stderr):
    return re.sub(r"; [0-9.]+ s$", "", stderr, flags=re.MULTILINE)


def test_cached_compile_equals_a_fresh_one(tmp_path, monkeypatch):
    """Spec and problems (warnings included) come back as compiled; an edit of the generator's
    source names another entry."""
    monkeypatch.setenv("CANSPEC_CACHE_DIR", str(tmp_path))
    fresh = compile_spec(SPEC, [])
    first, second = spec_cache.compile_cached(SPEC, []), spec_cache.compile_cached(SPEC, [])
    assert len(entries(tmp_path)) == 1
    assert first.spec == second.spec == fresh.spec
    assert first.problems == second.problems == fresh.problems and fresh.warnings
    name = spec_cache._entry_name(SPEC, [])
    monkeypatch.setattr(spec_cache, "_source_hash", lambda: "edited")
    assert spec_cache._entry_name(SPEC, []) != name


@pytest.mark.parametrize("value", ["1", "yes"])
def test_no_cache_variable(monkeypatch, value):
    monkeypatch.setenv("CANSPEC_NO_CACHE", value)
    assert spec_cache.cache_dir() is None


CLASHING_DBC = ('VERSION ""\n\nNS_ :\n\nBS_:\n\nBU_: GW\n\nBO_ 256 ParkAid_Data2: 8 GW\n SG_ A : 0|8@1+ (1,0) [0|255] "" GW\n\n'
                'BO_ 257 ParkAid_Data_2: 8 GW\n SG_ B : 0|8@1+ (1,0) [0|255] "" GW\n')


def canspec_run(cache, *args, importtime=False):
    env = {**CANSPEC_ENV, "CANSPEC_CACHE_DIR": str(cache)}
    proc = subprocess.run([sys.executable, *(["-X", "importtime"] if importtime else []), "-m", "canspec", *map(str, args)], capture_output=True,
                          text=True, env=env, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    return proc


def test_gen_after_import_loads_the_spec_import_compiled(tmp_path):
    """`canspec import` compiles the spec it writes through the cache (its last clash-resolution
    round: here after renaming one of two messages whose Rust names meet), so the `canspec gen` of
    every target that follows loads it instead of compiling it again (the largest opendbc DBC's
    compile is 1.3 s of its gen); the same gen after an edit of the written spec compiles."""
    dbc, spec, cache = tmp_path / "bus.dbc", tmp_path / "spec", tmp_path / "cache"
    dbc.write_text(CLASHING_DBC, encoding="utf-8")
    assert "spec name parkaid_data_2_2" in canspec_run(cache, "import", dbc, "-o", spec).stderr
    gen = canspec_run(cache, "gen", "-q", spec, "-o", tmp_path / "out", importtime=True)
    assert "canspec.spec.loader" not in gen.stderr and (tmp_path / "out" / "dbc" / "bus.dbc").is_file()
    written = spec / "bus.yaml"
    written.write_text(written.read_text(encoding="utf-8") + "\n", encoding="utf-8")
    assert "canspec.spec.loader" in canspec_run(cache, "gen", "-q", spec, "-o", tmp_path / "out", importtime=True).stderr
